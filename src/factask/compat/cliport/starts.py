"""Start poses a task's author gave by hand that factask cannot take as they are.

* :func:`fits_inside`: whether an object fits between a receptacle's walls (a
  container as wide as the one under it rests on that one's rim: "the containers
  start stacked");
* :func:`separate_starts`: hand-placed objects on the table whose footprints
  overlap by a little are pushed apart until they touch, as PyBullet pushes them
  apart at its first step (a row of 4 cm blocks put 3.5 cm apart);
* :func:`settle` and :func:`placement`: where each object starts — on the table at
  the author's pose, ``StartInside`` / ``StartOn`` a host under it, or a random free
  spot — after objects in the air, sunk into the table, tilted, or on a support
  factask builds taller than the author placed it are put where factask starts them.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from factask.compat.cliport.goals import half_xy
from factask.compat.cliport.recorder import RecordedObject
from factask.compat.cliport.sharing import SEPARATE_GAP, SEPARATE_ROUNDS
from factask.compat.cliport.transforms import footprint_separation, xyzw_to_wxyz, yaw_of_xyzw
from factask.geometry import Pose, tilt_deg
from factask.scene.collision import centre_in_workspace
from factask.scene.objects import floor_thickness
from factask.vocabulary.kinds import WALL_THICKNESS, kind_spec
from factask.vocabulary.variables import AtFixedPose, OnTable, StartInside, StartOn

#: An object whose bottom is this far above the table starts on something.
START_ABOVE_TABLE = 0.01
#: Slack when deciding that a support's top is under an object's bottom, metres.
SUPPORT_SLACK = 0.02
#: An object too wide for a receptacle whose bottom is at most this far (m) below the
#: receptacle's top rests on its rim.
RIM_SLACK = 0.005
#: An object whose bottom is this far (m) below the table top has sunk into it.
SINK_EPS = 0.001
#: Objects tilted more than this (degrees) at the start lose their tilt (with a warning).
TILT_WARN_DEG = 5.0

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
             and footprint_separation(_footprint(a), _footprint(b)) is not None]
    if not pairs:
        return
    start = {o.obj_id: np.array(o.pos, dtype=float) for o in solid}
    for _ in range(SEPARATE_ROUNDS):
        pushed = False
        for a, b in pairs:
            move = footprint_separation(_footprint(a), _footprint(b))
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
    left = any(footprint_separation(_footprint(a), _footprint(b)) is not None for a, b in pairs)
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


def inside_footprint(xy: np.ndarray, o: RecordedObject) -> bool:
    """Whether point ``xy`` lies within ``o``'s footprint as the author turned it."""
    yaw = yaw_of_xyzw(o.quat)
    d = xy - o.pos[:2]
    c, s = math.cos(-yaw), math.sin(-yaw)
    local = np.array([c * d[0] - s * d[1], s * d[0] + c * d[1]])
    return bool(abs(local[0]) <= o.size[0] / 2 and abs(local[1]) <= o.size[1] / 2)


def _in_workspace(o: RecordedObject) -> bool:
    """The object's centre is inside the workspace (tasks park objects far away, e.g.
    palletizing's boxes waiting to be spawned at y - 10)."""
    return centre_in_workspace(Pose(np.asarray(o.pos, dtype=float), xyzw_to_wxyz(o.quat)))


def _hosts(o: RecordedObject, others: list[RecordedObject]
           ) -> tuple[list[RecordedObject], list[RecordedObject], list[RecordedObject]]:
    """The receptacles ``o`` starts in, the supports it starts on, and the
    receptacles on whose rim it rests (too wide to go in: stacked containers)."""
    bottom = float(o.pos[2]) - o.size[2] / 2
    # Any other object may hold it, whatever the order the task added them in (a
    # stack added top first); only a lower one can be its support, so no cycles.
    holders = [c for c in others if _in_workspace(c) and inside_footprint(o.pos[:2], c)]
    # A receptacle smaller than ``o`` all round holds nothing of it: ``o`` is under
    # it (a pallet with a bowl put on its centre), not in it.
    receptacles = [c for c in holders if kind_spec(c.kind).receptacle
                   and c.pos[2] - c.size[2] / 2 <= bottom + SUPPORT_SLACK
                   and not _wider_than(o, c)]
    rims = [c for c in receptacles if not fits_inside(o, c)
            and bottom >= c.pos[2] + c.size[2] / 2 - RIM_SLACK]
    receptacles = [c for c in receptacles if c not in rims]
    # A centre inside a support's footprint cannot rest on the table: it is on it.
    # Its top counts as the author placed it (a pallet placed with a smaller size
    # than factask's is raised to the table; what the author put on it stays on it).
    supports = [c for c in holders if kind_spec(c.kind).support
                and min(c.pos[2] + c.size[2] / 2,
                        c.placed_top if c.placed_top is not None else np.inf)
                <= bottom + SUPPORT_SLACK]
    return receptacles, supports, rims


def _wider_than(o: RecordedObject, host: RecordedObject) -> bool:
    """Whether ``o``'s footprint, turned as the author turned it, is wider than
    ``host``'s whole footprint along both of the host's axes."""
    half = half_xy(o.size, yaw_of_xyzw(o.quat) - yaw_of_xyzw(host.quat))
    return bool(half[0] > host.size[0] / 2 and half[1] > host.size[1] / 2)


def on_table_as_given(o: RecordedObject, others: list[RecordedObject],
                       moved: set[int]) -> bool:
    """Whether factask starts ``o`` on the table at the author's pose (``AtFixedPose``)."""
    if o.random_start and o.obj_id in moved and o.category != "fixed":
        return False
    return _in_workspace(o) and not any(_hosts(o, others))


def settle(objects: list[RecordedObject], names: dict[int, str], moved: set[int],
            warn: Any) -> None:
    """Put objects that start in the air on nothing, sunk into the table, or tilted,
    where factask starts them (on the table, upright, same x, y and yaw), before
    anything reads their poses: targets resting in or on them follow them (a 6-DoF
    fixture down, a pallet placed with a smaller size than factask's up).
    """
    for k, o in enumerate(objects):
        if (o.random_start and o.obj_id in moved and o.category != "fixed") or (
                not _in_workspace(o)):
            continue  # factask samples its start anyway
        if any(_hosts(o, objects[:k] + objects[k + 1:])):
            continue  # in or on a host (or on a rim: a random start, see placement)
        name = names[o.obj_id]
        bottom = float(o.pos[2]) - o.size[2] / 2
        if bottom < -SINK_EPS:
            # Sunk into the table: factask's asset is taller than the size the author
            # placed it with (a 2 cm pallet hint for a 3.75 cm pallet). The author put
            # it on the table, so does factask; targets on it follow it up.
            # The author's asset rested on the table with its centre at z: its top
            # was at 2 z, and targets above that are on it.
            o.placed_top = 2 * float(o.pos[2])
            o.pos = np.array([o.pos[0], o.pos[1], o.size[2] / 2], dtype=float)
        if bottom > START_ABOVE_TABLE:
            warn(f"{name} starts {bottom:.3f} m above the table on nothing; it starts on "
                 "the table instead (targets in or on it follow it down)")
            o.pos = np.array([o.pos[0], o.pos[1], o.size[2] / 2], dtype=float)
        if tilt_deg(xyzw_to_wxyz(o.quat)) > TILT_WARN_DEG:
            warn(f"{name} starts tilted; only its yaw is kept")
            yaw = yaw_of_xyzw(o.quat)
            o.quat = np.array([0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)])
    _seat_in_receptacles(objects, names, moved, warn)
    _seat_on_raised_supports(objects, names, moved, warn)


def _seat_in_receptacles(objects: list[RecordedObject], names: dict[int, str],
                         moved: set[int], warn: Any) -> None:
    """Objects the author put inside a receptacle at a height of their own (a block
    at the container's pose plus 2 cm) start on its floor, as ``StartInside`` puts
    them; what is put into the receptacle later lands on them where they really lie,
    and targets over them are measured from there (:func:`resting_heights`). Their
    top as the author placed it is kept (``placed_top``), so targets the author put
    on them still count as on them.
    """
    for o in objects:
        if (o.random_start and o.obj_id in moved and o.category != "fixed") or (
                not _in_workspace(o)):
            continue
        receptacles, _supports, _rims = _hosts(o, [c for c in objects if c is not o])
        if not receptacles:
            continue
        host = receptacles[-1]
        bottom = float(o.pos[2]) - o.size[2] / 2
        floor = float(host.pos[2]) - host.size[2] / 2 + floor_thickness(host.kind)
        if abs(floor - bottom) <= SINK_EPS:
            continue
        if o.placed_top is None:
            o.placed_top = bottom + (floor_thickness(o.kind) if kind_spec(o.kind).receptacle
                                     else o.size[2])
        o.pos = np.array([o.pos[0], o.pos[1], floor + o.size[2] / 2], dtype=float)
        if abs(floor - bottom) > SUPPORT_SLACK / 2:
            warn(f"{names[o.obj_id]} starts in {names[host.obj_id]!r} {bottom - floor:+.3f} m "
                 "off its floor; it starts on the floor (what goes in later lands on it)")


def _seat_on_raised_supports(objects: list[RecordedObject], names: dict[int, str],
                             moved: set[int], warn: Any) -> None:
    """Objects the author put on a support that factask raised (a pallet placed
    with a smaller size hint than factask's asset) start on its real top, as
    ``StartOn`` puts them; what lies in or on them is measured from there (a ball's
    target in a bowl put on such a pallet rests on the bowl's floor, not inside its
    walls). Their top as the author placed it is kept (``placed_top``), so targets
    the author put on them still count as on them. Lowest first, so a stack follows.
    """
    for o in sorted(objects, key=lambda o: float(o.pos[2]) - o.size[2] / 2):
        if (o.random_start and o.obj_id in moved and o.category != "fixed") or (
                not _in_workspace(o)):
            continue
        receptacles, supports, rims = _hosts(o, [c for c in objects if c is not o])
        if receptacles or rims or not supports:
            continue
        host = max(supports, key=lambda c: c.pos[2] + c.size[2] / 2)
        if host.placed_top is None:
            continue  # the host stands where the author put it
        bottom = float(o.pos[2]) - o.size[2] / 2
        new_bottom = float(host.pos[2]) + host.size[2] / 2
        if abs(new_bottom - bottom) <= SINK_EPS:
            continue
        if o.placed_top is None:
            o.placed_top = bottom + (floor_thickness(o.kind) if kind_spec(o.kind).receptacle
                                     else o.size[2])
        o.pos = np.array([o.pos[0], o.pos[1], new_bottom + o.size[2] / 2], dtype=float)
        warn(f"{names[o.obj_id]} starts on {names[host.obj_id]!r}, which factask builds "
             f"{host.pos[2] + host.size[2] / 2 - host.placed_top:+.3f} m taller than the "
             "task placed it; it starts on its top (targets in or on it follow it)")


def placement(o: RecordedObject, others: list[RecordedObject], names: dict[int, str],
               moved: set[int], warn: Any) -> Any:
    name = names[o.obj_id]
    if o.random_start and o.obj_id in moved and o.category != "fixed":
        # The task asked for "a random free spot" (get_random_pose): so does factask,
        # each episode, clear of everything (objects added later included).
        return OnTable()
    x, y = float(o.pos[0]), float(o.pos[1])
    if not _in_workspace(o):
        warn(f"{name} starts outside the workspace at ({x:.3f}, {y:.3f}); it starts at a "
             "random free spot instead")
        return OnTable()
    receptacles, below, rims = _hosts(o, others)
    if rims and not receptacles and not below:
        warn(f"{name} starts on the rim of {names[rims[-1].obj_id]!r}, too wide to go in "
             "(stacked receptacles); factask cannot rest it on a rim: it starts at a "
             "random free spot instead")
        return OnTable()
    if receptacles:
        host = receptacles[-1]
        return StartInside(container=names[host.obj_id], **_given_place(o, host))
    if below:
        support = max(below, key=lambda c: c.pos[2] + c.size[2] / 2)
        return StartOn(support=names[support.obj_id], **_given_place(o, support))
    return AtFixedPose(x=x, y=y, yaw_deg=math.degrees(yaw_of_xyzw(o.quat)))



def _given_place(o: RecordedObject, host: RecordedObject) -> dict[str, Any]:
    """Where the task's author put ``o`` on ``host``: offset and yaw in the host's
    frame (a fact, like every pose the code gives), unless it asked for a random
    spot."""
    if o.random_start:
        return {}
    host_yaw = yaw_of_xyzw(host.quat)
    dx, dy = float(o.pos[0] - host.pos[0]), float(o.pos[1] - host.pos[1])
    c, s = math.cos(host_yaw), math.sin(host_yaw)
    yaw = math.degrees(yaw_of_xyzw(o.quat) - host_yaw)
    return {"offset": (round(c * dx + s * dy, 6), round(-s * dx + c * dy, 6)),
            "yaw_deg": round((yaw + 180.0) % 360.0 - 180.0, 6)}
