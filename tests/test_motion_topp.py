"""The time-optimal timing of a curve (sim/robots/motion.py: CurveTiming, curve_move).

Property: for random knots and limits, the joint samples a blend plays at the physics
timestep stay within the velocity and acceleration limits (finite differences, with
5 % for the discretisation: the timing plans for 98 % of each limit at the start,
middle and end of each interval of its grid of the path parameter), start and end at
rest at the knots, and take no longer than the trapezoid slowed down evenly to the
curve's worst point (the timing before it).
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.sim.robots.motion import (
    _CURVE_SAMPLES,
    CurveTiming,
    _NaturalSpline,
    blend,
    curve_move,
    move_starts,
    profile,
)

DT = 0.002
TOL = 1.05


def _even_slowdown(knots: np.ndarray, vmax: np.ndarray, amax: np.ndarray) -> float:
    """The duration of the timing curve_move used before (one trapezoid slowed down)."""
    chord = np.linalg.norm(np.diff(knots, axis=0), axis=1)
    spline = _NaturalSpline(np.concatenate([[0.0], np.cumsum(chord)]) / chord.sum(), knots)
    us = np.linspace(0.0, 1.0, _CURVE_SAMPLES)
    d1 = np.abs(spline(us, 1)).max(axis=0)
    d2 = np.abs(spline(us, 2)).max(axis=0)
    prof = profile(d1, vmax, amax)
    need = float(((d2 * prof.speed ** 2 + d1 * prof.accel) / amax).max())
    if need > 1.0:
        prof = profile(d1, vmax, amax, min_time=prof.duration * math.sqrt(need))
    return prof.duration


@st.composite
def _cases(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    dims = draw(st.integers(1, 6))
    m = draw(st.integers(3, 6))
    seed = draw(st.integers(0, 2**31 - 1))
    rng = np.random.default_rng(seed)
    steps = rng.normal(scale=draw(st.floats(0.05, 1.0)), size=(m - 1, dims))
    knots = np.cumsum(np.vstack([rng.normal(size=(1, dims)), steps]), axis=0)
    vmax = rng.uniform(0.5, 4.0, size=dims)
    amax = rng.uniform(2.0, 40.0, size=dims)
    return knots, vmax, amax


@settings(max_examples=200, deadline=None)
@given(_cases())
def test_curve_timing_keeps_the_limits_and_is_never_slower(case) -> None:
    knots, vmax, amax = case
    shape, timing = curve_move(knots, vmax, amax)
    assert timing.duration <= _even_slowdown(knots, vmax, amax) + 1e-9
    samples = blend([knots[0], knots[-1]], [timing], 0.0, DT, [shape])
    # At rest before the start and after the end.
    path = np.vstack([knots[0], knots[0], samples, knots[-1]])
    np.testing.assert_allclose(samples[-1], knots[-1], atol=1e-9)
    vel = np.diff(path, axis=0) / DT
    acc = np.diff(path, 2, axis=0) / DT**2
    assert (np.abs(vel) <= TOL * vmax).all()
    assert (np.abs(acc) <= TOL * amax).all()
    # Starts and ends at rest: the first and last steps are tiny.
    assert np.abs(vel[1]).max() <= TOL * amax.max() * DT
    assert np.abs(vel[-1]).max() <= TOL * amax.max() * DT


def test_curve_timing_is_monotone_and_ends_at_one() -> None:
    knots = np.array([[0.0, 0.0, 0.0], [0.3, 0.1, -0.2], [0.7, 0.15, -0.3], [1.0, 0.1, -0.2]])
    chord = np.linalg.norm(np.diff(knots, axis=0), axis=1)
    spline = _NaturalSpline(np.concatenate([[0.0], np.cumsum(chord)]) / chord.sum(), knots)
    timing = CurveTiming.of(spline, np.full(3, 2.0), np.full(3, 12.0))
    t = np.linspace(-0.1, timing.duration + 0.1, 2001)
    s = timing.at(t)
    assert (np.diff(s) >= -1e-12).all()
    assert s[0] == 0.0 and s[-1] == 1.0
    assert 0.0 < timing.accel_time < timing.duration / 2


def test_curve_timing_corners_overlap_like_a_profile() -> None:
    # move_starts reads accel_time of a curve's timing as of a trapezoid.
    knots = np.array([[0.0, 0.0], [0.4, 0.2], [0.8, 0.1]])
    _, timing = curve_move(knots, np.full(2, 2.0), np.full(2, 12.0))
    straight = profile(np.array([0.0, -0.1]), np.full(2, 2.0), np.full(2, 12.0))
    starts = move_starts([timing, straight], [1.0])
    assert starts[1] == timing.duration - min(timing.accel_time, straight.accel_time)
