"""Goal checks: per-factor progress and success from object poses (pure numpy/scipy).

Every call re-checks every factor from the current poses (nothing latches: a
stack that falls loses its progress). Objects held by the robot never count as
placed. Tolerances come from each relation's ``tolerances``
(:class:`factask.model.tolerances.Tolerances`), never from literals.

* Slot relations (``at_pose``, ``stack``, ``row``, ``circle``, ``aligned``): an
  object is *placed* in a slot when it is within ``xy`` in XY, within ``z`` of
  its resting height, upright, and within ``yaw_deg`` modulo its symmetry; the
  objects are matched one per slot (``linear_sum_assignment`` over the allowed
  ``matches``), progress = placed objects / objects. In a stack slot k counts
  only if slot k-1 does.
* ``on``: the object's centre is over the support's top (or the group of
  supports), its bottom within ``z`` of the support's top, upright.
* Region relations (``in_zone``, ``inside``): at least ``region_fraction`` of the
  object's sample points lie in the region's area; ``inside`` also wants the
  bottom between the floor and the rim.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import linear_sum_assignment

from factask.geometry import Pose, tilt_deg, yaw_error_deg
from factask.model.errors import FactaskError
from factask.model.graph import TaskGraph
from factask.model.tolerances import Tolerances
from factask.sim.layout import SolvedFactor
from factask.sim.objects import (
    SPHERE_KINDS,
    SceneObject,
    bottom_z,
    floor_top_z,
    footprint_points,
    group_area,
    objects_by_name,
    placement_area,
    rest_surface_z,
    top_z,
)

#: An object tilted more than this (degrees) from upright is not placed.
MAX_TILT_DEG = 20.0
#: Problems listed in a factor's detail text at most.
MAX_DETAIL_ITEMS = 3
_CM = 100.0


class CheckError(FactaskError):
    """A check was asked about something it does not know (missing pose or factor)."""


@dataclass(frozen=True)
class FactorStatus:
    """How far one factor is.

    Attributes:
        progress: Fraction of the factor's objects placed, in [0, 1].
        satisfied: Every object placed.
        detail: What is off, e.g. "red_block: 2.3 cm from target (tolerance 1.0 cm)".
    """

    progress: float
    satisfied: bool
    detail: str = ""


@dataclass(frozen=True)
class TaskStatus:
    """How far the whole task is.

    Attributes:
        reward: Weighted sum of factor progress, in [0, 1].
        success: Every factor satisfied at once.
        factors: Factor name -> status.
    """

    reward: float
    success: bool
    factors: dict[str, FactorStatus] = field(default_factory=dict)


def _pose(poses: Mapping[str, Pose], name: str) -> Pose:
    try:
        pose = poses[name]
    except KeyError:
        raise CheckError(f"no pose for object {name!r}; pass the pose of every instance "
                         "(fixed ones too)") from None
    if not pose.finite:
        # NaN compares False with every tolerance: it would pass every check.
        raise CheckError(f"pose of object {name!r} is not finite ({pose.to_list()}); "
                         "the simulation has failed")
    return pose


def _upright(obj: SceneObject, pose: Pose) -> float:
    """Tilt in degrees (0 for spheres, which have no upright)."""
    return 0.0 if obj.kind in SPHERE_KINDS else tilt_deg(pose.quat)


def _slot_error(obj: SceneObject, pose: Pose, target: Pose, tol: Tolerances,
                check_yaw: bool) -> str:
    """Why ``obj`` is not placed at ``target`` ("" if it is)."""
    dxy = float(np.linalg.norm(pose.pos[:2] - target.pos[:2]))
    if dxy > tol.xy:
        return f"{obj.name}: {dxy * _CM:.1f} cm from target (tolerance {tol.xy * _CM:.1f} cm)"
    dz = float(pose.pos[2] - target.pos[2])
    if abs(dz) > tol.z:
        return (f"{obj.name}: {abs(dz) * _CM:.1f} cm {'above' if dz > 0 else 'below'} its "
                f"target height (tolerance {tol.z * _CM:.1f} cm)")
    tilt = _upright(obj, pose)
    if tilt > MAX_TILT_DEG:
        return f"{obj.name}: tilted {tilt:.0f} deg (at most {MAX_TILT_DEG:.0f} deg)"
    if check_yaw:
        dyaw = yaw_error_deg(pose.yaw, target.yaw, obj.symmetry_deg)
        if dyaw > tol.yaw_deg:
            return (f"{obj.name}: yaw {dyaw:.0f} deg off (tolerance {tol.yaw_deg:.0f} deg, "
                    f"symmetry {obj.symmetry_deg:.0f} deg)")
    return ""


def _summary(n: int, placed: int, problems: list[str]) -> str:
    if placed == n:
        return f"all {n} object(s) placed"
    shown = problems[:MAX_DETAIL_ITEMS]
    more = len(problems) - len(shown)
    text = f"{placed}/{n} placed; " + "; ".join(shown)
    return text + (f"; +{more} more" if more > 0 else "")


def _check_slots(solved: SolvedFactor, objs: Mapping[str, SceneObject],
                 poses: Mapping[str, Pose], held: Collection[str],
                 tol: Tolerances) -> FactorStatus:
    n, m = len(solved.objects), len(solved.slots)
    ok = np.zeros((n, m), dtype=bool)
    errors: dict[tuple[int, int], str] = {}
    for i, name in enumerate(solved.objects):
        obj, pose = objs[name], _pose(poses, name)
        for j in range(m):
            if not solved.matches[i, j] or name in held:
                continue
            err = _slot_error(obj, pose, solved.target_pose(obj, j), tol, solved.check_yaw)
            errors[(i, j)] = err
            ok[i, j] = not err
    rows, cols = linear_sum_assignment(-ok.astype(float))
    filled = {int(c): int(r) for r, c in zip(rows, cols, strict=True) if ok[r, c]}
    if solved.chain:  # a column counts from the bottom up, without gaps
        k = 0
        while k in filled:
            k += 1
        filled = {j: i for j, i in filled.items() if j < k}
    placed_objects = set(filled.values())
    problems = []
    for i, name in enumerate(solved.objects):
        if i in placed_objects:
            continue
        if name in held:
            problems.append(f"{name}: held by the robot")
            continue
        allowed = [j for j in range(m) if solved.matches[i, j]]
        free = [j for j in allowed if j not in filled] or allowed
        near = min(free, key=lambda j: float(np.linalg.norm(
            _pose(poses, name).pos[:2] - solved.slots[j].pos[:2])))
        problems.append(errors.get((i, near)) or
                        f"{name}: placed but the slot below it in the stack is not filled")
    placed = len(placed_objects)
    return FactorStatus(placed / n if n else 1.0, placed == n, _summary(n, placed, problems))


def _check_on(solved: SolvedFactor, objs: Mapping[str, SceneObject],
              poses: Mapping[str, Pose], held: Collection[str], tol: Tolerances) -> FactorStatus:
    hosts = solved.support_group
    hobjs = [objs[h] for h in hosts]
    hposes = [_pose(poses, h) for h in hosts]
    area = group_area(hobjs, hposes)
    surface = max(rest_surface_z(o, p) for o, p in zip(hobjs, hposes, strict=True))
    problems = []
    placed = 0
    for name in solved.objects:
        obj, pose = objs[name], _pose(poses, name)
        if name in held:
            problems.append(f"{name}: held by the robot")
        elif not bool(area.contains(pose.pos[None, :2])[0]):
            problems.append(f"{name}: centre not over {'/'.join(hosts)}")
        elif abs(bottom_z(obj, pose) - surface) > tol.z:
            dz = bottom_z(obj, pose) - surface
            problems.append(f"{name}: bottom {abs(dz) * _CM:.1f} cm "
                            f"{'above' if dz > 0 else 'below'} the support's top "
                            f"(tolerance {tol.z * _CM:.1f} cm)")
        elif _upright(obj, pose) > MAX_TILT_DEG:
            problems.append(f"{name}: tilted {_upright(obj, pose):.0f} deg")
        else:
            placed += 1
    n = len(solved.objects)
    return FactorStatus(placed / n, placed == n, _summary(n, placed, problems))


def _check_region(solved: SolvedFactor, objs: Mapping[str, SceneObject],
                  poses: Mapping[str, Pose], held: Collection[str], tol: Tolerances,
                  inside: bool) -> FactorStatus:
    problems = []
    placed = 0
    for name in solved.objects:
        obj, pose = objs[name], _pose(poses, name)
        if name in held:
            problems.append(f"{name}: held by the robot")
            continue
        pts = footprint_points(obj, pose)
        best, why = 0.0, ""
        for region in solved.regions:
            robj, rpose = objs[region], _pose(poses, region)
            frac = float(placement_area(robj, rpose).contains(pts).mean())
            if frac + 1e-12 < tol.region_fraction:
                best = max(best, frac)
                why = why or (f"{name}: {frac:.0%} inside {region} "
                              f"(needs {tol.region_fraction:.0%})")
                continue
            if inside:
                b = bottom_z(obj, pose)
                floor, rim = floor_top_z(robj, rpose), top_z(robj, rpose)
                if b < floor - tol.z or b >= rim:
                    why = (f"{name}: bottom at {b * _CM:.1f} cm, not between {region}'s "
                           f"floor ({floor * _CM:.1f} cm) and rim ({rim * _CM:.1f} cm)")
                    continue
            best = 1.0
            break
        if best >= 1.0:
            placed += 1
        else:
            problems.append(why or f"{name}: not in {'/'.join(solved.regions)}")
    n = len(solved.objects)
    return FactorStatus(placed / n, placed == n, _summary(n, placed, problems))


def check_factor(graph: TaskGraph, solved: SolvedFactor, poses: Mapping[str, Pose],
                 held: Collection[str] = frozenset(),
                 objects: Mapping[str, SceneObject] | None = None) -> FactorStatus:
    """Progress and success of one factor from the current poses.

    Args:
        graph: The task graph (for the relation's tolerances and the objects).
        solved: The factor's solved targets (:func:`factask.sim.layout.solve_targets`).
        poses: Current pose of every instance (fixed ones too).
        held: Instances the robot holds now (never count as placed).
        objects: ``objects_by_name(graph)``, to save rebuilding it each call.

    Returns:
        The factor's :class:`FactorStatus`.

    Raises:
        CheckError: a needed pose is missing.
        GraphValidationError: the factor is not in ``graph``.
    """
    objs = objects if objects is not None else objects_by_name(graph)
    tol = graph.factor(solved.factor).goal.tolerances
    if solved.relation in ("in_zone", "inside"):
        return _check_region(solved, objs, poses, held, tol, solved.relation == "inside")
    if solved.relation == "on":
        return _check_on(solved, objs, poses, held, tol)
    return _check_slots(solved, objs, poses, held, tol)


def check_task(graph: TaskGraph, solved: Mapping[str, SolvedFactor],
               poses: Mapping[str, Pose], held: Collection[str] = frozenset(),
               objects: Mapping[str, SceneObject] | None = None) -> TaskStatus:
    """Reward and success of the whole task (every factor re-checked).

    Args:
        graph: The task graph.
        solved: Factor name -> solved targets, for every factor of ``graph``.
        poses: Current pose of every instance.
        held: Instances the robot holds now.
        objects: ``objects_by_name(graph)`` (optional cache).

    Returns:
        :class:`TaskStatus`: reward = sum of weight x progress; success = all satisfied.

    Raises:
        CheckError: a factor has no solved targets, or a pose is missing.
    """
    objs = objects if objects is not None else objects_by_name(graph)
    statuses: dict[str, FactorStatus] = {}
    reward = 0.0
    for f in graph.factors:
        if f.name not in solved:
            raise CheckError(f"factor {f.name!r} has no solved targets; pass the dict "
                             "solve_targets / reset_layout returns")
        st = check_factor(graph, solved[f.name], poses, held, objs)
        statuses[f.name] = st
        reward += f.weight * st.progress
    success = bool(statuses) and all(s.satisfied for s in statuses.values())
    return TaskStatus(float(min(1.0, max(0.0, reward))), success, statuses)


__all__ = ["MAX_TILT_DEG", "CheckError", "FactorStatus", "TaskStatus", "check_factor",
           "check_task"]
