"""What a CLIPort task's goals say, read faithfully: the goal records and their targets.

* :func:`read_goals` reads ``task.goals`` (GenSim's ``add_goal`` and goals
  appended directly, Ravens' tuple layout) into :class:`RecordedGoal` records;
* :func:`resting_heights` puts every pose target where the object would rest,
  taking the targets in queue order, as the robot places them;
* :func:`target_pose` and :func:`zone_poses` turn targets into factask poses —
  an author's explicit placements are facts;
* :func:`zone_parts` splits a zone goal over several zones by its ``matches``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from scipy.optimize import linear_sum_assignment

from factask.compat.cliport.errors import CliportImportError, Unsupported
from factask.compat.cliport.recorder import RecordedObject, Session
from factask.compat.cliport.transforms import split_pose, yaw_of_xyzw
from factask.model.kinds import kind_spec
from factask.model.tolerances import Z_TOLERANCE
from factask.relations import TargetPose
from factask.scene.objects import floor_thickness

#: Footprints closer than this to merely touching do not support each other, metres.
OVERLAP_SHRINK = 0.002
#: Rounds of pairwise pushes :func:`separate_targets` makes before giving up.
SEPARATE_ROUNDS = 20
#: Gap (m) left between targets it pushes apart (they touch, not overlap).
SEPARATE_GAP = 0.0005
#: Decimals kept of target coordinates (metres, degrees): 1 micrometre.
TARGET_DECIMALS = 6


@dataclass
class RecordedGoal:
    index: int
    objs: list[RecordedObject]
    symmetries: list[float]
    matches: np.ndarray
    targets: list[tuple[np.ndarray, np.ndarray]]
    replace: bool
    rotations: bool
    metric: str
    zones: list[tuple[np.ndarray, np.ndarray, tuple[float, float]]]
    max_reward: float
    language: str



def goal_language(task: Any, index: int, goal: Any) -> str:
    for g, text in getattr(task, "_factask_goal_lang", []):
        if g is goal and text:
            return text
    langs = list(getattr(task, "lang_goals", []) or [])
    if len(langs) == len(task.goals) and langs:
        return str(langs[index])
    if langs:
        return str(langs[min(index, len(langs) - 1)])
    return str(getattr(task, "lang_template", "") or f"goal {index}")


def read_goals(task: Any, session: Session) -> list[RecordedGoal]:
    out = []
    for i, goal in enumerate(task.goals):
        if len(goal) != 8:
            raise CliportImportError(f"goal {i} has {len(goal)} fields; CLIPort goals are "
                                     "(objs, matches, targs, replace, rotations, metric, "
                                     "params, max_reward)")
        objs, matches, targs, replace, rotations, metric, params, max_reward = goal
        objs = list(objs)
        ids, syms = [], []
        for o in objs:
            if isinstance(o, (tuple, list)):
                ids.append(o[0])
                sym = o[1][0] if isinstance(o[1], (tuple, list)) else o[1]
                syms.append(float(sym or 0.0))
            else:
                ids.append(o)
                syms.append(0.0)
        recorded = [session.obj(oid) for oid in ids]
        if len({o.obj_id for o in recorded}) != len(recorded):
            raise CliportImportError(f"goal {i} lists the same object twice")
        targets = []
        for t in list(targs or []):
            try:
                targets.append(split_pose(t))
            except (TypeError, ValueError) as exc:
                raise CliportImportError(f"goal {i}: bad target pose {t!r}: {exc}") from None
        m = np.asarray(matches if matches is not None else np.ones((len(ids), len(targets))),
                       dtype=float)
        if m.ndim == 1 and len(ids) == 1:
            m = m.reshape(1, -1)
        if metric == "pose" and m.ndim == 2 and m.shape[0] == len(ids) \
                and m.shape[1] != len(targets):
            # Ravens only looks at the matrix's columns: extra targets are never matched,
            # extra columns name targets that do not exist.
            session.warn(f"goal {i}: matches has {m.shape[1]} column(s) for {len(targets)} "
                         "target(s); missing columns count as 0, extra ones are ignored")
            fixed = np.zeros((len(ids), len(targets)))
            n = min(m.shape[1], len(targets))
            fixed[:, :n] = m[:, :n]
            m = fixed
        if metric == "pose" and m.shape != (len(ids), len(targets)):
            raise CliportImportError(f"goal {i}: matches is {m.shape}, expected "
                                     f"{(len(ids), len(targets))} (objects x targets)")
        zones = []
        if metric == "zone":
            for zp in _zone_list(params):
                zpos, zquat = split_pose(zp[0])
                zsize = np.asarray(zp[1], dtype=float).reshape(-1)
                zones.append((zpos, zquat, (float(zsize[0]), float(zsize[-1] if len(zsize) == 1
                                                                   else zsize[1]))))
            if not zones:
                raise CliportImportError(f"goal {i}: metric 'zone' needs params "
                                         "[(zone_pose, zone_size)]")
        elif metric != "pose":
            raise Unsupported(f"goal {i}: metric {metric!r} (only 'pose' and 'zone' exist)")
        try:
            max_reward = float(max_reward)
        except (TypeError, ValueError):
            raise CliportImportError(f"goal {i}: step_max_reward must be a number, got "
                                     f"{max_reward!r}") from None
        out.append(RecordedGoal(i, recorded, syms, (m > 0).astype(int), targets, bool(replace),
                         bool(rotations), str(metric), zones, max_reward,
                         goal_language(task, i, goal)))
    return out


def _ring(count: int, objs: list[RecordedObject]) -> float:
    """Radius of a ring of ``count`` copies side by side, each as wide as the widest
    footprint diagonal of ``objs`` (clear of each other at any yaw, as
    :func:`separate_targets` measures them)."""
    width = max(math.hypot(o.size[0], o.size[1]) for o in objs) + 2 * SEPARATE_GAP
    return width / 2 / math.sin(math.pi / count)


def share_targets(goal: RecordedGoal, warn: Any, spread: float = 0.0) -> None:
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
    """
    n, m = len(goal.objs), len(goal.targets)
    if goal.metric != "pose" or not goal.replace or n <= m or m == 0:
        return
    taken = [0] * m
    owner: list[int] = []  # the target each object's copy is of
    for i in range(n):
        allowed = [j for j in range(m) if goal.matches[i, j]]
        j = min(allowed, key=lambda t: (taken[t], t))
        owner.append(j)
        taken[j] += 1
    targets, matches_cols = [], []
    ringed: list[bool] = []  # per shared target: side by side (True) or stacked
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


def _separation(a: tuple[np.ndarray, float, tuple[float, float]],
                b: tuple[np.ndarray, float, tuple[float, float]]) -> np.ndarray | None:
    """The shortest XY move of footprint ``b`` that clears footprint ``a`` (both
    turned rectangles: centre, yaw, half extents), or None if they do not overlap."""
    axes = [np.array([math.cos(y), math.sin(y)]) for _, y, _ in (a, b)]
    axes += [np.array([-v[1], v[0]]) for v in axes]
    gap = b[0] - a[0]
    best: np.ndarray | None = None
    depth = math.inf
    for n in axes:
        reach = 0.0
        for _, yaw, (hx, hy) in (a, b):
            u = np.array([math.cos(yaw), math.sin(yaw)])
            reach += hx * abs(float(u @ n)) + hy * abs(float(u[1] * n[0] - u[0] * n[1]))
        d = float(gap @ n)
        overlap = reach - abs(d)
        if overlap <= 0:
            return None
        if overlap < depth:
            depth, best = overlap, n * overlap * (1.0 if d >= 0 else -1.0)
    return best


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


def _zone_list(params: Any) -> list[Any]:
    """The (zone_pose, zone_size) pairs of a zone goal's params, in either form task
    code writes: GenSim's ``add_goal`` takes ``[(zone_pose, zone_size), ...]``; a goal
    appended to ``self.goals`` directly carries Ravens' ``(object_points, zones)``,
    where ``object_points`` maps object ids to sample points (factask samples its own)."""
    if isinstance(params, (tuple, list)) and len(params) == 2 and isinstance(params[0], dict):
        return list(params[1] or [])
    return list(params or [])



@dataclass
class _Slot:
    key: tuple[int, int]
    x: float
    y: float
    z: float
    half: tuple[float, float]
    height: float
    objects: frozenset[int]  # ids of the objects that may take the target
    certain: bool  # every target of its goal gets an object (not a choice among them)
    # Height of the floor above the slot's bottom when what goes there is a
    # receptacle (a container moved into a zone): what is put in it rests inside.
    floor: float | None = None


def _half_xy(size: tuple[float, float, float], yaw: float) -> tuple[float, float]:
    """Half extents of the axis-aligned box around a footprint turned by ``yaw``."""
    c, s = abs(math.cos(yaw)), abs(math.sin(yaw))
    hx, hy = size[0] / 2, size[1] / 2
    return c * hx + s * hy, s * hx + c * hy


def _overlap(ax: float, ay: float, ah: tuple[float, float], bx: float, by: float,
             bh: tuple[float, float]) -> bool:
    return (abs(ax - bx) < ah[0] + bh[0] - OVERLAP_SHRINK
            and abs(ay - by) < ah[1] + bh[1] - OVERLAP_SHRINK)


def resting_heights(goals: list[RecordedGoal], objects: list[RecordedObject],
                    moved: set[int]) -> dict[tuple[int, int], float]:
    """Physical centre height of every pose target, from what would lie under it.

    Ravens ignores target z, so task code often gets it wrong (e.g. 5 cm layers for
    4 cm blocks); factask checks heights. A target's height is recomputed as the top
    of what supports it (the table, a fixed object, or a lower target) plus half
    the height of the objects that may go there, taking the targets in queue order.
    A target whose objects a later goal moves again stops supporting anything
    from that goal on (a towers-of-hanoi disk leaves its peg), and the targets of a
    goal with more targets than objects (a choice) support nothing.

    Returns:
        (goal index, target index) -> centre z, metres.
    """
    slots: list[_Slot] = []
    for g in goals:
        if not g.objs or (g.metric != "pose" and len(g.targets) < len(g.objs)):
            continue  # a zone goal's targets count only as per-object placements
        for j, (pos, quat) in enumerate(g.targets):
            allowed = [o for i, o in enumerate(g.objs) if g.matches[i, j]]
            if not allowed:
                continue
            yaw = yaw_of_xyzw(quat)
            size = max((o.size for o in allowed), key=lambda s: s[2])
            receptacle = all(kind_spec(o.kind).receptacle for o in allowed)
            slots.append(_Slot((g.index, j), float(pos[0]), float(pos[1]), float(pos[2]),
                               _half_xy(size, yaw), size[2],
                               frozenset(o.obj_id for o in allowed),
                               len(g.objs) >= len(g.targets),
                               max(floor_thickness(o.kind) for o in allowed)
                               if receptacle else None))
    fixed = []
    for o in objects:
        spec = kind_spec(o.kind)
        if o.obj_id in moved or not spec.collides:
            continue
        bottom = float(o.pos[2]) - o.size[2] / 2
        top = bottom + (floor_thickness(o.kind) if spec.receptacle else o.size[2])
        # A target is on it when above its top as the author placed it (a pallet
        # factask builds taller than the author's size hint still carries the row
        # the author put 3.5 cm up, and every layer stacked on that row).
        placed = top if o.placed_top is None else o.placed_top
        fixed.append((float(o.pos[0]), float(o.pos[1]), _half_xy(o.size, yaw_of_xyzw(o.quat)),
                      top, placed, spec.receptacle))
    out: dict[tuple[int, int], float] = {}
    done: list[tuple[_Slot, float]] = []
    # In queue order (then the author's z within a goal), as the robot places them:
    # a target rests on what is under it when it is placed — a fixed object, or a
    # target placed before it (at the same author z too: Ravens ignores z, so towers
    # whose every target is the rod's base point still stack).
    goal_objects = {g.index: {o.obj_id for o in g.objs} for g in goals}
    for slot in sorted(slots, key=lambda s: (s.key[0], s.z)):
        # Earlier targets whose objects this goal moves again are vacated.
        done = [(other, z) for other, z in done if other.key[0] == slot.key[0]
                or not other.objects <= goal_objects[slot.key[0]]]
        support, on_floor = 0.0, True
        for fx, fy, fh, top, placed, receptacle in fixed:
            if (placed <= slot.z and _overlap(slot.x, slot.y, slot.half, fx, fy, fh)
                    and top > support):
                support, on_floor = top, receptacle
        for other, z in done:
            if not other.certain:
                # A goal with more targets than objects fills the ones the robot
                # picks at run time (each red block into either red container):
                # none of its targets is known to carry anything.
                continue
            # A target rests on one the author put lower, where they overlap. At the
            # same author z, a target of an earlier goal is already placed when this
            # one is: it supports this one if it stands right under its centre (a
            # tower sent to one point); neighbours (kit holes, a row) do not stack.
            if other.z < slot.z - OVERLAP_SHRINK:
                below = _overlap(slot.x, slot.y, slot.half, other.x, other.y, other.half)
            else:
                below = (other.key[0] < slot.key[0] and other.z <= slot.z + Z_TOLERANCE
                         and abs(slot.x - other.x) < other.half[0]
                         and abs(slot.y - other.y) < other.half[1])
            if not below:
                continue
            if other.floor is not None:
                # Put into a receptacle that was moved there: on its floor, where
                # the checker finds it (as for a fixed receptacle).
                floor = z - other.height / 2 + other.floor
                if floor > support:
                    support, on_floor = floor, True
            elif z + other.height / 2 > support:
                support, on_floor = z + other.height / 2, False
        z_rest = support + slot.height / 2
        # A target on the table or on a receptacle's floor is reported as resting on
        # the table: its height is left to the checker, which finds the floor (and
        # no explicit z makes a tight fit in a container collide with its wall).
        # What stands on it is measured from where it really rests.
        out[slot.key] = slot.height / 2 if on_floor else z_rest
        done.append((slot, z_rest))
    return out


def target_pose(pos: np.ndarray, quat: np.ndarray, height: float, z_rest: float | None,
            where: str, warn: Any) -> TargetPose:
    z = float(pos[2]) if z_rest is None else z_rest
    if z_rest is not None and abs(float(pos[2]) - z_rest) > Z_TOLERANCE:
        warn(f"{where}: target z {float(pos[2]):.4f} m is not where the object would rest; "
             f"using {z_rest:.4f} m (Ravens ignores z, factask checks it)")
    # "Resting on the table" is left to the checker; a target on something keeps its height.
    keep_z = z > height / 2 + Z_TOLERANCE if z_rest is None else z_rest > height / 2 + 1e-6
    # Round away utils.apply's float32 noise (a 1 cm gap must stay 1 cm).
    return TargetPose(x=round(float(pos[0]), TARGET_DECIMALS),
                      y=round(float(pos[1]), TARGET_DECIMALS),
                      z=round(z, TARGET_DECIMALS) if keep_z else None,
                      yaw_deg=round(math.degrees(yaw_of_xyzw(quat)), TARGET_DECIMALS))


def zone_poses(goal: RecordedGoal, rest: dict[tuple[int, int], float]
               ) -> list[TargetPose] | None:
    """The author's own place for each object inside the zone (e.g. a packing plan):
    when the goal gives every object a target of its own (within ``matches``) whose
    centre lies in the zone, those targets are facts; otherwise None (factask packs).
    A target that rests on something other than the table or a receptacle's floor
    (a second layer on a pallet) keeps its resting height from ``rest``
    (:func:`resting_heights`)."""
    n = len(goal.objs)
    if len(goal.targets) < n or goal.matches.shape != (n, len(goal.targets)):
        return None
    rows, cols = linear_sum_assignment(-goal.matches.astype(float))
    if len(rows) < n or not all(goal.matches[r, c] for r, c in zip(rows, cols, strict=True)):
        return None
    zpos, zquat, (sx, sy) = goal.zones[0]
    zyaw = yaw_of_xyzw(zquat)
    c, s = math.cos(zyaw), math.sin(zyaw)
    poses = []
    for r in np.argsort(rows):
        pos, quat = goal.targets[int(cols[r])]
        dx, dy = float(pos[0] - zpos[0]), float(pos[1] - zpos[1])
        if abs(c * dx + s * dy) > sx / 2 or abs(-s * dx + c * dy) > sy / 2:
            return None
        j = int(cols[r])
        z = rest.get((goal.index, j))
        height = goal.objs[int(rows[r])].size[2]
        poses.append(TargetPose(x=round(float(pos[0]), TARGET_DECIMALS),
                                y=round(float(pos[1]), TARGET_DECIMALS),
                                z=round(z, TARGET_DECIMALS) if z is not None
                                and z > height / 2 + Z_TOLERANCE else None,
                                yaw_deg=round(math.degrees(yaw_of_xyzw(quat)), TARGET_DECIMALS)))
    return poses


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
