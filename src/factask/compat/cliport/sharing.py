"""Targets several objects share or crowd, made one per object.

* :func:`share_targets`: objects of a pose goal sharing targets (``replace=True``)
  get copies of their own, stacked or side by side;
* :func:`separate_targets`: targets overlapping by a little are pushed apart;
* :func:`zone_parts`: a zone goal over several zones splits by its ``matches``.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from factask.compat.cliport.goals import RecordedGoal
from factask.compat.cliport.recorder import RecordedObject
from factask.compat.cliport.transforms import footprint_separation as _separation
from factask.compat.cliport.transforms import yaw_of_xyzw
from factask.vocabulary.kinds import kind_spec
from factask.vocabulary.tolerances import Z_TOLERANCE

#: Rounds of pairwise pushes :func:`separate_targets` makes before giving up.
SEPARATE_ROUNDS = 20
#: Gap (m) left between targets it pushes apart (they touch, not overlap).
SEPARATE_GAP = 0.0005


def _ring(count: int, objs: list[RecordedObject]) -> float:
    """Radius of a ring of ``count`` copies side by side, each as wide as the widest
    footprint diagonal of ``objs`` (clear of each other at any yaw, as
    :func:`separate_targets` measures them)."""
    width = max(math.hypot(o.size[0], o.size[1]) for o in objs) + 2 * SEPARATE_GAP
    return width / 2 / math.sin(math.pi / count)


def share_targets(goal: RecordedGoal, warn: Any, spread: float = 0.0) -> float | None:
    """Give each object of a pose goal that shares its targets (``replace=True``, more
    objects than targets) a copy of a target of its own: copies at one point stacked,
    or side by side around it when the objects cannot carry one another.

    Ravens lets any number of objects match one target when ``replace`` is set and
    checks XY only: "all blocks in the bowl" as ``matches = ones((n, 1))`` to the
    bowl's pose is met by a stack at the bowl's centre, which is what its oracle
    builds. factask checks every object against a target of its own, with heights: the
    objects are spread over the targets each may take (as evenly as ``matches``
    allows), and the k-th copy at a target is put one object height above the one
    before, so :func:`resting_heights` stacks them. Objects that are no support (balls:
    a ball on a ball does not stay) are put in a ring around the target instead, each
    touching its neighbours, when the ring's radius is within ``spread`` (the author's
    ``pos_eps`` less a margin: every copy stays within the author's tolerance of the
    target, so Ravens' XY check holds too); otherwise they are stacked as before.

    Returns:
        The distance (m) between neighbouring copies side by side, the smallest over
        the goal's rings, or None when no copies are side by side. A position
        tolerance of half that tells the copies apart: with a wider one (a bowl's
        5 cm for 3 cm balls 4.3 cm apart) one ball is within tolerance of both copies,
        and the oracle took the copy it stands on for free and put the next ball on it.
    """
    n, m = len(goal.objs), len(goal.targets)
    if goal.metric != "pose" or not goal.replace or n <= m or m == 0:
        return None
    taken = [0] * m
    owner: list[int] = []  # the target each object's copy is of
    for i in range(n):
        allowed = [j for j in range(m) if goal.matches[i, j]]
        j = min(allowed, key=lambda t: (taken[t], t))
        owner.append(j)
        taken[j] += 1
    targets, matches_cols = [], []
    ringed: list[bool] = []  # per shared target: side by side (True) or stacked
    spacing: float | None = None
    for j, (pos, quat) in enumerate(goal.targets):
        allowed = [o for i, o in enumerate(goal.objs) if goal.matches[i, j]]
        height = max((o.size[2] for o in allowed), default=0.0)
        k_all = taken[j]
        ring = (_ring(k_all, allowed) if k_all > 1 and allowed
                and not any(kind_spec(o.kind).support for o in allowed) else math.inf)
        for k in range(k_all):
            if ring <= spread:
                angle = 2 * math.pi * k / k_all
                offset = np.array([ring * math.cos(angle), ring * math.sin(angle), 0.0])
            else:
                offset = np.array([0.0, 0.0, k * height])
            targets.append((np.asarray(pos, dtype=float) + offset, np.asarray(quat, dtype=float)))
            matches_cols.append(goal.matches[:, j])
        if k_all > 1:
            ringed.append(ring <= spread)
            if ring <= spread:
                gap = 2 * ring * math.sin(math.pi / k_all)
                spacing = gap if spacing is None else min(spacing, gap)
    goal.targets = targets
    goal.matches = np.stack(matches_cols, axis=1).astype(int)
    stacked = "/".join(str(t) for t, r in zip([t for t in taken if t > 1], ringed,
                                               strict=True) if not r)
    side = "/".join(str(t) for t, r in zip([t for t in taken if t > 1], ringed,
                                            strict=True) if r)
    how = ", ".join(([f"{stacked} stacked at one point"] if stacked else [])
                    + ([f"{side} side by side around one point (they cannot carry "
                        "one another)"] if side else []))
    warn(f"goal {goal.index}: {n} objects share {m} target pose(s) (replace=True; Ravens "
         f"checks XY only): each gets a copy of one, {how}")
    return spacing


def separate_targets(goals: list[RecordedGoal], limit: float) -> dict[int, float]:
    """Push apart pose targets whose footprints overlap by a little, each by at most
    ``limit``; returns goal index -> the largest move of its targets (m).

    Authors space targets by hand and Ravens checks them within ``pos_eps`` (1 cm):
    a row spaced 3.5 cm for 4 cm blocks is met by blocks that touch, each a few mm
    off its target. factask's targets are where the oracle puts the objects, so
    targets that overlap by less than twice ``limit`` are moved apart until they
    touch (the caller tightens the goal's tolerance by the move, so the check stays
    at least as strict as the author's). Deeper overlaps (a tower sent to one point,
    objects stacked) are the author's layout and stay. Targets at different heights
    do not meet; the targets of a goal with more targets than objects (a choice) are
    left alone.
    """
    slots: list[tuple[int, int, float, float, tuple[float, float]]] = []
    centres: list[np.ndarray] = []
    for g in goals:
        if g.metric != "pose" or len(g.objs) < len(g.targets):
            continue
        for j, (pos, _) in enumerate(g.targets):
            allowed = [o for i, o in enumerate(g.objs) if g.matches[i, j]]
            if not allowed:
                continue
            sx = max(o.size[0] for o in allowed)
            sy = max(o.size[1] for o in allowed)
            sz = max(o.size[2] for o in allowed)
            slots.append((g.index, j, float(pos[2]) - sz / 2, float(pos[2]) + sz / 2,
                          (sx / 2, sy / 2)))
            centres.append(np.array(pos[:2], dtype=float))
    if len(slots) < 2:
        return {}
    by_index = {g.index: g for g in goals}
    start = [c.copy() for c in centres]
    yaws = [yaw_of_xyzw(by_index[gi].targets[j][1]) for gi, j, *_ in slots]
    # Pairs in one layer (one above the other never meet).
    pairs = [(a, b) for a in range(len(slots)) for b in range(a + 1, len(slots))
             if min(slots[a][3], slots[b][3]) - max(slots[a][2], slots[b][2]) > Z_TOLERANCE]

    def push(a: int, b: int) -> np.ndarray | None:
        return _separation((centres[a], yaws[a], slots[a][4]), (centres[b], yaws[b], slots[b][4]))

    deep = {(a, b) for a, b in pairs
            if (p := push(a, b)) is not None and float(np.linalg.norm(p)) > 2 * limit}
    pairs = [pair for pair in pairs if pair not in deep]  # the author's own layout
    for _ in range(SEPARATE_ROUNDS):
        moved = False
        for a, b in pairs:
            move = push(a, b)
            if move is None:
                continue
            half = move / 2 * (1 + SEPARATE_GAP / max(float(np.linalg.norm(move)), 1e-9))
            centres[a] -= half
            centres[b] += half
            moved = True
        if not moved:
            break
    shifts = [float(np.linalg.norm(c - c0)) for c, c0 in zip(centres, start, strict=True)]
    if (not any(shifts) or max(shifts) > limit
            or any(push(a, b) is not None for a, b in pairs)):
        return {}  # nothing to do, or no way within the author's tolerance
    out: dict[int, float] = {}
    for (gi, j, *_), c, shift in zip(slots, centres, shifts, strict=True):
        if shift > 0:
            pos, quat = by_index[gi].targets[j]
            moved_pos = np.array(pos, dtype=float)
            moved_pos[:2] = c
            by_index[gi].targets[j] = (moved_pos, quat)
            out[gi] = max(out.get(gi, 0.0), shift)
    return out


def _centre_in(pos: np.ndarray, zone: tuple[np.ndarray, np.ndarray, tuple[float, float]]
               ) -> bool:
    zpos, zquat, (sx, sy) = zone
    zyaw = yaw_of_xyzw(zquat)
    dx, dy = float(pos[0] - zpos[0]), float(pos[1] - zpos[1])
    c, s = math.cos(zyaw), math.sin(zyaw)
    return abs(c * dx + s * dy) <= sx / 2 and abs(-s * dx + c * dy) <= sy / 2


def zone_parts(goal: RecordedGoal, warn: Any) -> list[RecordedGoal]:
    """A zone goal over several zones as one goal per zone, each object in the zone
    its ``matches`` sends it to (sort the blocks into the zones by colour).

    An object's zones are those holding the centre of a target its row of
    ``matches`` allows (authors pass the zone poses themselves as targets, or
    places inside them). Ravens' own zone metric counts an object in *any* of the
    zones (and, summing over zones, never reaches the goal's reward with more than
    one); the author's matrix is the meaning. An object allowed several zones (or
    none that a target shows) is given the least loaded of them, with a warning:
    factask checks one zone per object. A goal with one zone is returned as is.
    The parts share the goal's index and targets; their rewards split the goal's
    by their number of objects.
    """
    if len(goal.zones) < 2:
        return [goal]
    n, m = len(goal.objs), goal.matches
    everywhere = list(range(len(goal.zones)))
    allowed = []
    for i in range(n):
        ks: set[int] = set()
        if m.ndim == 2 and m.shape[0] == n:
            for j, (pos, _) in enumerate(goal.targets[:m.shape[1]]):
                if m[i, j]:
                    ks |= {k for k, zone in enumerate(goal.zones) if _centre_in(pos, zone)}
        allowed.append(sorted(ks) or everywhere)
    load = [0] * len(goal.zones)
    assigned = []
    for ks in allowed:
        k = min(ks, key=lambda k: (load[k], k))
        load[k] += 1
        assigned.append(k)
    chosen = sum(len(ks) > 1 for ks in allowed)
    if chosen:
        warn(f"goal {goal.index}: {chosen} object(s) may go to any of several of its "
             f"{len(goal.zones)} zones; each is given one (the least loaded), which "
             "factask checks")
    parts = []
    for k, zone in enumerate(goal.zones):
        rows = [i for i, a in enumerate(assigned) if a == k]
        if rows:
            parts.append(replace(
                goal, objs=[goal.objs[i] for i in rows],
                symmetries=[goal.symmetries[i] for i in rows],
                matches=m[rows, :] if m.ndim == 2 and m.shape[0] == n else m,
                zones=[zone], max_reward=goal.max_reward * len(rows) / n))
    return parts
