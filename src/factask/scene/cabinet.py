"""Cabinets and their drawers as geometry (pure numpy; never imports MuJoCo).

A ``cabinet`` is fixed to the table; each ``drawer`` variable that starts
``in_cabinet`` of it takes one of its bays, stacked from the bottom (level 0), and
slides out along the cabinet's -x axis by up to
:func:`~factask.vocabulary.kinds.drawer_travel`. A drawer is a scene object of its
own whose pose is its box's centre, so everything that reads a receptacle's pose
(``inside``, the packing of slots) follows it as it slides. Its opening — the one
fact the ``open`` and ``closed`` relations read — is the distance it has slid out
of its closed place, over its travel: a number in [0, 1] computed from its pose
and its cabinet's here, and nowhere else.
"""

from __future__ import annotations

import numpy as np

from factask.geometry import Pose, rotation_matrix
from factask.scene.objects import Area, SceneObject, placement_area, yaw_rotation_2d
from factask.vocabulary.errors import InvalidValueError
from factask.vocabulary.kinds import (
    HANDLE_DEPTH,
    HANDLE_THICKNESS,
    HANDLE_WIDTH,
    WALL_THICKNESS,
    cabinet_bay,
    drawer_closed_offset,
    drawer_travel,
    handle_top,
)
from factask.vocabulary.variables import InCabinet, VariableSet, drawers_of

#: Room (m) kept free beside a cabinet's front beyond its drawers' travel: the
#: suction cup's radius and a margin, so the cup reaches a handle pulled all the way.
FRONT_MARGIN = 0.04


#: A box of an asset: its name and its low and high corners in the body frame.
Box = tuple[str, tuple[float, float, float], tuple[float, float, float]]


def cabinet_boxes(size: tuple[float, float, float], bays: int) -> list[Box]:
    """The panels of a cabinet of ``size`` with ``bays`` bays: back (+x), sides, top,
    bottom and a shelf between bays; open at -x. Their bounding box is ``size``."""
    x, y, z = (s / 2 for s in size)
    t = WALL_THICKNESS
    out: list[Box] = [("back", (x - t, -y, -z), (x, y, z)),
                      ("side_ny", (-x, -y, -z), (x - t, -y + t, z)),
                      ("side_py", (-x, y - t, -z), (x - t, y, z)),
                      ("bottom", (-x, -y + t, -z), (x - t, y - t, -z + t)),
                      ("top", (-x, -y + t, z - t), (x - t, y - t, z))]
    for k in range(1, bays):
        floor, _ = cabinet_bay(size, bays, k)
        out.append((f"shelf{k}", (-x, -y + t, floor - t), (x - t, y - t, floor)))
    return out


def drawer_boxes(size: tuple[float, float, float], bays: int, level: int) -> list[Box]:
    """The parts of a drawer of ``size``: floor and four walls behind its handle, and
    the handle (a flat tab at its -x end, flush with its rim, placed along y by its
    level: :func:`~factask.vocabulary.kinds.handle_top`). Their bounding box is
    ``size``."""
    x, y, z = (s / 2 for s in size)
    t, front = WALL_THICKNESS, -x + HANDLE_DEPTH
    _, hy, _ = handle_top(size, bays, level)
    return [("floor", (front + t, -y + t, -z), (x - t, y - t, -z + t)),
            ("wall_nx", (front, -y, -z), (front + t, y, z)),
            ("wall_px", (x - t, -y, -z), (x, y, z)),
            ("wall_py", (front + t, y - t, -z), (x - t, y, z)),
            ("wall_ny", (front + t, -y, -z), (x - t, -y + t, z)),
            ("handle", (-x, hy - HANDLE_WIDTH / 2, z - HANDLE_THICKNESS),
             (front, hy + HANDLE_WIDTH / 2, z))]


class DrawerSeat:
    """Where a drawer sits: its cabinet's instance, its level and its cabinet's bays.

    Args:
        cabinet: The cabinet's instance (its variable's name: a cabinet is one object).
        level: The drawer's bay, 0 the bottom one.
        bays: How many drawers the cabinet holds.
    """

    def __init__(self, cabinet: str, level: int, bays: int) -> None:
        self.cabinet, self.level, self.bays = cabinet, level, bays


def drawer_seat(graph: VariableSet, drawer: str) -> DrawerSeat:
    """The :class:`DrawerSeat` of drawer variable ``drawer``.

    Raises:
        InvalidValueError: ``drawer`` does not start in a cabinet (validation forbids it).
    """
    start = graph.variable(drawer).initial
    if not isinstance(start, InCabinet):
        raise InvalidValueError(f"variable {drawer!r} is not a drawer in a cabinet")
    return DrawerSeat(start.cabinet, start.level, len(drawers_of(graph.variables,
                                                                 start.cabinet)))


def drawer_pose(cabinet: SceneObject, cabinet_pose: Pose, seat: DrawerSeat,
                drawer: SceneObject, opening: float) -> Pose:
    """The pose of a drawer pulled out by ``opening`` (a fraction of its travel).

    Args:
        cabinet: The drawer's cabinet.
        cabinet_pose: Its pose.
        seat: The drawer's seat in it.
        drawer: The drawer.
        opening: 0 closed .. 1 all the way out.
    """
    local = np.array(drawer_closed_offset(cabinet.size, seat.bays, seat.level))
    local[0] -= opening * drawer_travel(drawer.size)
    pos = cabinet_pose.pos + rotation_matrix(cabinet_pose.quat) @ local
    return Pose(pos, cabinet_pose.quat.copy())


def drawer_opening(cabinet: SceneObject, cabinet_pose: Pose, drawer: SceneObject,
                   pose: Pose) -> float:
    """How far a drawer at ``pose`` is pulled out, as a fraction of its travel (its
    slide along the cabinet's -x axis; 0 closed, 1 all the way out; not clipped)."""
    local = rotation_matrix(cabinet_pose.quat).T @ (pose.pos - cabinet_pose.pos)
    closed_x = drawer_closed_offset(cabinet.size, 1, 0)[0]  # the same for every bay
    return float((closed_x - local[0]) / drawer_travel(drawer.size))


def drawer_shown_area(drawer: SceneObject, pose: Pose) -> Area:
    """The part of a drawer's inside that stands out of its cabinet once the drawer
    is all the way open: the front of its floor, :func:`drawer_travel` deep behind
    its front wall. Only there can a top-down robot reach what lies in the drawer
    (the rest stays under the cabinet's top or the bay above), so a thing starts in
    a drawer there.

    Args:
        drawer: The drawer.
        pose: Its pose (any opening: the area moves with it).
    """
    inner = placement_area(drawer, pose)
    front = -drawer.half[0] + HANDLE_DEPTH + WALL_THICKNESS  # the inner x of its front wall
    back = -drawer.half[0] + HANDLE_DEPTH + drawer_travel(drawer.size)
    centre_x = (front + back) / 2
    centre = pose.pos[:2] + yaw_rotation_2d(pose.yaw) @ np.array([centre_x, 0.0])
    return Area(centre, pose.yaw, np.array([max(back - front, 0.0) / 2, inner.half[1]]))


def handle_point(drawer: SceneObject, pose: Pose, seat: DrawerSeat) -> np.ndarray:
    """World position (3,) of the centre of the top of a drawer's handle: where the
    suction cup holds it."""
    local = np.array(handle_top(drawer.size, seat.bays, seat.level))
    return pose.pos + rotation_matrix(pose.quat) @ local


def front_reserve(cabinet: SceneObject, drawer_depth: float) -> tuple[float, float,
                                                                      tuple[float, float]]:
    """The rectangle in front of a cabinet (its -x side) its drawers slide into, in the
    cabinet's frame: (centre x, centre y, (x extent, y extent)).

    Args:
        cabinet: The cabinet.
        drawer_depth: Its drawers' size x (handle included).
    """
    travel = drawer_travel((drawer_depth, 0.0, 0.0))
    depth = HANDLE_DEPTH + travel + FRONT_MARGIN
    return (-cabinet.size[0] / 2 - depth / 2, 0.0,
            (depth, cabinet.size[1]))
