"""Pose maths in PyBullet's conventions (quaternions x, y, z, w).

CLIPort code passes poses as ``(position, quaternion_xyzw)`` pairs and relies on
PyBullet for products and inverses. These are the same operations in numpy, so
the stand-in ``pybullet`` module and ``cliport.utils.utils`` need no physics
server. factask itself uses (w, x, y, z) (:mod:`factask.geometry`); the two
helpers at the bottom convert.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from factask.compat.cliport.errors import PoseError
from factask.geometry import yaw_of

#: The identity rotation, x, y, z, w.
IDENTITY_XYZW = (0.0, 0.0, 0.0, 1.0)

PoseLike = tuple[Sequence[float], Sequence[float]]


def as_quat_xyzw(quat: Any) -> np.ndarray:
    """A normalised (4,) float array from any x, y, z, w sequence.

    Raises:
        PoseError: not four finite numbers, or a zero quaternion.
    """
    q = np.asarray(quat, dtype=float).reshape(-1)
    if q.shape != (4,) or not np.all(np.isfinite(q)):
        raise PoseError(f"expected a quaternion (x, y, z, w), got {quat!r}")
    n = float(np.linalg.norm(q))
    if n == 0.0:
        raise PoseError("zero quaternion")
    return q / n


def split_pose(pose: Any) -> tuple[np.ndarray, np.ndarray]:
    """Position (3,) and quaternion xyzw (4,) of a CLIPort pose.

    Accepts ``(position, quaternion)`` pairs and, as GenSim does, a bare position
    (three numbers), which means "no rotation".

    Raises:
        PoseError: the value is neither form.
    """
    if len(pose) == 3 and not hasattr(pose[0], "__len__"):
        return _finite(np.asarray(pose, dtype=float).reshape(3)), np.array(IDENTITY_XYZW)
    if len(pose) != 2:
        raise PoseError(f"expected a pose (position, quaternion), got {pose!r}")
    pos = np.asarray(pose[0], dtype=float).reshape(-1)
    if pos.shape != (3,):
        raise PoseError(f"expected a 3-D position, got {pose[0]!r}")
    return _finite(pos), as_quat_xyzw(pose[1])


def _finite(pos: np.ndarray) -> np.ndarray:
    """``pos`` if every coordinate is a finite number (a 0/0 spacing gives NaN)."""
    if not np.all(np.isfinite(pos)):
        raise PoseError(f"position {tuple(float(v) for v in pos)} is not finite")
    return pos


def rotation(quat_xyzw: Any) -> Rotation:
    """A scipy Rotation of an x, y, z, w quaternion."""
    return Rotation.from_quat(as_quat_xyzw(quat_xyzw))


def multiply(pose0: Any, pose1: Any) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """``pose0 * pose1`` as PyBullet's ``multiplyTransforms`` returns it."""
    p0, q0 = split_pose(pose0)
    p1, q1 = split_pose(pose1)
    r0 = rotation(q0)
    pos = p0 + r0.apply(p1)
    quat = (r0 * rotation(q1)).as_quat()
    return tuple(float(c) for c in pos), tuple(float(c) for c in quat)


def invert(pose: Any) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Inverse pose, as PyBullet's ``invertTransform`` returns it."""
    pos, quat = split_pose(pose)
    inv = rotation(quat).inv()
    return tuple(float(c) for c in -inv.apply(pos)), tuple(float(c) for c in inv.as_quat())


def rotation_wxyz(quat_wxyz: Any) -> Rotation:
    """A scipy Rotation of a MuJoCo (w, x, y, z) quaternion (scipy normalises it)."""
    w, x, y, z = (float(c) for c in np.asarray(quat_wxyz, dtype=float).reshape(4))
    return Rotation.from_quat([x, y, z, w])


def matrix(quat_xyzw: Any) -> tuple[float, ...]:
    """Row-major 3x3 rotation matrix as a flat 9-tuple (``getMatrixFromQuaternion``)."""
    return tuple(float(c) for c in rotation(quat_xyzw).as_matrix().reshape(-1))


def yaw_of_xyzw(quat_xyzw: Any) -> float:
    """Rotation about world z (radians, in (-pi, pi]) of an x, y, z, w quaternion."""
    return yaw_of(xyzw_to_wxyz(quat_xyzw))


def xyzw_to_wxyz(quat_xyzw: Any) -> np.ndarray:
    """Reorder a PyBullet quaternion into MuJoCo's (w, x, y, z)."""
    x, y, z, w = as_quat_xyzw(quat_xyzw)
    return np.array([w, x, y, z])


def wxyz_to_xyzw(quat_wxyz: Any) -> np.ndarray:
    """Reorder a MuJoCo quaternion into PyBullet's (x, y, z, w)."""
    w, x, y, z = (float(c) for c in np.asarray(quat_wxyz, dtype=float).reshape(4))
    return as_quat_xyzw((x, y, z, w))


def footprint_separation(a: tuple[np.ndarray, float, tuple[float, float]],
                         b: tuple[np.ndarray, float, tuple[float, float]]) -> np.ndarray | None:
    """The shortest XY move of footprint ``b`` that clears footprint ``a``.

    Args:
        a: A turned rectangle: centre (x, y), yaw (rad), half extents (x, y).
        b: Another, in the same form.

    Returns:
        The move (2,), its length the overlap's depth, or None if they do not
        overlap (separating-axis test on both rectangles' axes).
    """
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
