"""The pybullet stand-in computes PyBullet's pure quaternion maths."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.compat.cliport import pybullet_stub as p

angles = st.floats(-math.pi, math.pi, allow_nan=False)


def _same_turn(q0, q1) -> bool:
    return abs(abs(float(np.dot(q0, q1))) - 1.0) < 1e-9  # q and -q are one turn


def test_axis_angle_about_z_is_a_yaw() -> None:
    q = p.getQuaternionFromAxisAngle([0, 0, 2], math.pi / 2)  # the axis need not be unit
    assert _same_turn(q, p.getQuaternionFromEuler((0, 0, math.pi / 2)))
    assert p.rotateVector(q, [1, 0, 0]) == pytest.approx((0, 1, 0), abs=1e-12)
    axis, angle = p.getAxisAngleFromQuaternion(q)
    assert axis == pytest.approx((0, 0, 1)) and angle == pytest.approx(math.pi / 2)
    assert p.getAxisAngleFromQuaternion((0, 0, 0, 1)) == ((1.0, 0.0, 0.0), 0.0)
    with pytest.raises(ValueError, match="axis is zero"):
        p.getQuaternionFromAxisAngle([0, 0, 0], 1.0)


@settings(max_examples=50, deadline=None)
@given(angles, angles, angles, angles, st.floats(0, 1))
def test_difference_and_slerp_join_two_orientations(r0, y0, r1, y1, t) -> None:
    a = p.getQuaternionFromEuler((r0, 0.3, y0))
    b = p.getQuaternionFromEuler((r1, -0.2, y1))
    d = p.getDifferenceQuaternion(a, b)
    # the difference turns a into b (world frame: d * a)
    assert _same_turn(p.multiplyTransforms((0, 0, 0), d, (0, 0, 0), a)[1], b)
    assert _same_turn(p.getQuaternionSlerp(a, b, 0.0), a)
    assert _same_turn(p.getQuaternionSlerp(a, b, 1.0), b)
    mid = p.getQuaternionSlerp(a, b, t)
    whole = p.getAxisAngleFromQuaternion(d)[1]
    part = p.getAxisAngleFromQuaternion(p.getDifferenceQuaternion(a, mid))[1]
    assert part == pytest.approx(t * whole, abs=1e-7)  # the way the slerp goes: the shorter one
