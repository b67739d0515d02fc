"""Shelves and their levels as geometry (pure numpy; never imports MuJoCo).

A ``shelf`` is fixed to the table; each ``shelf_level`` variable that starts
``in_cabinet`` of it (its ``level`` field: 0 the lowest) is one step of a
staircase rising from the shelf's -x side towards its back panel at +x. A level
is a solid box from the table up to its top, so every level's top is open to the
sky and a top-down robot reaches each one; the shelf itself is its frame: a back
panel and, beside each level, side panels that stand a lip above it. A level is
a support of its own, so ``on`` a level needs nothing ``on`` does not already
read: its pose is computed from its shelf's here (:func:`level_pose`) and
nowhere else.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from factask.geometry import Pose, rotation_matrix
from factask.scene.objects import Area, SceneObject
from factask.vocabulary.errors import InvalidValueError
from factask.vocabulary.kinds import (
    SHELF_LIP,
    WALL_THICKNESS,
    shelf_level_offset,
    shelf_level_top,
)
from factask.vocabulary.variables import InCabinet, VariableSet, drawers_of

#: The kinds of this module.
SHELF_KIND = "shelf"
LEVEL_KIND = "shelf_level"

#: A box of an asset: its name and its low and high corners in the body frame.
Box = tuple[str, tuple[float, float, float], tuple[float, float, float]]


def shelf_boxes(size: tuple[float, float, float], levels: int) -> list[Box]:
    """The panels of a shelf of ``size`` with ``levels`` levels: a back panel (+x) of
    the full height and, beside each level, a side panel at -y and +y standing
    :data:`~factask.vocabulary.kinds.SHELF_LIP` above the level's top. (The levels
    are bodies of their own.) Their bounding box is ``size``."""
    x, y, z = (s / 2 for s in size)
    t = WALL_THICKNESS
    out: list[Box] = [("back", (x - t, -y, -z), (x, y, z))]
    depth = (size[0] - t) / levels
    for k in range(levels):
        x0, x1 = -x + k * depth, -x + (k + 1) * depth
        top = min(-z + shelf_level_top(size, levels, k) + SHELF_LIP, z)
        out.append((f"side{k}_ny", (x0, -y, -z), (x1, -y + t, top)))
        out.append((f"side{k}_py", (x0, y - t, -z), (x1, y, top)))
    return out


@dataclass(frozen=True)
class LevelSeat:
    """Where a level sits: its shelf's instance, its level and its shelf's levels.

    Args:
        shelf: The shelf's instance (its variable's name: a shelf is one object).
        level: The level, 0 the lowest.
        levels: How many levels the shelf has.
    """

    shelf: str
    level: int
    levels: int


def level_seat(graph: VariableSet, level: str) -> LevelSeat:
    """The :class:`LevelSeat` of shelf level variable ``level``.

    Args:
        graph: The task graph.
        level: A shelf level variable's name.

    Returns:
        Its shelf, its level and the shelf's number of levels.

    Raises:
        InvalidValueError: ``level`` does not start in a shelf (validation forbids it).
    """
    start = graph.variable(level).initial
    if not isinstance(start, InCabinet):
        raise InvalidValueError(f"variable {level!r} is not a level of a shelf; give it "
                                'initial {"type": "in_cabinet", "cabinet": <a shelf>, '
                                '"level": k}')
    return LevelSeat(start.cabinet, start.level,
                     len(drawers_of(graph.variables, start.cabinet)))


def level_pose(shelf: SceneObject, shelf_pose: Pose, seat: LevelSeat) -> Pose:
    """The pose of the level at ``seat`` of ``shelf`` standing at ``shelf_pose`` (the
    one place a level's pose is computed: the layout and the scene read it).

    Args:
        shelf: The shelf.
        shelf_pose: Its pose.
        seat: The level's seat.

    Returns:
        The level's pose: its centre, turned as its shelf.
    """
    local = np.array(shelf_level_offset(shelf.size, seat.levels, seat.level))
    return Pose(shelf_pose.pos + rotation_matrix(shelf_pose.quat) @ local,
                shelf_pose.quat.copy())


def shelf_inner_area(shelf: SceneObject, pose: Pose) -> Area:
    """The shelf's area inside its side and back panels (over its levels): what lies
    wholly in it meets the levels, which are bodies of their own, never the shelf's
    panels (the collision rule of :mod:`factask.scene.collision`)."""
    t = WALL_THICKNESS
    half = np.array([shelf.size[0] / 2 - t / 2, shelf.size[1] / 2 - t])
    local = np.array([-t / 2, 0.0])
    c, s = np.cos(pose.yaw), np.sin(pose.yaw)
    centre = pose.pos[:2] + np.array([c * local[0] - s * local[1], s * local[0] + c * local[1]])
    return Area(centre, pose.yaw, half)
