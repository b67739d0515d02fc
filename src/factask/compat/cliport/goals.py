"""What a CLIPort task's goals say, read faithfully: the goal records and their targets.

* :func:`read_goals` reads ``task.goals`` (GenSim's ``add_goal`` and goals
  appended directly, Ravens' tuple layout) into :class:`RecordedGoal` records;
* :func:`resting_heights` puts every pose target where the object would rest,
  taking the targets in queue order, as the robot places them;
* :func:`target_pose` and :func:`zone_poses` turn targets into factask poses —
  an author's explicit placements are facts.

Targets several objects share or crowd are made one per object in
:mod:`factask.compat.cliport.sharing`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import linear_sum_assignment

from factask.compat.cliport.errors import CliportImportError, Unsupported
from factask.compat.cliport.recorder import RecordedObject, Session
from factask.compat.cliport.transforms import (
    footprint_separation,
    split_pose,
    xyzw_to_wxyz,
    yaw_of_xyzw,
)
from factask.geometry import tilt_deg
from factask.relations import TargetPose
from factask.scene.objects import floor_thickness
from factask.vocabulary.kinds import WALL_THICKNESS, kind_spec
from factask.vocabulary.tolerances import Z_TOLERANCE

#: Footprints closer than this to merely touching do not support each other, metres.
OVERLAP_SHRINK = 0.002
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
        if m.ndim == 2 and m.shape[0] > len(ids):
            # Ravens reads row i for object i only: rows past the objects (a matrix
            # written for the objects a short symmetries list dropped) are never read.
            session.warn(f"goal {i}: matches has {m.shape[0]} row(s) for {len(ids)} "
                         "object(s); the extra rows are ignored, as Ravens ignores them")
            m = m[:len(ids)]
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


def _zone_list(params: Any) -> list[Any]:
    """The (zone_pose, zone_size) pairs of a zone goal's params, in either form task
    code writes: GenSim's ``add_goal`` takes ``[(zone_pose, zone_size), ...]``; a goal
    appended to ``self.goals`` directly carries Ravens' ``(object_points, zones)``,
    where ``object_points`` maps object ids to sample points (factask samples its own)."""
    if isinstance(params, (tuple, list)) and len(params) == 2 and isinstance(params[0], dict):
        return list(params[1] or [])
    return list(params or [])



@dataclass(frozen=True)
class _Foot:
    """A footprint as the author turned it: centre, yaw, half extents; a round one
    (ball, cylinder, bowl) is a disc whose radius is ``half[0]``."""

    x: float
    y: float
    yaw: float
    half: tuple[float, float]
    round: bool


def _foot(x: float, y: float, size: tuple[float, float, float], yaw: float,
          kind: str) -> _Foot:
    return _Foot(x, y, yaw, (size[0] / 2, size[1] / 2), kind_spec(kind).round)


@dataclass
class _Slot:
    key: tuple[int, int]
    x: float
    y: float
    z: float
    foot: _Foot
    height: float
    objects: frozenset[int]  # ids of the objects that may take the target
    certain: bool  # every target of its goal gets an object (not a choice among them)
    # Height of the floor above the slot's bottom when what goes there is a
    # receptacle (a container moved into a zone): what is put in it rests inside.
    floor: float | None = None


def half_xy(size: tuple[float, float, float], yaw: float) -> tuple[float, float]:
    """Half extents of the axis-aligned box around a footprint turned by ``yaw``."""
    c, s = abs(math.cos(yaw)), abs(math.sin(yaw))
    hx, hy = size[0] / 2, size[1] / 2
    return c * hx + s * hy, s * hx + c * hy


def _overlap(a: _Foot, b: _Foot) -> bool:
    """Whether two footprints overlap by more than ``OVERLAP_SHRINK``, turned as the
    author turned them (not the boxes around them: a sphere between two blocks of a
    row turned 45 degrees is not on either block)."""
    if a.round and b.round:
        return math.hypot(a.x - b.x, a.y - b.y) < a.half[0] + b.half[0] - OVERLAP_SHRINK
    # A disc against a rectangle: the square around the disc, square to the rectangle.
    ya = b.yaw if a.round else a.yaw
    yb = a.yaw if b.round else b.yaw
    move = footprint_separation((np.array([a.x, a.y]), ya, a.half),
                                (np.array([b.x, b.y]), yb, b.half))
    return move is not None and float(np.linalg.norm(move)) > OVERLAP_SHRINK


def _on_rim(slot: _Slot, host: _Foot, rim: float) -> bool:
    """Whether what goes to ``slot`` is too wide to go between the walls of receptacle
    ``host`` (turned as the author turned both) and the author put it at the rim's
    height or above: it rests on the walls, not on the floor."""
    if slot.z - slot.height / 2 < rim - Z_TOLERANCE:
        return False
    if slot.foot.round:
        half = (slot.foot.half[0], slot.foot.half[0])
    else:
        size = (2 * slot.foot.half[0], 2 * slot.foot.half[1], slot.height)
        half = half_xy(size, slot.foot.yaw - host.yaw)
    room = (host.half[0] - WALL_THICKNESS, host.half[1] - WALL_THICKNESS)
    if host.round:
        return math.hypot(*half) > room[0] if not slot.foot.round else half[0] > room[0]
    return half[0] > room[0] or half[1] > room[1]


def _centre_on(a: _Foot, b: _Foot) -> bool:
    """Whether ``a``'s centre lies strictly inside footprint ``b``."""
    dx, dy = a.x - b.x, a.y - b.y
    if b.round:
        return math.hypot(dx, dy) < b.half[0]
    c, s = math.cos(b.yaw), math.sin(b.yaw)
    return abs(c * dx + s * dy) < b.half[0] and abs(-s * dx + c * dy) < b.half[1]


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
            tallest = max(allowed, key=lambda o: o.size[2])
            size = tallest.size
            receptacle = all(kind_spec(o.kind).receptacle for o in allowed)
            slots.append(_Slot((g.index, j), float(pos[0]), float(pos[1]), float(pos[2]),
                               _foot(float(pos[0]), float(pos[1]), size, yaw, tallest.kind),
                               size[2],
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
        rim = bottom + o.size[2] if spec.receptacle else None
        fixed.append((_foot(float(o.pos[0]), float(o.pos[1]), o.size, yaw_of_xyzw(o.quat),
                            o.kind), top, placed, rim))
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
        for foot, top, placed, rim in fixed:
            if not _overlap(slot.foot, foot):
                continue
            if placed > slot.z:
                if rim is None and _centre_on(slot.foot, foot) and top > support:
                    # Ravens ignores z: a target whose centre is over a fixed object
                    # the author put it into (a box sent to the pallet's own pose) lands
                    # on it. Its height stays the checker's to find (resting on what is
                    # under it); what is stacked on it later stands on its top.
                    support = top
                continue
            if rim is not None and _on_rim(slot, foot, rim):
                # Too wide to go in, put at its rim: it rests on the walls (a lid).
                if rim > support:
                    support, on_floor = rim, False
            elif top > support:
                support, on_floor = top, rim is not None
        for other, z in done:
            if not other.certain:
                # A goal with more targets than objects fills the ones the robot
                # picks at run time (each red block into either red container):
                # none of its targets is known to carry anything.
                continue
            # A target rests on one the author put lower, where they overlap. At the
            # same author z, a target of an earlier goal is already placed when this
            # one is, and Ravens lets the robot put the object down wherever it lands:
            # on that object where they overlap (a tower sent to one point; boxes sent
            # one by one to the pallet's centre, or closer than they are wide). Targets
            # of one goal side by side (kit holes, a row) do not stack; overlaps of a
            # few millimetres were pushed apart before (sharing.separate_targets).
            if other.z < slot.z - OVERLAP_SHRINK:
                below = _overlap(slot.foot, other.foot)
            else:
                below = (other.key[0] < slot.key[0] and other.z <= slot.z + Z_TOLERANCE
                         and _overlap(slot.foot, other.foot))
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


#: A target tilted more than this (degrees) off upright, or off upside down, is
#: placed upright (with a warning): factask's objects stand upright.
TARGET_TILT_WARN_DEG = 5.0


def target_pose(pos: np.ndarray, quat: np.ndarray, height: float, z_rest: float | None,
            where: str, warn: Any) -> TargetPose:
    tilt = tilt_deg(xyzw_to_wxyz(quat))
    if TARGET_TILT_WARN_DEG < tilt < 180.0 - TARGET_TILT_WARN_DEG:
        warn(f"{where}: the target is tilted {tilt:.0f} degrees; factask places objects "
             "upright, so only its yaw is kept (an object laid on its side stands)")
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


def _in_zone_pose(pos: np.ndarray, quat: np.ndarray, height: float, z: float | None,
                  zone: tuple[np.ndarray, np.ndarray, tuple[float, float]]
                  ) -> TargetPose | None:
    """The factask pose of a target whose centre lies in ``zone``, else None. A
    target resting on something other than the table or a receptacle's floor keeps
    its resting height ``z``."""
    zpos, zquat, (sx, sy) = zone
    zyaw = yaw_of_xyzw(zquat)
    c, s = math.cos(zyaw), math.sin(zyaw)
    dx, dy = float(pos[0] - zpos[0]), float(pos[1] - zpos[1])
    if abs(c * dx + s * dy) > sx / 2 or abs(-s * dx + c * dy) > sy / 2:
        return None
    return TargetPose(x=round(float(pos[0]), TARGET_DECIMALS),
                      y=round(float(pos[1]), TARGET_DECIMALS),
                      z=round(z, TARGET_DECIMALS) if z is not None
                      and z > height / 2 + Z_TOLERANCE else None,
                      yaw_deg=round(math.degrees(yaw_of_xyzw(quat)), TARGET_DECIMALS))


def zone_poses(goal: RecordedGoal, rest: dict[tuple[int, int], float],
               earlier: list[RecordedGoal] | None = None) -> list[TargetPose] | None:
    """The author's own place for each object inside the zone (e.g. a packing plan):
    when the goal gives every object a target of its own (within ``matches``) whose
    centre lies in the zone, those targets are facts; otherwise None (factask packs).
    A target that rests on something other than the table or a receptacle's floor
    (a second layer on a pallet) keeps its resting height from ``rest``
    (:func:`resting_heights`).

    Failing that, when ``earlier`` goals (those queued before this one) already put
    every object at a target of its own inside the zone (one pose goal per block
    into the container, then "all blocks are in the container"), those targets are
    the places: Ravens finds the zone goal met when it reaches it.
    """
    n = len(goal.objs)
    if len(goal.targets) >= n and goal.matches.shape == (n, len(goal.targets)):
        rows, cols = linear_sum_assignment(-goal.matches.astype(float))
        if len(rows) == n and all(goal.matches[r, c] for r, c in zip(rows, cols, strict=True)):
            poses = [_in_zone_pose(*goal.targets[int(cols[r])], goal.objs[int(rows[r])].size[2],
                                   rest.get((goal.index, int(cols[r]))), goal.zones[0])
                     for r in np.argsort(rows)]
            if all(p is not None for p in poses):
                return poses  # type: ignore[return-value]
    return _earlier_places(goal, earlier or [], rest)


def _earlier_places(goal: RecordedGoal, earlier: list[RecordedGoal],
                    rest: dict[tuple[int, int], float]) -> list[TargetPose] | None:
    """Each object's place in the zone from the last earlier pose goal that gives it
    exactly one target, or None unless every object has one inside the zone."""
    poses = []
    for o in goal.objs:
        place = None
        for g in reversed(earlier):
            ids = [x.obj_id for x in g.objs]
            if g.metric != "pose" or o.obj_id not in ids:
                continue
            row = g.matches[ids.index(o.obj_id)]
            allowed = np.flatnonzero(row[:len(g.targets)])
            if len(allowed) == 1:
                j = int(allowed[0])
                place = _in_zone_pose(*g.targets[j], o.size[2], rest.get((g.index, j)),
                                      goal.zones[0])
            break
        if place is None:
            return None
        poses.append(place)
    return poses
