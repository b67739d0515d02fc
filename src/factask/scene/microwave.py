"""Microwaves and their hinged doors as geometry (pure numpy; never imports MuJoCo).

A ``microwave`` is a box fixed to the table, open at its -x side where its
``door`` hangs; it is open at the top too, because the robots are top-down suction
cups that put things in from above (a roof would leave them no way in). The door
is a variable of its own that starts ``in_cabinet`` of its microwave: a panel on
the microwave's -x face with a flat handle tab sticking out at the top of its free
(+y) end, swinging outwards about a vertical hinge at its -y edge
(:func:`~factask.vocabulary.kinds.door_hinge`) by up to
:data:`~factask.vocabulary.kinds.DOOR_RANGE`. Its pose is its box's centre, so it
is read like every object's. Its opening -- the one fact ``open`` and ``closed``
read -- is the angle it has swung out of its closed place over its range: a
number in [0, 1] computed from its pose and its microwave's here, and nowhere else.
"""

from __future__ import annotations

import math

import numpy as np

from factask.geometry import Pose, quat_from_yaw, quat_mul, rotation_matrix, wrap_angle
from factask.scene.cabinet import FRONT_MARGIN, Box
from factask.scene.objects import SceneObject
from factask.vocabulary.kinds import (
    DOOR_RANGE,
    DOOR_THICKNESS,
    HANDLE_DEPTH,
    HANDLE_THICKNESS,
    HANDLE_WIDTH,
    WALL_THICKNESS,
    door_closed_offset,
    door_handle_top,
    door_hinge,
)


def microwave_boxes(size: tuple[float, float, float]) -> list[Box]:
    """The panels of a microwave of ``size``: back (+x), two sides and a floor; open
    at -x (its door) and at the top. Their bounding box is ``size``."""
    x, y, z = (s / 2 for s in size)
    t = WALL_THICKNESS
    return [("back", (x - t, -y, -z), (x, y, z)),
            ("side_ny", (-x, -y, -z), (x - t, -y + t, z)),
            ("side_py", (-x, y - t, -z), (x - t, y, z)),
            ("floor", (-x, -y + t, -z), (x - t, y - t, -z + t))]


def door_boxes(size: tuple[float, float, float]) -> list[Box]:
    """The parts of a door of ``size``: its panel (at +x, against the microwave) and
    its handle (a flat tab out of the panel's -x face, flush with its top, near its
    free +y edge: :func:`~factask.vocabulary.kinds.door_handle_top`). Their bounding
    box is ``size``."""
    x, y, z = (s / 2 for s in size)
    hx, hy, _ = door_handle_top(size)
    return [("panel", (x - DOOR_THICKNESS, -y, -z), (x, y, z)),
            ("handle", (-x, hy - HANDLE_WIDTH / 2, z - HANDLE_THICKNESS),
             (hx + HANDLE_DEPTH / 2, hy + HANDLE_WIDTH / 2, z))]


def door_pose(microwave: SceneObject, microwave_pose: Pose, door: SceneObject,
              opening: float) -> Pose:
    """The pose of a door swung out by ``opening`` (a fraction of its range).

    Args:
        microwave: The door's microwave.
        microwave_pose: Its pose.
        door: The door (its size: the closed offset and hinge follow from the
            microwave's).
        opening: 0 closed .. 1 swung all the way out.

    Returns:
        The door's centre and orientation.
    """
    angle = opening * DOOR_RANGE
    hinge = np.array(door_hinge(microwave.size))
    c, s = math.cos(angle), math.sin(angle)
    turn = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    local = hinge + turn @ (np.array(door_closed_offset(microwave.size)) - hinge)
    pos = microwave_pose.pos + rotation_matrix(microwave_pose.quat) @ local
    return Pose(pos, quat_mul(microwave_pose.quat, quat_from_yaw(angle)))


def door_opening(microwave: SceneObject, microwave_pose: Pose, door: SceneObject,
                 pose: Pose) -> float:
    """How far a door at ``pose`` has swung out, as a fraction of its range (its yaw
    relative to its microwave's; 0 closed, 1 all the way out; not clipped, and a
    door swung past shut reads below 0)."""
    return float(wrap_angle(pose.yaw - microwave_pose.yaw) / DOOR_RANGE)


def door_handle_point(door: SceneObject, pose: Pose) -> np.ndarray:
    """World position (3,) of the centre of the top of a door's handle: where the
    suction cup holds it."""
    return pose.pos + rotation_matrix(pose.quat) @ np.array(door_handle_top(door.size))


def hinge_point(microwave: SceneObject, microwave_pose: Pose) -> np.ndarray:
    """World position (3,) of a microwave's door hinge, at the microwave's mid-height:
    the centre of the arc the door's handle swings along."""
    return microwave_pose.pos + rotation_matrix(microwave_pose.quat) @ np.array(
        door_hinge(microwave.size))


def swing_reserve(microwave: SceneObject) -> tuple[float, float, tuple[float, float]]:
    """The rectangle in front of a microwave (its -x side) its door swings through,
    in the microwave's frame: (centre x, centre y, (x extent, y extent)). It holds
    the quarter disc of the door's width about the hinge, the handle where it
    sticks out past the hinge (towards -y) all the way open, and room for the cup
    round the handle (:data:`FRONT_MARGIN`)."""
    width = microwave.size[1]
    depth = DOOR_THICKNESS + width + FRONT_MARGIN
    low_y = -width / 2 - HANDLE_DEPTH - FRONT_MARGIN
    return (-microwave.size[0] / 2 - depth / 2, (low_y + width / 2) / 2,
            (depth, width / 2 - low_y))
