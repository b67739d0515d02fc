"""``on``: objects resting on top of a support (or centred on a group of supports)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar, Literal

import numpy as np

from factask.geometry import Pose
from factask.relations.base import RelationBase
from factask.relations.packing import pack_plan
from factask.relations.solving import Infeasible, Plan, SolveContext, SolvedFactor, make_plan
from factask.relations.status import MAX_TILT_DEG, CheckScene, Verdict, upright_tilt_deg
from factask.scene.collision import CLEARANCE
from factask.scene.objects import (
    GEOMETRY_EPS,
    SceneObject,
    bottom_z,
    footprint_corners,
    group_area,
    obb_overlaps,
    placement_area,
    rest_surface_z,
    resting_pose,
    yaw_rotation_2d,
)
from factask.vocabulary.names import Name

_CM = 100.0


class On(RelationBase):
    """Put the objects resting on top of ``support`` (side by side if several).
    If ``support`` has several instances the objects rest centred on the group,
    aligned with it (e.g. a bar bridging two pillars)."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {
        "support": ("support", "receptacle")}
    met_by_starting_in: ClassVar[str | None] = "support"

    type: Literal["on"] = "on"
    support: Name

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], On]:
        return ([{"name": "block", "kind": "block", "color": "blue"},
                 {"name": "pallet", "kind": "pallet"}],
                cls(objects=["block"], support="pallet"))

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        hosts = ctx.inst(self.support)
        n = len(movers)
        ones = np.ones((n, n), dtype=bool)
        if len(hosts) == 1:
            host = hosts[0]
            hobj, hpose = ctx.objs[host], ctx.current[host]
            area = placement_area(hobj, hpose)
            fits = all(np.all(o.half_xy <= area.packing_half() + GEOMETRY_EPS) for o in movers)
            if n == 1 and not fits:  # bigger than the top face: centred on it
                surface = rest_surface_z(hobj, hpose)
                slot = resting_pose(movers[0], *area.center, surface, area.yaw)
                return make_plan([slot], [surface], [host], [{host}], ones, support_group=hosts)
            slots, surfaces, supports = pack_plan(ctx, movers, [(host, list(range(n)))],
                                                  ctx.attempt % 2 == 1)
            return make_plan(slots, surfaces, supports, [{host}] * n, ones,
                             support_group=hosts, random=True)
        hobjs = [ctx.objs[h] for h in hosts]
        hposes = [ctx.current[h] for h in hosts]
        area = group_area(hobjs, hposes)
        surface = max(rest_surface_z(o, p) for o, p in zip(hobjs, hposes, strict=True))
        width = max(o.size[1] for o in movers) + CLEARANCE
        normal = yaw_rotation_2d(area.yaw) @ np.array([0.0, 1.0])
        slots = [resting_pose(o, *(area.center + (k - (n - 1) / 2) * width * normal), surface,
                              area.yaw) for k, o in enumerate(movers)]
        # Each object rests on every instance of the support (a deck on both pillars):
        # instances standing apart -- nothing has arranged them -- hold nothing between.
        tops = np.array([footprint_corners(h, p) for h, p in zip(hobjs, hposes, strict=True)])
        for o, slot in zip(movers, slots, strict=True):
            if not obb_overlaps(footprint_corners(o, slot), tops).all():
                raise Infeasible(
                    f"{o.name} cannot rest on every instance of {self.support!r}: they stand "
                    f"{_spread(hposes):.2f} m apart and it is {2 * float(o.half_xy.max()):.2f} m "
                    "long (a goal must first put them side by side, e.g. a row)", retry=False)
        return make_plan(slots, [surface] * n, [hosts[0]] * n, [set(hosts)] * n, ones,
                         support_group=hosts)

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        """Placed: centre over the support's top (or the group's), bottom within ``z``
        of that top, upright."""
        objs = scene.objects
        tol = self.tolerances
        hosts = solved.support_group
        hobjs = [objs[h] for h in hosts]
        hposes = [scene.pose(h) for h in hosts]
        area = group_area(hobjs, hposes)
        surface = max(rest_surface_z(o, p) for o, p in zip(hobjs, hposes, strict=True))
        problems = []
        placed: dict[str, int | None] = {}
        for name in solved.objects:
            obj, pose = objs[name], scene.pose(name)
            if name in scene.held:
                problems.append(f"{name}: held by the robot")
            elif not bool(area.contains(pose.pos[None, :2])[0]):
                problems.append(f"{name}: centre not over {'/'.join(hosts)}")
            elif abs(bottom_z(obj, pose) - surface) > tol.z:
                dz = bottom_z(obj, pose) - surface
                problems.append(f"{name}: bottom {abs(dz) * _CM:.1f} cm "
                                f"{'above' if dz > 0 else 'below'} the support's top "
                                f"(tolerance {tol.z * _CM:.1f} cm)")
            elif upright_tilt_deg(obj, pose) > MAX_TILT_DEG:
                problems.append(f"{name}: tilted {upright_tilt_deg(obj, pose):.0f} deg")
            else:
                placed[name] = None
        return Verdict(placed, problems)


def _spread(poses: list[Pose]) -> float:
    """The largest distance between two of ``poses``' centres (m)."""
    xy = np.array([p.pos[:2] for p in poses])
    return float(np.linalg.norm(xy[:, None, :] - xy[None, :, :], axis=-1).max())
