"""A scripted suction oracle that solves any valid task graph.

The oracle sees only what a policy could also be given: the objects' current
poses and sizes, and the solved targets of every factor. Each call to
:meth:`Oracle.act` returns one pick-and-place action:

1. Take the factors in the graph's order; the first one that is not satisfied
   is worked on (a finished factor that becomes unsatisfied again — a knocked
   stack — is worked on again: the oracle re-plans every action).
2. Read the factor's status (:class:`~factask.relations.status.FactorStatus`):
   which objects are placed, and the free slot each unplaced object should take.
   Choose the one whose target is lowest (supports before what rests on them),
   farthest first on ties (Ravens).
3. If something rests on that object, or stands where it must go, move that
   obstacle to a free spot of the table first (the collision model's
   :func:`~factask.scene.collision.parking_spot`).
4. Pick at the top of the object (tool yaw = object yaw) and place so the object
   ends at its target, turned to the target yaw modulo the object's symmetry by
   the shortest rotation.

A ``pile_in_zone`` factor is worked on by pushes instead
(:mod:`factask.sim.oracle.push`), until its threshold holds.

It gives up, with the reason, when one object fails too often or no free spot
exists for an obstacle.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from factask.geometry import Pose, tilt_deg, wrap_angle
from factask.graph.taskgraph import TaskGraph
from factask.relations.drawer import ArticulatedRelation
from factask.relations.pile_in_zone import PileInZone
from factask.relations.rope import RopeAlong
from factask.relations.solving import SolvedFactor
from factask.relations.status import MAX_TILT_DEG, FactorStatus
from factask.relations.switch import SwitchRelation
from factask.scene.cabinet import drawer_seat, handle_point
from factask.scene.collision import beneath, occupying, parking_spot, resting_on
from factask.scene.microwave import door_handle_point, hinge_point
from factask.scene.objects import SPHERE_KINDS, SceneObject
from factask.scene.switch import button_top
from factask.sim.layout.checks import TaskStatus
from factask.sim.oracle.pick_points import pick_and_place_points
from factask.sim.oracle.push import PushAction, plan_push
from factask.sim.oracle.rope import MAX_FOLD_FIXES, plan_rope_carry
from factask.sim.robots.door_swing import SwingAction
from factask.sim.robots.low_carry import CarryAction
from factask.sim.robots.slide_pull import SlideAction
from factask.sim.robots.switch_press import PressAction
from factask.vocabulary.kinds import yaw_symmetry_deg

#: Attempts at placing one object for one factor before the oracle gives up.
MAX_ATTEMPTS_PER_OBJECT = 3
#: Where a moved-away obstacle may not come closer than this to anything (m).
PARKING_CLEARANCE = 0.015
#: Random candidate spots tried when parking an obstacle.
PARKING_SAMPLES = 400
#: Pushes in a row that do not raise a pile goal's progress before the oracle gives up.
MAX_IDLE_PUSHES = 6


class OracleView(Protocol):
    """What the oracle reads of an env: :class:`factask.sim.env.FactaskEnv` after
    ``reset``, or one world of a batch (:class:`factask.batch.planner.WorldView`).

    The oracle never steps the env itself (its caller does), so it needs no import of
    the env: it sits beside it, below the episode loop that drives both.
    """

    graph: TaskGraph
    objects: Mapping[str, SceneObject]

    @property
    def solved(self) -> Mapping[str, SolvedFactor]: ...

    def object_poses(self) -> dict[str, Pose]: ...

    def held_objects(self) -> set[str]: ...

    def status(self) -> TaskStatus: ...


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
    return wrap_angle(yaw)


class Oracle:
    """Scripted agent for a :class:`~factask.sim.env.FactaskEnv` (any :class:`OracleView`).

    Args:
        env: The environment (after ``reset``).
        seed: Seed of the oracle's own choices (parking spots).
    """

    def __init__(self, env: OracleView, seed: int = 0) -> None:
        self.env = env
        self.order = env.graph.factor_order()
        self.milestones = env.graph.milestones()
        self.rng = np.random.default_rng(seed)
        self.attempts: Counter[tuple[str, str]] = Counter()
        self.failure: str | None = None
        # Pile goals: the best progress seen (pushes that do not raise it count).
        self._pile_best: dict[str, float] = {}
        self._pile_aims: dict[str, list[str]] = {}

    def _targets(self, fname: str, status: FactorStatus) -> dict[str, Pose]:
        """Target pose of every unplaced object of a factor: the free slot its status
        gives it."""
        solved = self.env.solved[fname]
        objs = self.env.objects
        return {name: solved.target_pose(objs[name], slot)
                for name, slot in status.targets.items()}

    def _action(self, obj: SceneObject, current: Pose, target: Pose, factor: str,
                purpose: str) -> OracleAction:
        pick_yaw = current.yaw
        # Where the goal ignores yaw (symmetry 0), still turn by the object's shape
        # symmetry: a box set down askew can hit its neighbours.
        symmetry = obj.symmetry_deg or yaw_symmetry_deg(obj.kind, obj.size)
        place_yaw = _yaw_toward(target.yaw, pick_yaw, symmetry)
        # At the top centre, or on the rim of a receptacle (sim.pick_points).
        pick, place = pick_and_place_points(obj, current, target, pick_yaw, place_yaw,
                                            self.env.objects, self.env.object_poses())
        return OracleAction(pick, place, obj.name, factor, purpose)

    def _move_away(self, name: str, poses: dict[str, Pose], factor: str,
                   why: str) -> OracleAction | None:
        objs = self.env.objects
        targets = [(objs[inst], pose) for solved in self.env.solved.values()
                   for inst, pose in solved.targets(objs).items()]
        spot = parking_spot(name, objs, poses, targets, self.rng, PARKING_CLEARANCE,
                            PARKING_SAMPLES)
        if spot is None:
            self.failure = f"factor {factor!r}: no free spot to move {name!r} out of the way"
            return None
        return self._action(self.env.objects[name], poses[name], spot, factor, why)

    def _moved_later(self, fname: str, status: TaskStatus) -> set[str]:
        """Objects a goal other than ``fname``, not satisfied yet, has still to place."""
        return {o for f, fs in status.factors.items() if f != fname and not fs.satisfied
                for o in self.env.solved[f].objects if o not in fs.placed}

    # ------------------------------------------------------------------- act
    def plan(self) -> (OracleAction | PushAction | CarryAction | SlideAction | SwingAction
                       | PressAction | None):
        """The next action, or None when done or giving up (see :attr:`failure`)."""
        env = self.env
        status = env.status()
        if status.success:
            return None
        poses = env.object_poses()
        objs = env.objects
        pending_milestones = [n for n in self.milestones if n not in status.reached]
        for fname in self.order:
            fstatus = status.factors[fname]
            if fstatus.satisfied:
                continue
            if fname in status.reached and any(self.order.index(m) > self.order.index(fname)
                                               for m in pending_milestones):
                # A final goal reached earlier and disturbed since: a milestone still
                # ahead may need its objects; restore it once the milestones are done.
                continue
            goal = env.graph.factor(fname).goal
            if isinstance(goal, PileInZone):  # blocks are pushed, never picked
                return self._push(fname, goal, fstatus, poses)
            if isinstance(goal, RopeAlong):  # segments in order along the run
                return self._rope_segment(fname, fstatus, poses)
            if isinstance(goal, ArticulatedRelation):  # slid (swung) by the handle, never picked
                return self._slide(fname, fstatus, poses)
            if isinstance(goal, SwitchRelation):  # pressed (pulled) by the cup, never picked
                return self._press(fname, fstatus, poses)
            for name in fstatus.placed:  # a success resets the object's retry budget
                self.attempts.pop((fname, name), None)
            targets = self._targets(fname, fstatus)
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
            above = resting_on(name, objs, poses)
            if above:
                return self._move_away(above[0], poses, fname, f"uncover {name}")
            blockers = occupying(name, targets[name], objs, poses, keep=fstatus.placed)
            if blockers:
                return self._move_away(blockers[0], poses, fname, f"clear the target of {name}")
            # Something under the target that a goal still to do will move, and that the
            # goal does not mean it to rest on: move it now, or taking it later pulls it
            # from under (or bumps) what rests there. (A support the goal names may be
            # moved later on purpose: towers-of-hanoi's disks.)
            solved = env.solved[fname]
            meant = {*solved.supports, *solved.support_group}
            later = self._moved_later(fname, status) - meant
            under = [o for o in beneath(name, targets[name], objs, poses) if o in later]
            if under:
                return self._move_away(under[0], poses, fname, f"clear under the target of {name}")
            self.attempts[(fname, name)] += 1
            if self.attempts[(fname, name)] > MAX_ATTEMPTS_PER_OBJECT:
                self.failure = (f"factor {fname!r}: could not place {name!r} after "
                                f"{MAX_ATTEMPTS_PER_OBJECT} attempts ({fstatus.detail})")
                return None
            return self._action(objs[name], poses[name], targets[name], fname,
                                f"place {name}")
        self.failure = "every factor is satisfied but the task is not (inconsistent checks)"
        return None

    def _push(self, fname: str, goal: PileInZone, fstatus: FactorStatus,
              poses: dict[str, Pose]) -> PushAction | None:
        """The next push for a pile goal (:mod:`factask.sim.oracle.push`); gives up
        when :data:`MAX_IDLE_PUSHES` pushes in a row did not raise its progress."""
        best = self._pile_best.get(fname, -1.0)
        aimed = self._pile_aims.setdefault(fname, [])
        if fstatus.progress > best + 1e-6:
            self._pile_best[fname] = fstatus.progress
            self.attempts[(fname, "")] = 0
            aimed.clear()
        self.attempts[(fname, "")] += 1
        if self.attempts[(fname, "")] > MAX_IDLE_PUSHES:
            self.failure = (f"factor {fname!r}: {MAX_IDLE_PUSHES} pushes did not raise its "
                            f"progress ({fstatus.detail})")
            return None
        # Blocks aimed at since the progress last rose come last: aim elsewhere.
        action = plan_push(fname, goal, self.env.solved[fname], self.env.objects, poses,
                           self.env.held_objects(), avoid=set(aimed))
        if action is None:
            self.failure = f"factor {fname!r}: no block outside but not satisfied"
            return None
        aimed.append(action.obj)
        return action

    def _rope_segment(self, fname: str, fstatus: FactorStatus,
                      poses: dict[str, Pose]) -> CarryAction | None:
        """Place the rope's next segment (:func:`~factask.sim.oracle.rope.plan_rope_carry`:
        its two ends, then folds, then the farthest from its place, each set down head
        first along the run), carried low so the rope slides after it."""
        for name in fstatus.placed:
            self.attempts.pop((fname, name), None)
        # A segment placed already is moved again as a fold; a few times at most.
        settled = {n for n in fstatus.placed
                   if self.attempts[(fname, f"fold:{n}")] >= MAX_FOLD_FIXES}
        action = plan_rope_carry(fname, self.env.solved[fname], fstatus, self.env.objects,
                                 poses, settled)
        if action is None:
            self.failure = f"factor {fname!r}: no slot for the rope's segments"
            return None
        self.attempts[(fname, action.obj)] += 1
        if self.attempts[(fname, action.obj)] > MAX_ATTEMPTS_PER_OBJECT:
            self.failure = (f"factor {fname!r}: could not place {action.obj!r} after "
                            f"{MAX_ATTEMPTS_PER_OBJECT} attempts ({fstatus.detail})")
            return None
        if action.obj in fstatus.placed:
            self.attempts[(fname, f"fold:{action.obj}")] += 1
        return action

    def _slide(self, fname: str, fstatus: FactorStatus,
               poses: dict[str, Pose]) -> SlideAction | SwingAction | None:
        """Slide the factor's first drawer not there yet to its slot: the cup holds
        its handle and moves by the drawer's offset from its target; a door is swung
        about its hinge until its handle is where the target puts it."""
        solved = self.env.solved[fname]
        name = next((n for n in solved.objects if n not in fstatus.placed), None)
        if name is None:
            self.failure = f"factor {fname!r}: every drawer is there but not satisfied"
            return None
        self.attempts[(fname, name)] += 1
        if self.attempts[(fname, name)] > MAX_ATTEMPTS_PER_OBJECT:
            self.failure = (f"factor {fname!r}: could not slide {name!r} after "
                            f"{MAX_ATTEMPTS_PER_OBJECT} attempts ({fstatus.detail})")
            return None
        obj = self.env.objects[name]
        target = solved.target_pose(obj, solved.objects.index(name))
        if obj.kind == "door":
            host = solved.supports[solved.objects.index(name)]
            grasp = door_handle_point(obj, poses[name])
            to = door_handle_point(obj, target)
            hinge = hinge_point(self.env.objects[host], poses[host])
            yaw = poses[name].yaw
            return SwingAction(np.array([*grasp, yaw]), np.array([*to, yaw]), hinge[:2],
                               name, fname, f"swing {name} to its {solved.relation} place")
        grasp = handle_point(obj, poses[name], drawer_seat(self.env.graph, obj.variable))
        to = grasp + (target.pos - poses[name].pos)
        yaw = poses[name].yaw
        return SlideAction(np.array([*grasp, yaw]), np.array([*to, yaw]), name, fname,
                           f"slide {name} to its {solved.relation} place")

    def _press(self, fname: str, fstatus: FactorStatus,
               poses: dict[str, Pose]) -> PressAction | None:
        """Press the factor's first switch not there yet to its slot: the cup comes
        down on its button's top and moves it by the button's offset from its target
        (down: a press; up: a pull)."""
        solved = self.env.solved[fname]
        name = next((n for n in solved.objects if n not in fstatus.placed), None)
        if name is None:
            self.failure = f"factor {fname!r}: every switch is there but not satisfied"
            return None
        self.attempts[(fname, name)] += 1
        if self.attempts[(fname, name)] > MAX_ATTEMPTS_PER_OBJECT:
            self.failure = (f"factor {fname!r}: could not press {name!r} after "
                            f"{MAX_ATTEMPTS_PER_OBJECT} attempts ({fstatus.detail})")
            return None
        obj = self.env.objects[name]
        target = solved.target_pose(obj, solved.objects.index(name))
        top = button_top(obj, poses[name])
        to = top + (target.pos - poses[name].pos)
        yaw = poses[name].yaw
        return PressAction(np.array([*top, yaw]), np.array([*to, yaw]), name, fname,
                           f"press {name} to its {solved.relation} place")

    def act(self) -> dict[str, np.ndarray] | None:
        """The next action for ``env.step``, or None (done, or gave up)."""
        planned = self.plan()
        return None if planned is None else planned.as_env_action()
