"""``at_pose``: objects at explicit target poses (world or an anchor's frame)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Annotated, Any, ClassVar, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field
from scipy.optimize import linear_sum_assignment

from factask.geometry import Pose
from factask.relations.base import RelationBase
from factask.relations.solving import (
    Infeasible,
    Plan,
    SolveContext,
    SolvedFactor,
    make_plan,
)
from factask.relations.status import CheckScene, Verdict, check_slots
from factask.scene.collision import TABLE
from factask.scene.objects import (
    SceneObject,
    placement_area,
    rest_surface_z,
    resting_pose,
    yaw_rotation_2d,
)
from factask.vocabulary.errors import Problem
from factask.vocabulary.names import Name
from factask.vocabulary.world import TABLE_Z, WORKSPACE_X, WORKSPACE_Y, WORKSPACE_Z

if TYPE_CHECKING:
    from factask.vocabulary.variables import StateVariable

#: Target coordinates are bounded (metres): far beyond any table, never overflowing.
COORDINATE_LIMIT = 10.0
Coordinate = Annotated[float, Field(ge=-COORDINATE_LIMIT, le=COORDINATE_LIMIT,
                                    allow_inf_nan=False)]
#: Yaw in degrees (any finite turn up to two full turns either way).
Angle = Annotated[float, Field(ge=-720.0, le=720.0, allow_inf_nan=False)]


class TargetPose(BaseModel):
    """A target pose on the table: position (metres) and yaw (degrees).

    ``z`` is the height of the object's centre; leave it out to mean "resting on
    whatever is below" (the table or a support).
    """

    model_config = ConfigDict(extra="forbid")

    x: Coordinate
    y: Coordinate
    z: Coordinate | None = None
    yaw_deg: Angle = 0.0


class AtPose(RelationBase):
    """Put the objects at explicit target poses. ``poses`` are in world coordinates,
    or in the frame of variable ``frame`` if given. ``matches[i][j] = 1`` lets object
    instance i go to pose j (default: any object to any pose); each object needs its
    own pose. ``check_yaw`` false ignores rotation."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {"frame": ()}

    type: Literal["at_pose"] = "at_pose"
    poses: list[TargetPose] = Field(min_length=1)
    matches: list[list[Annotated[int, Field(ge=0, le=1)]]] | None = None
    frame: Name | None = None
    check_yaw: bool = True

    def problems(self, factor: str, variables: Mapping[str, StateVariable]) -> list[Problem]:
        out = super().problems(factor, variables)
        if any(o not in variables for o in self.objects):
            return out
        if self.frame is None:
            for j, pose in enumerate(self.poses):
                if not (WORKSPACE_X[0] <= pose.x <= WORKSPACE_X[1]
                        and WORKSPACE_Y[0] <= pose.y <= WORKSPACE_Y[1]):
                    out.append(Problem(factor, f"goal.poses.{j}", f"pose ({pose.x}, {pose.y}) "
                                       f"is outside the workspace x {WORKSPACE_X}, y "
                                       f"{WORKSPACE_Y}",
                                       "give a target on the table in front of the robot"))
                if pose.z is not None and not WORKSPACE_Z[0] <= pose.z <= WORKSPACE_Z[1]:
                    out.append(Problem(factor, f"goal.poses.{j}", f"height {pose.z} is outside "
                                       f"the workspace z {WORKSPACE_Z}", "leave z out to rest "
                                       "the object on whatever is below"))
        n = sum(variables[o].count for o in self.objects)
        m = len(self.poses)
        if m < n:
            out.append(Problem(factor, "goal.poses", f"{n} object(s) but only {m} pose(s)",
                               "give every object instance its own target pose"))
        if self.matches is not None:
            rows = self.matches
            if len(rows) != n or any(len(r) != m for r in rows):
                shape = f"{len(rows)}x{len(rows[0]) if rows else 0}"
                out.append(Problem(factor, "goal.matches", f"matches is {shape}, expected "
                                   f"{n}x{m} (object instances x poses)", "fix the matrix shape"))
            else:
                for i, r in enumerate(rows):
                    if not any(r):
                        out.append(Problem(factor, "goal.matches", f"object instance {i} may "
                                           "go to no pose", "allow at least one pose per row"))
        return out

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], AtPose]:
        return ([{"name": "red_block", "kind": "block", "color": "red"}],
                cls(objects=["red_block"], poses=[TargetPose(x=0.5, y=0.1, yaw_deg=30.0)]))

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        n, m = len(movers), len(self.poses)
        matches = (np.array(self.matches, dtype=bool) if self.matches is not None
                   else np.ones((n, m), dtype=bool))
        return solve_given_poses(ctx, movers, self.poses, matches, self.frame, self.check_yaw)

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        return check_slots(solved, scene, self.tolerances)


def solve_given_poses(ctx: SolveContext, movers: list[SceneObject], poses: list[TargetPose],
                      matches: np.ndarray, frame: str | None = None,
                      check_yaw: bool = True) -> Plan:
    """Slots at poses an author gave (see :class:`AtPose`), shared by every relation
    that takes explicit poses.

    Raises:
        Infeasible: ``matches`` has the wrong shape or leaves an object without a pose.
    """
    n, m = len(movers), len(poses)
    if matches.shape != (n, m):
        raise Infeasible(f"matches is {matches.shape}, expected ({n}, {m})", retry=False)
    frame_pose = ctx.current[ctx.inst(frame)[0]] if frame else None
    xy_list, yaws, zs = [], [], []
    for tp in poses:
        xy = np.array([tp.x, tp.y])
        yaw = math.radians(tp.yaw_deg)
        z = tp.z
        if frame_pose is not None:
            xy = frame_pose.pos[:2] + yaw_rotation_2d(frame_pose.yaw) @ xy
            yaw += frame_pose.yaw
            z = None if z is None else float(frame_pose.pos[2] + z)
        xy_list.append(xy)
        yaws.append(yaw)
        zs.append(z)
    start = np.array([ctx.current[o.name].pos[:2] for o in movers])
    dist = np.linalg.norm(start[:, None, :] - np.array(xy_list)[None, :, :], axis=-1)
    rows, cols = linear_sum_assignment(np.where(matches, dist, 1e6))
    if np.any(~matches[rows, cols]):
        raise Infeasible("matches leave some object without a pose of its own",
                         retry=False)
    assignment = [0] * n
    for r, c in zip(rows, cols, strict=True):
        assignment[int(r)] = int(c)
    slots, surfaces, supports, ignore = [], [], [], []
    moving = {o.name for o in movers}
    for j in range(m):
        who = [i for i in range(n) if assignment[i] == j]
        obj = movers[who[0]] if who else movers[int(np.argmax(matches[:, j]))]
        if zs[j] is not None:
            surface, host = None, TABLE
            slots.append(Pose.from_xyz_yaw(*xy_list[j], zs[j], yaws[j]))
        else:
            surface, host = _surface_under(ctx, xy_list[j], exclude=moving)
            slots.append(resting_pose(obj, *xy_list[j], surface, yaws[j]))
        surfaces.append(surface)
        supports.append(host)
        ignore.append(set() if host == TABLE else {host})
    return make_plan(slots, surfaces, supports, ignore, matches, assignment=assignment,
                     check_yaw=check_yaw, given=True)


def _surface_under(ctx: SolveContext, xy: np.ndarray, exclude: set[str]) -> tuple[float, str]:
    """Highest resting surface under point ``xy`` and what provides it."""
    best, host = TABLE_Z, TABLE
    for name in ctx.occ.names():
        if name in exclude or name not in ctx.objs:
            continue
        obj = ctx.objs[name]
        if not obj.collides or not (obj.spec.support or obj.is_receptacle):
            continue
        pose = ctx.current[name]
        if not bool(placement_area(obj, pose).contains(xy[None, :])[0]):
            continue
        s = rest_surface_z(obj, pose)
        if s > best:
            best, host = s, name
    return best, host
