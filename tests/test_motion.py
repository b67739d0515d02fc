"""Minimum-time motions (sim/robots/motion.py): profiles, blends and curves through via points."""

from __future__ import annotations

import itertools

import numpy as np

from factask.sim.robots.motion import blend, curve_move, profile

DT = 0.002
VMAX = np.array([2.0, 2.0, 3.0])
AMAX = np.array([12.0, 12.0, 12.0])


def _limits_hold(samples: np.ndarray, slack: float = 1.05) -> tuple[bool, bool]:
    vel = np.diff(samples, axis=0) / DT
    acc = np.diff(samples, 2, axis=0) / DT**2
    return (bool((np.abs(vel).max(axis=0) <= slack * VMAX).all()),
            bool((np.abs(acc).max(axis=0) <= slack * AMAX).all()))


def test_curve_move_goes_through_its_ends_within_the_limits() -> None:
    knots = np.array([[0.0, 0.0, 0.0], [0.3, 0.1, -0.2], [0.7, 0.15, -0.3], [1.0, 0.1, -0.2]])
    shape, prof = curve_move(knots, VMAX, AMAX)
    start, end = knots[0], knots[-1]
    np.testing.assert_allclose(shape(np.array([0.0]))[0], 0.0, atol=1e-12)
    np.testing.assert_allclose(shape(np.array([1.0]))[0], end - start, atol=1e-12)
    samples = blend([start, end], [prof], 0.0, DT, [shape])
    np.testing.assert_allclose(samples[-1], end)
    speed_ok, accel_ok = _limits_hold(np.vstack([start, samples]))
    assert speed_ok and accel_ok


def test_curve_move_is_faster_than_stopping_at_each_via_point() -> None:
    knots = np.array([[0.0, 0.0, 0.0], [0.4, 0.05, 0.1], [0.8, 0.05, 0.2], [1.2, 0.0, 0.3]])
    _, prof = curve_move(knots, VMAX, AMAX)
    stops = sum(profile(b - a, VMAX, AMAX).duration for a, b in itertools.pairwise(knots))
    assert prof.duration < stops


def test_curve_move_of_two_knots_is_the_straight_move() -> None:
    a, b = np.zeros(3), np.array([0.5, -0.2, 0.1])
    shape, prof = curve_move(np.array([a, b]), VMAX, AMAX)
    assert prof == profile(b - a, VMAX, AMAX)
    np.testing.assert_allclose(shape(np.array([0.5]))[0], 0.5 * (b - a))


def test_natural_spline_matches_scipy() -> None:
    from scipy.interpolate import CubicSpline

    from factask.sim.robots.motion import _NaturalSpline

    u = np.array([0.0, 0.3, 0.55, 1.0])
    y = np.random.default_rng(0).normal(size=(4, 6))
    ours, ref = _NaturalSpline(u, y), CubicSpline(u, y, axis=0, bc_type="natural")
    s = np.linspace(0.0, 1.0, 101)
    for derivative in (0, 1, 2):
        np.testing.assert_allclose(ours(s, derivative), ref(s, derivative), atol=1e-9)
