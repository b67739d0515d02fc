"""Start poses a task's author gave by hand that factask cannot take as they are.

* :func:`fits_inside`: whether an object fits between a receptacle's walls (a
  container as wide as the one under it rests on that one's rim: "the containers
  start stacked");
* :func:`separate_starts`: hand-placed objects on the table whose footprints
  overlap by a little are pushed apart until they touch, as PyBullet pushes them
  apart at its first step (a row of 4 cm blocks put 3.5 cm apart).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from factask.compat.cliport.goals import half_xy
from factask.compat.cliport.recorder import RecordedObject
from factask.compat.cliport.sharing import SEPARATE_GAP, SEPARATE_ROUNDS, _separation
from factask.compat.cliport.transforms import yaw_of_xyzw
from factask.model.kinds import WALL_THICKNESS, kind_spec

#: Farthest (m) one hand-placed start is moved off the objects it overlaps. Deeper
#: overlaps are not a nudge PyBullet would make quietly: they are left as given.
START_NUDGE = 0.02


def _half_extents(o: RecordedObject, yaw: float) -> np.ndarray:
    """Half extents (x, y) of the box around ``o``'s footprint in a frame at ``yaw``."""
    return np.array(half_xy(o.size, yaw_of_xyzw(o.quat) - yaw))


def fits_inside(o: RecordedObject, host: RecordedObject) -> bool:
    """Whether ``o``'s footprint, turned as the author turned it, fits between the
    walls of receptacle ``host`` (its size less a wall each side)."""
    room = np.array(host.size[:2], dtype=float) / 2 - WALL_THICKNESS
    return bool(np.all(_half_extents(o, yaw_of_xyzw(host.quat)) <= room))


def _footprint(o: RecordedObject) -> tuple[np.ndarray, float, tuple[float, float]]:
    return (np.array(o.pos[:2], dtype=float), yaw_of_xyzw(o.quat),
            (o.size[0] / 2, o.size[1] / 2))


def separate_starts(objects: list[RecordedObject], movable: set[int], names: dict[int, str],
                    warn: Any, limit: float = START_NUDGE) -> None:
    """Push apart hand-placed objects on the table whose footprints overlap by a little.

    ``objects`` are the objects factask starts at the author's pose on the table;
    ``movable`` the ids among them that may move (a fixed body stays where it was
    put, and two fixed bodies may interpenetrate). Authors place rows by hand and
    PyBullet separates what overlaps at its first step; factask refuses an overlap
    at a given pose. Each movable object is moved (in place, with a warning) at most
    ``limit``; when that does not clear every overlap, nothing is moved.
    """
    solid = [o for o in objects if kind_spec(o.kind).collides]
    pairs = [(a, b) for i, a in enumerate(solid) for b in solid[i + 1:]
             if (a.obj_id in movable or b.obj_id in movable)
             and _separation(_footprint(a), _footprint(b)) is not None]
    if not pairs:
        return
    start = {o.obj_id: np.array(o.pos, dtype=float) for o in solid}
    for _ in range(SEPARATE_ROUNDS):
        pushed = False
        for a, b in pairs:
            move = _separation(_footprint(a), _footprint(b))
            if move is None:
                continue
            move = move * (1 + 2 * SEPARATE_GAP / max(float(np.linalg.norm(move)), 1e-9))
            share_a = 0.5 if b.obj_id in movable else 1.0
            if a.obj_id not in movable:
                share_a = 0.0
            a.pos[:2] = a.pos[:2] - share_a * move
            b.pos[:2] = b.pos[:2] + (1.0 - share_a) * move
            pushed = True
        if not pushed:
            break
    shifts = {o.obj_id: float(np.linalg.norm(o.pos[:2] - start[o.obj_id][:2])) for o in solid}
    left = any(_separation(_footprint(a), _footprint(b)) is not None for a, b in pairs)
    if left or max(shifts.values()) > limit:
        for o in solid:
            o.pos = start[o.obj_id]
        return
    touched = sorted({names[o.obj_id] for pair in pairs for o in pair})
    most = max(shifts.values())
    warn(f"{', '.join(touched)} start overlapping where the task put them by hand; moved "
         f"apart until they touch, each by at most {most * 1000:.1f} mm (PyBullet pushes "
         "overlapping objects apart at its first step)")


#: How close (m) an object's start must be to a target to count as added there.
AT_TARGET_EPS = 1e-4


def scatter_added_at_targets(goals: list[Any], names: dict[int, str], warn: Any) -> None:
    """Objects a goal finds at its targets before any action start at random spots.

    A task that computes a packing plan adds each box at its planned pose and then
    moves it out (Ravens' packing tasks ``resetBasePositionAndOrientation`` it to a
    random pose); one that forgets leaves a goal met before the robot acts (Ravens
    scores it done at once; factask refuses a goal met at the start). When every
    movable object of a goal — the first goal that moves each — starts at one of the
    targets its ``matches`` row allows (within 0.1 mm, z included), they start at
    random free spots instead, as ``get_random_pose`` would give them (warning).
    """
    first: dict[int, int] = {}
    for g in goals:
        for o in g.objs:
            first.setdefault(o.obj_id, g.index)
    for g in goals:
        objs = list(g.objs)
        if not objs or not g.targets or any(
                first[o.obj_id] != g.index or o.category == "fixed" or o.random_start
                for o in objs):
            continue
        at = []
        for i, o in enumerate(objs):
            row = g.matches[i] if i < len(g.matches) else []
            at.append(any(j < len(row) and row[j] and float(np.linalg.norm(
                np.asarray(o.pos, dtype=float) - np.asarray(t[0], dtype=float)[:3]))
                < AT_TARGET_EPS for j, t in enumerate(g.targets)))
        if not all(at):
            continue
        for o in objs:
            o.random_start = True
        warn(f"goal {g.index}: {', '.join(names[o.obj_id] for o in objs)} start at the "
             "targets the goal gives them (added in place and never moved out), so the "
             "goal would be met before any action; they start at random free spots "
             "instead")
