"""The oracle's next move for a ``rope_along`` factor: which segment, and where.

A rope is a chain: segment k's head (+x) is linked to segment k+1's tail. Two
rules make the moves converge (:func:`plan_rope_carry`):

* **Head first along the run.** A segment is set down on its slot turned to the
  run's direction there, its head towards the next segment's slot (the run's
  direction, or the opposite one when the rope lies reversed). A segment is a box,
  symmetric under a half turn, but its links are not: set down the other way
  round, its neighbour must fold back over it, and that fold holds rope the far
  end then lacks. Placing one end then drags the other end off, and back: the
  oscillation seen on 2 of 12 seeds before.
* **Slack.** Slots a whole segment apart (Ravens' bead targets) leave the rope no
  slack: laid exactly on them it is taut, and setting one end down drags the
  other off its slot. The oracle aims at the slots drawn together along the run
  towards its middle, :data:`~factask.relations.rope.SLOT_PITCH` of a segment
  apart (:func:`aim_points`; at most ~1 cm at the ends of a 20-segment rope,
  within Ravens' 2 cm); slots already that close are aimed at as they are.
* **Folds before the farthest segment.** After the two ends
  (:func:`~factask.relations.rope.rope_slot_order`), a segment near its slot but
  turned more than :data:`KINK_DEG` from the run's direction is placed next, even
  when it is within tolerance of its slot: straightening it gives the rope its
  length back. A segment straightened :data:`MAX_FOLD_FIXES` times that its
  neighbours turned back is no fold any more (the oracle's choice).
* **A slow carry.** The carry moves at
  :data:`~factask.sim.low_carry.CARRY_SPEED`: carried fast, the rope trailing
  behind runs on when the segment stops and piles up over it (a tangle no single
  placement undoes).

Each move is a low carry (:mod:`factask.sim.low_carry`): the segment is lifted
:data:`~factask.sim.low_carry.ROPE_LIFT` and the rest of the rope slides after it.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping

import numpy as np

from factask.geometry import Pose, wrap_angle
from factask.relations.rope import SLOT_PITCH, rope_slot_order
from factask.relations.solving import SolvedFactor
from factask.relations.status import FactorStatus
from factask.scene.objects import SceneObject, top_z
from factask.sim.low_carry import ROPE_LIFT, CarryAction

#: A segment turned more than this (degrees) from the run's direction is a fold...
KINK_DEG = 90.0
#: Straightening one segment this often is enough (its neighbours hold it turned).
MAX_FOLD_FIXES = 2
#: ... when it lies within this (m) of where it is aimed (farther off, it is merely
#: not laid out yet).
FOLD_NEAR = 0.04


def segment_slots(solved: SolvedFactor, status: FactorStatus) -> dict[str, int]:
    """Every segment's slot in the rope's current direction (placed ones too)."""
    slots = {name: int(s) for name, s in status.placed.items() if s is not None}
    slots.update(status.targets)
    return slots


def heading(solved: SolvedFactor, objects: Mapping[str, SceneObject], name: str,
            slot: int) -> float:
    """The yaw (rad) segment ``name`` should have on ``slot``: its head towards the
    next segment's slot (the slot's yaw, turned half round when the rope lies
    reversed along the run)."""
    k = solved.objects.index(name)
    yaw = solved.target_pose(objects[name], slot).yaw
    return wrap_angle(yaw + (math.pi if slot != k else 0.0))


def aim_points(slots: np.ndarray, segment: float, pitch: float = SLOT_PITCH) -> np.ndarray:
    """Where to set the segments down: the run through ``slots`` (n, 2) drawn
    together towards its middle (along its length) until neighbours are at most
    ``pitch`` segment lengths apart.

    Args:
        slots: The slots' centres in run order.
        segment: A segment's length (m).
        pitch: The widest spacing aimed at, in segment lengths.
    """
    steps = np.linalg.norm(np.diff(slots, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(steps)])
    if len(slots) < 2 or s[-1] <= 0:
        return slots.copy()
    f = min(1.0, pitch * segment * (len(slots) - 1) / s[-1])
    want = s[-1] / 2 + (s - s[-1] / 2) * f
    return np.column_stack([np.interp(want, s, slots[:, 0]), np.interp(want, s, slots[:, 1])])


def plan_rope_carry(fname: str, solved: SolvedFactor, status: FactorStatus,
                    objects: Mapping[str, SceneObject], poses: Mapping[str, Pose],
                    settled: Collection[str] = (), lift: float = ROPE_LIFT
                    ) -> CarryAction | None:
    """The next low carry for a ``rope_along`` factor, or None when no segment is
    left to place.

    Args:
        fname: The factor.
        solved: Its solved slots.
        status: Its status now (which segments are placed, on which slots).
        objects: Scene objects by instance name.
        poses: Current poses.
        settled: Segments no longer treated as folds (straightened often enough: their
            neighbours turn them back).
        lift: How high the segment is carried.
    """
    if not status.targets:
        return None
    slots = segment_slots(solved, status)
    first = objects[solved.objects[0]]
    run = np.array([solved.target_pose(first, k).pos[:2] for k in range(len(solved.objects))])
    aims = aim_points(run, first.size[0])
    want = {name: heading(solved, objects, name, s) for name, s in slots.items()}
    dist = {name: float(np.linalg.norm(poses[name].pos[:2] - aims[s]))
            for name, s in slots.items()}
    bend = {name: abs(math.degrees(wrap_angle(poses[name].yaw - want[name])))
            for name in slots if name not in settled}
    name = rope_slot_order(status.targets, len(solved.objects), dist, bend=bend,
                           kink_deg=KINK_DEG, near=FOLD_NEAR)
    obj, now = objects[name], poses[name]
    target = solved.target_pose(obj, slots[name])
    pick = np.array([now.pos[0], now.pos[1], top_z(obj, now), now.yaw])
    aim = aims[slots[name]]
    place = np.array([aim[0], aim[1], target.pos[2] + obj.half[2], want[name]])
    return CarryAction(pick, place, lift, name, fname, f"place {name}")


__all__ = ["FOLD_NEAR", "KINK_DEG", "MAX_FOLD_FIXES", "aim_points", "heading",
           "plan_rope_carry", "segment_slots"]
