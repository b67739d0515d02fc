"""A factor's status — the one truth about it — and the checks every relation shares.

A relation's :meth:`~factask.relations.base.RelationBase.check` says which of its
objects are placed (and on which slot, where it has slots) and, in words, why the
others are not (a :class:`Verdict`). :func:`factor_status` turns that into a
:class:`FactorStatus`: progress, satisfied, the placed objects with their slots,
the free slots and, for every object still to place, the free slot it should take
(the nearest, by one optimal assignment). The env's reward and ``info``, the
oracle, the CLI and the scoring all read that status; nobody re-derives it.

Every check re-checks from the current poses (a stack that falls loses its
progress); only milestone factors latch, and that is decided where the statuses
are added up (:mod:`factask.sim.layout.checks`), never inside a relation. Objects held
by the robot never count as placed. Tolerances come from each relation's
``tolerances``, never from literals.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import linear_sum_assignment

from factask.geometry import Pose, tilt_deg, without_roll, yaw_error_deg
from factask.relations.solving import SolvedFactor
from factask.scene.objects import SPHERE_KINDS, SceneObject
from factask.vocabulary.errors import FactaskError
from factask.vocabulary.tolerances import Tolerances

#: An object tilted more than this (degrees) from upright is not placed.
MAX_TILT_DEG = 20.0
#: Problems listed in a factor's detail text at most.
MAX_DETAIL_ITEMS = 3
#: Assignment cost of a slot an object may not take.
_FORBIDDEN = 1e6
_CM = 100.0


class CheckError(FactaskError):
    """A check was asked about something it does not know (missing pose or factor)."""


@dataclass(frozen=True)
class FactorStatus:
    """How far one factor is: the one truth everyone reads.

    Attributes:
        progress: Fraction of the factor's objects placed, in [0, 1].
        satisfied: Every object placed.
        detail: What is off, e.g. "red_block: 2.3 cm from target (tolerance 1.0 cm)".
        placed: Placed object -> the slot it occupies.
        free_slots: Slots no placed object occupies, ascending.
        targets: Object still to place -> the free slot it should take (nearest by
            one optimal assignment within the relation's matches); an object with
            no allowed free slot is absent.
        latched: A milestone reached earlier: full progress whatever the poses now.
        waiting_for: A milestone not ready yet: the factors before it that have not
            been reached (its progress stays 0 until they are).
    """

    progress: float
    satisfied: bool
    detail: str = ""
    placed: Mapping[str, int] = field(default_factory=dict)
    free_slots: tuple[int, ...] = ()
    targets: Mapping[str, int] = field(default_factory=dict)
    latched: bool = False
    waiting_for: tuple[str, ...] = ()


@dataclass(frozen=True)
class CheckScene:
    """What a check looks at: the scene objects, their current poses, what is held.

    Attributes:
        objects: Scene objects by instance name.
        poses: Current pose of every instance (fixed ones too).
        held: Instances the robot holds now (never count as placed).
    """

    objects: Mapping[str, SceneObject]
    poses: Mapping[str, Pose]
    held: Collection[str] = frozenset()

    def pose(self, name: str) -> Pose:
        """The current pose of ``name``.

        Raises:
            CheckError: no pose, or a non-finite one (the simulation has failed).
        """
        try:
            pose = self.poses[name]
        except KeyError:
            raise CheckError(f"no pose for object {name!r}; pass the pose of every instance "
                             "(fixed ones too)") from None
        if not pose.finite:
            # NaN compares False with every tolerance: it would pass every check.
            raise CheckError(f"pose of object {name!r} is not finite ({pose.to_list()}); "
                             "the simulation has failed")
        return pose


@dataclass(frozen=True)
class Verdict:
    """What a relation's check found.

    Attributes:
        placed: Placed object -> its slot, or None where the relation does not
            match objects to slots (``on``, regions).
        problems: Why each unplaced object is not placed, in object order.
    """

    placed: dict[str, int | None]
    problems: list[str]


def upright_tilt_deg(obj: SceneObject, pose: Pose) -> float:
    """Tilt from upright in degrees (0 for spheres, which have no upright; a log's
    axis's slope, however far it has rolled about it)."""
    if obj.kind in SPHERE_KINDS:
        return 0.0
    return tilt_deg(without_roll(pose.quat) if obj.kind == "log" else pose.quat)


def slot_error(obj: SceneObject, pose: Pose, target: Pose, tol: Tolerances,
               check_yaw: bool) -> str:
    """Why ``obj`` is not placed at ``target`` ("" if it is)."""
    dxy = float(np.linalg.norm(pose.pos[:2] - target.pos[:2]))
    if dxy > tol.xy:
        return f"{obj.name}: {dxy * _CM:.1f} cm from target (tolerance {tol.xy * _CM:.1f} cm)"
    dz = float(pose.pos[2] - target.pos[2])
    if abs(dz) > tol.z:
        return (f"{obj.name}: {abs(dz) * _CM:.1f} cm {'above' if dz > 0 else 'below'} its "
                f"target height (tolerance {tol.z * _CM:.1f} cm)")
    tilt = upright_tilt_deg(obj, pose)
    if tilt > MAX_TILT_DEG:
        return f"{obj.name}: tilted {tilt:.0f} deg (at most {MAX_TILT_DEG:.0f} deg)"
    if check_yaw:
        dyaw = yaw_error_deg(pose.yaw, target.yaw, obj.symmetry_deg)
        if dyaw > tol.yaw_deg:
            return (f"{obj.name}: yaw {dyaw:.0f} deg off (tolerance {tol.yaw_deg:.0f} deg, "
                    f"symmetry {obj.symmetry_deg:.0f} deg)")
    return ""


def check_slots(solved: SolvedFactor, scene: CheckScene, tol: Tolerances) -> Verdict:
    """The check of every slot relation: an object is placed in a slot when it is
    within ``xy`` in XY, within ``z`` of its resting height, upright and within
    ``yaw_deg`` modulo its symmetry; objects are matched one per slot
    (``linear_sum_assignment`` over the allowed ``matches``). In a chain (a stack)
    slot k counts only if slot k-1 does."""
    objs = scene.objects
    n, m = len(solved.objects), len(solved.slots)
    ok = np.zeros((n, m), dtype=bool)
    errors: dict[tuple[int, int], str] = {}
    for i, name in enumerate(solved.objects):
        obj, pose = objs[name], scene.pose(name)
        for j in range(m):
            if not solved.matches[i, j] or name in scene.held:
                continue
            err = slot_error(obj, pose, solved.target_pose(obj, j), tol, solved.check_yaw)
            errors[(i, j)] = err
            ok[i, j] = not err
    rows, cols = linear_sum_assignment(-ok.astype(float))
    filled = {int(c): int(r) for r, c in zip(rows, cols, strict=True) if ok[r, c]}
    if solved.chain:  # a column counts from the bottom up, without gaps
        k = 0
        while k in filled:
            k += 1
        filled = {j: i for j, i in filled.items() if j < k}
    slot_of = {i: j for j, i in filled.items()}
    problems = []
    for i, name in enumerate(solved.objects):
        if i in slot_of:
            continue
        if name in scene.held:
            problems.append(f"{name}: held by the robot")
            continue
        allowed = [j for j in range(m) if solved.matches[i, j]]
        free = [j for j in allowed if j not in filled] or allowed
        near = min(free, key=lambda j: float(np.linalg.norm(
            scene.pose(name).pos[:2] - solved.slots[j].pos[:2])))
        problems.append(errors.get((i, near)) or
                        f"{name}: placed but the slot below it in the stack is not filled")
    placed = {solved.objects[i]: j for i, j in sorted(slot_of.items())}
    return Verdict(placed, problems)  # type: ignore[arg-type]


def _summary(n: int, placed: int, problems: list[str]) -> str:
    if placed == n:
        return f"all {n} object(s) placed"
    shown = problems[:MAX_DETAIL_ITEMS]
    more = len(problems) - len(shown)
    text = f"{placed}/{n} placed; " + "; ".join(shown)
    return text + (f"; +{more} more" if more > 0 else "")


def factor_status(solved: SolvedFactor, scene: CheckScene, verdict: Verdict) -> FactorStatus:
    """The :class:`FactorStatus` of a factor from its relation's verdict.

    Placed objects without a slot of their own (``on``, regions) take the nearest
    allowed slot still free, in object order; every object still to place gets a
    free slot by one optimal assignment (distance of its centre to the slot's
    target), so the robot knows where each goes.
    """
    objs = scene.objects
    n_slots = len(solved.slots)
    index = {name: i for i, name in enumerate(solved.objects)}
    taken = {j for j in verdict.placed.values() if j is not None}
    slots: dict[str, int] = {}
    for name, j in verdict.placed.items():
        if j is None:
            i = index[name]
            allowed = [k for k in range(n_slots) if solved.matches[i, k] and k not in taken]
            if not allowed:
                continue
            here = scene.pose(name).pos
            d = [np.linalg.norm(here - solved.target_pose(objs[name], k).pos) for k in allowed]
            j = allowed[int(np.argmin(d))]
            taken.add(j)
        slots[name] = j
    free = tuple(j for j in range(n_slots) if j not in taken)
    todo = [name for name in solved.objects if name not in verdict.placed]
    targets: dict[str, int] = {}
    if todo and free:
        cost = np.full((len(todo), len(free)), _FORBIDDEN)
        for a, name in enumerate(todo):
            i = index[name]
            here = scene.pose(name).pos
            for b, j in enumerate(free):
                if solved.matches[i, j]:
                    cost[a, b] = float(np.linalg.norm(
                        here - solved.target_pose(objs[name], j).pos))
        rows, cols = linear_sum_assignment(cost)
        targets = {todo[r]: free[c] for r, c in zip(rows, cols, strict=True)
                   if cost[r, c] < _FORBIDDEN}
    n = len(solved.objects)
    count = len(verdict.placed)
    return FactorStatus(count / n if n else 1.0, count == n,
                        _summary(n, count, verdict.problems), slots, free, targets)
