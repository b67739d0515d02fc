"""Switches as geometry (pure numpy; never imports MuJoCo).

A switchable fixture (a ``stove``, a ``lamp``: the kinds of
:data:`~factask.vocabulary.kinds.SWITCH_HOSTS`) is fixed to the table; its
``switch`` variable (initial ``mounted_on`` it) is a push button standing in the
middle of the -x strip of its top, which slides down along the host's -z axis by
up to :func:`~factask.vocabulary.kinds.switch_travel`. The switch is a scene object
of its own whose pose is its box's centre; how far it is pressed — the one fact
the ``switched_on`` and ``switched_off`` relations read — is its drop below its
off place over its travel: a number in [0, 1] computed from its pose and its
host's here, and nowhere else (the batched check is its array twin).
"""

from __future__ import annotations

import numpy as np

from factask.geometry import Pose, rotation_matrix
from factask.scene.objects import SceneObject
from factask.vocabulary.errors import InvalidValueError
from factask.vocabulary.kinds import switch_off_offset, switch_travel
from factask.vocabulary.variables import MountedOn, VariableSet


def switch_host(graph: VariableSet, switch: str) -> str:
    """The variable switch variable ``switch`` is mounted on.

    Args:
        graph: The task graph.
        switch: A switch variable's name.

    Returns:
        Its host's name (one object: its instance name is the same).

    Raises:
        InvalidValueError: ``switch`` is not mounted on a host (validation forbids it).
    """
    start = graph.variable(switch).initial
    if not isinstance(start, MountedOn):
        raise InvalidValueError(f"variable {switch!r} is not a switch mounted on a fixture; "
                                'give it initial {"type": "mounted_on", "host": ...}')
    return start.host


def switch_pose(host: SceneObject, host_pose: Pose, pressed: float) -> Pose:
    """The pose of the switch of ``host`` pressed down by ``pressed``.

    Args:
        host: The switchable fixture.
        host_pose: Its pose.
        pressed: 0 off (up) .. 1 on (pressed all the way down).

    Returns:
        The switch's world pose (its host's orientation).
    """
    local = np.array(switch_off_offset(host.kind, host.size))
    local[2] -= pressed * switch_travel()
    return Pose(host_pose.pos + rotation_matrix(host_pose.quat) @ local, host_pose.quat.copy())


def switch_pressed(host: SceneObject, host_pose: Pose, pose: Pose) -> tuple[float, float]:
    """How far a switch at ``pose`` is pressed down, a fraction of its travel (its
    slide along the host's -z axis; 0 off, 1 on; not clipped), and how far (m) it
    stands off its mount sideways (0 for any state its joint allows).

    Args:
        host: The switchable fixture the switch is mounted on.
        host_pose: Its pose.
        pose: The switch's pose.

    Returns:
        (pressed fraction, horizontal distance from its mount's axis).
    """
    local = rotation_matrix(host_pose.quat).T @ (pose.pos - host_pose.pos)
    off = switch_off_offset(host.kind, host.size)
    lateral = float(np.hypot(local[0] - off[0], local[1] - off[1]))
    return float((off[2] - local[2]) / switch_travel()), lateral


def button_top(switch: SceneObject, pose: Pose) -> np.ndarray:
    """World position (3,) of the centre of a switch's top: where the cup presses it
    (and holds it to pull it back up).

    Args:
        switch: The switch.
        pose: Its pose.

    Returns:
        The point, metres.
    """
    return pose.pos + rotation_matrix(pose.quat) @ np.array([0.0, 0.0, switch.size[2] / 2])
