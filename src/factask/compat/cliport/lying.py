"""Cylinders an author lays on their side become logs.

A CLIPort cylinder (``cylinder/cylinder-template.urdf``) is upright in its own frame;
an author who turns it by 90 degrees about a horizontal axis (``roll = pi / 2``)
means a cylinder lying on its side -- "balance the cylinder horizontally on the
blocks". factask has that as its own kind, ``log`` (axis along its x, size
``(length, diameter, diameter)``), because its objects otherwise stand upright and
an upright cylinder in a lying cylinder's place is another task (it stands in a
bridge's gap instead of spanning it). A cylinder that starts lying, or whose pose
target lies, is a log: its size is turned, its start and targets keep the
direction of its axis in the table plane as the log's yaw. A suction cup picking
from the top can neither tip a cylinder over nor stand one up, so a cylinder that
starts upright and must end lying starts lying (a warning says so), and one that
starts lying and must end upright stays lying (a warning too).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from factask.compat.cliport.goals import RecordedGoal
from factask.compat.cliport.recorder import RecordedObject
from factask.compat.cliport.transforms import rotation, wxyz_to_xyzw, yaw_of_xyzw
from factask.geometry import quat_from_yaw

#: A cylinder whose axis is within this many degrees of horizontal is lying.
LYING_TOLERANCE_DEG = 20.0


def axis_of(quat_xyzw: np.ndarray) -> np.ndarray:
    """The world direction of a cylinder's axis (its body z) at orientation ``quat_xyzw``."""
    return rotation(quat_xyzw).as_matrix()[:, 2]


def is_lying(quat_xyzw: np.ndarray) -> bool:
    """True when a cylinder at ``quat_xyzw`` lies on its side (its axis near horizontal)."""
    tilt = math.degrees(math.acos(min(1.0, abs(float(axis_of(quat_xyzw)[2])))))
    return tilt > 90.0 - LYING_TOLERANCE_DEG


def log_quat(quat_xyzw: np.ndarray) -> np.ndarray:
    """The x, y, z, w quaternion of a log lying along the cylinder's axis: a turn
    about z only (the log's own axis is its x)."""
    axis = axis_of(quat_xyzw)
    return wxyz_to_xyzw(quat_from_yaw(math.atan2(float(axis[1]), float(axis[0]))))


def _yaw_quat(quat_xyzw: np.ndarray) -> np.ndarray:
    """Only the turn about z of an upright orientation (as every start and target
    keeps it: :func:`~factask.compat.cliport.transforms.yaw_of_xyzw`)."""
    return wxyz_to_xyzw(quat_from_yaw(yaw_of_xyzw(quat_xyzw)))


def lay_down_cylinders(objects: list[RecordedObject], goals: list[RecordedGoal],
                       warn: Callable[[str], None]) -> set[int]:
    """Make every cylinder that starts lying, or that a pose goal lays down, a ``log``.

    Args:
        objects: The recorded objects (changed in place: kind, size, start quat).
        goals: The recorded goals (pose targets of the logs changed in place).
        warn: Where the approximations are reported.

    Returns:
        The object ids turned into logs.
    """
    out: set[int] = set()
    for o in objects:
        if o.kind != "cylinder":
            continue
        targets = [(g, int(j)) for g in goals if g.metric == "pose"
                   for i, obj in enumerate(g.objs) if obj.obj_id == o.obj_id
                   for j in np.flatnonzero(g.matches[i])]
        starts_lying = is_lying(o.quat)
        lying_targets = [(g, j) for g, j in targets if is_lying(g.targets[j][1])]
        if not starts_lying and not lying_targets:
            continue
        diameter, _, height = o.size
        o.kind, o.size = "log", (height, diameter, diameter)
        if starts_lying:
            o.quat = log_quat(o.quat)
            if len(lying_targets) < len(targets):
                warn(f"cylinder {o.obj_id} ({o.urdf}) starts lying on its side and a target "
                     "stands it up: it stays lying (a suction cup picking from the top "
                     "cannot stand it up)")
        else:
            o.quat = _yaw_quat(o.quat)
            warn(f"cylinder {o.obj_id} ({o.urdf}) starts upright and a target lays it on its "
                 "side: it starts lying (a suction cup picking from the top cannot tip it "
                 "over)")
        for g, j in targets:
            pos, quat = g.targets[j]
            g.targets[j] = (pos, log_quat(quat) if is_lying(quat) else _yaw_quat(quat))
        out.add(o.obj_id)
    return out
