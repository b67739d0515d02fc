"""A scripted suction oracle that solves any valid task graph.

The oracle sees only what a policy could also be given: the objects' current
poses and sizes, and the solved targets of every factor. Each call to
:meth:`Oracle.act` returns one pick-and-place action:

1. Take the factors in the graph's order; the first one that is not satisfied
   is worked on (a finished factor that becomes unsatisfied again — a knocked
   stack — is worked on again: the oracle re-plans every action).
2. Find which of its objects are not placed (an object counts as placed when
   taking it away lowers the factor's progress), give each a free target slot
   the relation allows (optimal assignment), and choose the one whose target is
   lowest (supports before what rests on them), farthest first on ties (Ravens).
3. If something rests on that object, or stands where it must go, move that
   obstacle to a free spot of the table first.
4. Pick at the top of the object (tool yaw = object yaw) and place so the object
   ends at its target, turned to the target yaw modulo the object's symmetry by
   the shortest rotation.

It gives up, with the reason, when one object fails too often or no free spot
exists for an obstacle.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from factask.geometry import Pose, tilt_deg
from factask.model.kinds import yaw_symmetry_deg
from factask.model.world import WORKSPACE_X, WORKSPACE_Y
from factask.sim.checks import MAX_TILT_DEG, check_factor
from factask.sim.env import FactaskEnv
from factask.sim.layout import SolvedFactor
from factask.sim.objects import (
    SPHERE_KINDS,
    SceneObject,
    bottom_z,
    footprint_corners,
    obb_overlaps,
    top_z,
)

#: Attempts at placing one object for one factor before the oracle gives up.
MAX_ATTEMPTS_PER_OBJECT = 3
#: Where a moved-away obstacle may not come closer than this to anything (m).
PARKING_CLEARANCE = 0.015
#: Random candidate spots tried when parking an obstacle.
PARKING_SAMPLES = 400
#: Vertical slack (m) when deciding that one object rests on another.
REST_EPS = 0.01
#: How far away (m) an object is moved when testing whether it counts as placed.
_AWAY = 100.0


@dataclass(frozen=True)
class OracleAction:
    """One planned action and why it was chosen."""

    pick: np.ndarray
    place: np.ndarray
    obj: str
    factor: str
    purpose: str

    def as_env_action(self) -> dict[str, np.ndarray]:
        return {"pick": self.pick, "place": self.place}


def _yaw_toward(target: float, current: float, symmetry_deg: float) -> float:
    """The yaw equivalent to ``target`` (modulo symmetry) closest to ``current``."""
    if symmetry_deg <= 0:
        return current
    period = math.radians(symmetry_deg)
    k = round((current - target) / period)
    yaw = target + k * period
    return math.atan2(math.sin(yaw), math.cos(yaw))


class Oracle:
    """Scripted agent for a :class:`~factask.sim.env.FactaskEnv`.

    Args:
        env: The environment (after ``reset``).
        seed: Seed of the oracle's own choices (parking spots).
    """

    def __init__(self, env: FactaskEnv, seed: int = 0) -> None:
        self.env = env
        self.order = env.graph.factor_order()
        self.rng = np.random.default_rng(seed)
        self.attempts: Counter[tuple[str, str]] = Counter()
        self.failure: str | None = None

    # ---------------------------------------------------------------- helpers
    def _placed(self, solved: SolvedFactor, poses: dict[str, Pose], base: float) -> set[str]:
        """Objects of the factor that count towards its progress now."""
        placed = set()
        for name in solved.objects:
            moved = dict(poses)
            p = poses[name]
            moved[name] = Pose(p.pos + np.array([_AWAY, _AWAY, 0.0]), p.quat)
            if check_factor(self.env.graph, solved, moved, (), self.env.objects).progress < base:
                placed.add(name)
        return placed

    def _targets(self, solved: SolvedFactor, poses: dict[str, Pose], placed: set[str]
                 ) -> dict[str, Pose]:
        """A target pose for every unplaced object, on slots placed objects do not take."""
        objs = self.env.objects
        n_slots = len(solved.slots)
        taken: set[int] = set()
        for name in placed:
            i = solved.objects.index(name)
            allowed = [j for j in range(n_slots) if solved.matches[i, j] and j not in taken]
            if allowed:
                d = [np.linalg.norm(poses[name].pos - solved.target_pose(objs[name], j).pos)
                     for j in allowed]
                taken.add(allowed[int(np.argmin(d))])
        todo = [n for n in solved.objects if n not in placed]
        free = [j for j in range(n_slots) if j not in taken]
        if not todo or not free:
            return {}
        cost = np.full((len(todo), len(free)), 1e6)
        for a, name in enumerate(todo):
            i = solved.objects.index(name)
            for b, j in enumerate(free):
                if solved.matches[i, j]:
                    cost[a, b] = float(np.linalg.norm(
                        poses[name].pos - solved.target_pose(objs[name], j).pos))
        rows, cols = linear_sum_assignment(cost)
        return {todo[r]: solved.target_pose(objs[todo[r]], free[c])
                for r, c in zip(rows, cols, strict=True) if cost[r, c] < 1e6}

    def _resting_on(self, name: str, poses: dict[str, Pose]) -> list[str]:
        """Free objects resting on top of ``name`` (directly), highest first."""
        objs = self.env.objects
        me = objs[name]
        top = top_z(me, poses[name])
        mine = footprint_corners(me, poses[name])
        out = []
        for other, obj in objs.items():
            if other == name or obj.fixed or not obj.collides:
                continue
            if abs(bottom_z(obj, poses[other]) - top) < REST_EPS and obb_overlaps(
                    mine, footprint_corners(obj, poses[other]))[0, 0]:
                out.append(other)
        return sorted(out, key=lambda o: -poses[o].pos[2])

    def _blocking_target(self, name: str, target: Pose, poses: dict[str, Pose],
                         keep: set[str]) -> list[str]:
        """Free objects (not in ``keep``) occupying the space ``name`` goes to."""
        objs = self.env.objects
        me = objs[name]
        lo, hi = target.pos[2] - me.half[2], target.pos[2] + me.half[2]
        corners = footprint_corners(me, target, margin=-0.002)
        out = []
        for other, obj in objs.items():
            if other == name or other in keep or obj.fixed or not obj.collides:
                continue
            p = poses[other]
            if bottom_z(obj, p) < hi - REST_EPS and top_z(obj, p) > lo + REST_EPS and \
                    obb_overlaps(corners, footprint_corners(obj, p))[0, 0]:
                out.append(other)
        return out

    def _parking_spot(self, name: str, poses: dict[str, Pose]) -> Pose | None:
        """A free table spot for ``name`` away from every object and every target."""
        objs = self.env.objects
        obj = objs[name]
        others = [footprint_corners(o, poses[n], PARKING_CLEARANCE)
                  for n, o in objs.items() if n != name and o.collides]
        for solved in self.env.solved.values():
            for inst, pose in solved.targets(objs).items():
                others.append(footprint_corners(objs[inst], pose, PARKING_CLEARANCE))
        # Regions (zones, lines) are not collisions but parking there would count.
        occupied = np.array(others + [footprint_corners(o, poses[n]) for n, o in objs.items()
                                      if not o.collides]).reshape(-1, 4, 2)
        margin = float(np.linalg.norm(obj.half_xy)) + 0.01
        for _ in range(PARKING_SAMPLES):
            x = self.rng.uniform(WORKSPACE_X[0] + margin, WORKSPACE_X[1] - margin)
            y = self.rng.uniform(WORKSPACE_Y[0] + margin, WORKSPACE_Y[1] - margin)
            pose = Pose.from_xyz_yaw(x, y, obj.half[2], poses[name].yaw)
            if not obb_overlaps(footprint_corners(obj, pose), occupied).any():
                return pose
        return None

    def _action(self, obj: SceneObject, current: Pose, target: Pose, factor: str,
                purpose: str) -> OracleAction:
        pick_yaw = current.yaw
        # Where the goal ignores yaw (symmetry 0), still turn by the object's shape
        # symmetry: a box set down askew can hit its neighbours.
        symmetry = obj.symmetry_deg or yaw_symmetry_deg(obj.kind, obj.size)
        place_yaw = _yaw_toward(target.yaw, pick_yaw, symmetry)
        pick = np.array([current.pos[0], current.pos[1], top_z(obj, current), pick_yaw])
        place = np.array([target.pos[0], target.pos[1], target.pos[2] + obj.half[2],
                          place_yaw])
        return OracleAction(pick, place, obj.name, factor, purpose)

    def _move_away(self, name: str, poses: dict[str, Pose], factor: str,
                   why: str) -> OracleAction | None:
        spot = self._parking_spot(name, poses)
        if spot is None:
            self.failure = f"factor {factor!r}: no free spot to move {name!r} out of the way"
            return None
        return self._action(self.env.objects[name], poses[name], spot, factor, why)

    # ------------------------------------------------------------------- act
    def plan(self) -> OracleAction | None:
        """The next action, or None when done or giving up (see :attr:`failure`)."""
        env = self.env
        status = env.status()
        if status.success:
            return None
        poses = env.object_poses()
        objs = env.objects
        for fname in self.order:
            fstatus = status.factors[fname]
            if fstatus.satisfied:
                continue
            solved = env.solved[fname]
            placed = self._placed(solved, poses, fstatus.progress)
            for name in placed:  # a success resets the object's retry budget
                self.attempts.pop((fname, name), None)
            targets = self._targets(solved, poses, placed)
            if not targets:
                self.failure = (f"factor {fname!r}: no free target slot for its unplaced "
                                f"objects ({fstatus.detail})")
                return None
            # Lowest target first (supports before what rests on them); Ravens'
            # farthest-first on ties.
            name = min(targets, key=lambda n: (round(targets[n].pos[2], 3),
                                               -np.linalg.norm(poses[n].pos - targets[n].pos)))
            if objs[name].kind not in SPHERE_KINDS and tilt_deg(poses[name].quat) > MAX_TILT_DEG:
                # A top-down suction cup cannot turn an object back upright.
                self.failure = (f"factor {fname!r}: {name!r} lies tilted "
                                f"{tilt_deg(poses[name].quat):.0f} deg; a top-down suction "
                                "cup cannot right it")
                return None
            above = self._resting_on(name, poses)
            if above:
                return self._move_away(above[0], poses, fname, f"uncover {name}")
            blockers = self._blocking_target(name, targets[name], poses, placed)
            if blockers:
                return self._move_away(blockers[0], poses, fname, f"clear the target of {name}")
            self.attempts[(fname, name)] += 1
            if self.attempts[(fname, name)] > MAX_ATTEMPTS_PER_OBJECT:
                self.failure = (f"factor {fname!r}: could not place {name!r} after "
                                f"{MAX_ATTEMPTS_PER_OBJECT} attempts ({fstatus.detail})")
                return None
            return self._action(objs[name], poses[name], targets[name], fname,
                                f"place {name}")
        self.failure = "every factor is satisfied but the task is not (inconsistent checks)"
        return None

    def act(self) -> dict[str, np.ndarray] | None:
        """The next action for ``env.step``, or None (done, or gave up)."""
        planned = self.plan()
        return None if planned is None else planned.as_env_action()
