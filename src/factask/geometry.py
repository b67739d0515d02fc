"""Small pure-numpy pose helpers shared by layout, checks, robot and oracle.

Conventions: positions in metres (world frame, z up, table top at z = 0);
quaternions are MuJoCo's (w, x, y, z); yaw is a rotation about world z in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class Pose:
    """A rigid pose: position (3,) and unit quaternion (w, x, y, z)."""

    pos: np.ndarray
    quat: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0, 0.0]))

    def __post_init__(self) -> None:
        object.__setattr__(self, "pos", np.asarray(self.pos, dtype=float).reshape(3))
        q = np.asarray(self.quat, dtype=float).reshape(4)
        n = np.linalg.norm(q)
        if np.isfinite(n) and n > 0:
            q = q / n
        elif n == 0:
            q = np.array([1.0, 0.0, 0.0, 0.0])  # no rotation given
        # A non-finite quaternion stays non-finite: callers must see the NaN.
        object.__setattr__(self, "quat", q)

    @property
    def finite(self) -> bool:
        """True if position and orientation are finite numbers."""
        return bool(np.isfinite(self.pos).all() and np.isfinite(self.quat).all())

    @staticmethod
    def from_xyz_yaw(x: float, y: float, z: float, yaw: float = 0.0) -> Pose:
        return Pose(np.array([x, y, z]), quat_from_yaw(yaw))

    @property
    def yaw(self) -> float:
        return yaw_of(self.quat)

    def to_list(self) -> list[float]:
        return [*map(float, self.pos), *map(float, self.quat)]


def wrap_angle(angle: float) -> float:
    """``angle`` (radians) wrapped into (-pi, pi]."""
    return math.atan2(math.sin(angle), math.cos(angle))


def quat_from_yaw(yaw: float) -> np.ndarray:
    """Quaternion (w, x, y, z) of a rotation by ``yaw`` radians about z."""
    return np.array([math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2)])


def quat_from_axis_angle(axis: tuple[float, float, float], angle: float) -> np.ndarray:
    """Quaternion (w, x, y, z) of a rotation by ``angle`` radians about the unit ``axis``
    (components that are zero come out as +0.0, never -0.0)."""
    s = math.sin(angle / 2)
    return np.array([math.cos(angle / 2), *(s * float(a) + 0.0 for a in axis)])


def yaw_of(quat: np.ndarray) -> float:
    """Yaw (radians, in (-pi, pi]) of a quaternion (w, x, y, z)."""
    w, x, y, z = (float(c) for c in quat)
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def quat_mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Hamilton product a * b of (w, x, y, z) quaternions."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array([
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    ])


def quat_conj(q: np.ndarray) -> np.ndarray:
    return np.array([q[0], -q[1], -q[2], -q[3]])


def rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Rotate vector ``v`` by quaternion ``q``."""
    p = np.array([0.0, *v])
    return quat_mul(quat_mul(q, p), quat_conj(q))[1:]


def compose(a: Pose, b: Pose) -> Pose:
    """a * b: pose ``b`` expressed in frame ``a``, in the world."""
    return Pose(a.pos + rotate(a.quat, b.pos), quat_mul(a.quat, b.quat))


def inverse(a: Pose) -> Pose:
    qi = quat_conj(a.quat)
    return Pose(-rotate(qi, a.pos), qi)


def slerp(q0: np.ndarray, q1: np.ndarray, s: float) -> np.ndarray:
    """Spherical interpolation of unit quaternions (w, x, y, z), shortest way."""
    q0 = np.asarray(q0, dtype=float)
    q1 = np.asarray(q1, dtype=float)
    dot = float(np.dot(q0, q1))
    if dot < 0.0:
        q1, dot = -q1, -dot
    if dot > 0.9995:
        q = q0 + s * (q1 - q0)
        return q / np.linalg.norm(q)
    theta = math.acos(dot)
    return (math.sin((1 - s) * theta) * q0 + math.sin(s * theta) * q1) / math.sin(theta)


def rotation_matrix(quat: np.ndarray) -> np.ndarray:
    """3x3 rotation matrix of a unit quaternion (w, x, y, z)."""
    w, x, y, z = (float(c) for c in np.asarray(quat, dtype=float))
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def without_roll(quat: np.ndarray) -> np.ndarray:
    """The orientation with the same x axis and no turn about it (a yaw, then a pitch).

    A body symmetric about its x axis (a lying cylinder, ``log``) looks the same
    however far it has rolled; this is its orientation read modulo that roll, so its
    tilt is its axis's slope and its top is up.
    """
    x_axis = rotation_matrix(quat)[:, 0]
    yaw = math.atan2(x_axis[1], x_axis[0])
    pitch = math.atan2(-x_axis[2], math.hypot(x_axis[0], x_axis[1]))
    return quat_mul(quat_from_yaw(yaw), quat_from_axis_angle((0.0, 1.0, 0.0), pitch))


def tilt_deg(quat: np.ndarray) -> float:
    """Angle (degrees) between the body's z axis and world z (0 = upright)."""
    zaxis = rotate(np.asarray(quat, dtype=float), np.array([0.0, 0.0, 1.0]))
    return math.degrees(math.acos(max(-1.0, min(1.0, float(zaxis[2])))))


def yaw_error_deg(yaw_a: float, yaw_b: float, symmetry_deg: float) -> float:
    """Smallest yaw difference in degrees modulo ``symmetry_deg``.

    ``symmetry_deg`` 0 means any yaw is equivalent (error 0); 360 means no symmetry.
    """
    if symmetry_deg <= 0:
        return 0.0
    d = math.degrees(yaw_a - yaw_b) % symmetry_deg
    return min(d, symmetry_deg - d)
