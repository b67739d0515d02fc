"""Minimum-time motions under velocity and acceleration limits (pure numpy).

A move between two points of a space (tool position and yaw for the floating cup,
joint angles for the arm) follows one straight line in that space; the path
parameter ``s`` goes from 0 to 1 on a trapezoidal velocity profile: constant
acceleration, cruise, constant deceleration (a triangle when the move is too
short to reach the cruise speed). The profile is the fastest one that keeps
every axis within its own limits: with ``delta`` the move, axis ``i`` moves at
``|delta_i| * ds/dt``, so ``ds/dt <= min_i vmax_i / |delta_i|`` and likewise for
the acceleration. All axes start and stop together.

A path through several waypoints (up, over, down) is a sum of such moves, each
started a little before the previous one stops (:func:`blend`): the corner is
rounded by at most the distance covered in the overlap, and the robot never
stops at a via point.

A move may also follow a smooth curve through via points (:func:`curve_move`: a
cubic spline in the same space), timed from its start to its end without stopping
at the via points: by the time-optimal parameterisation of the curve under the
per-axis limits (:class:`CurveTiming`), or by one trapezoid slowed down evenly to
the curve's worst point where that is no slower.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

#: A move's shape: its displacement from its start at path parameters ``s``
#: (k,) in [0, 1], shape (k, dims); None: the straight line.
Shape = Callable[[np.ndarray], np.ndarray]
#: Samples of a curve's path parameter where its speed and curvature are bounded.
_CURVE_SAMPLES = 64
#: Intervals of the grid of the path parameter the time-optimal timing works on.
_TOPP_STEPS = 100
#: Share of each limit the time-optimal timing plans for: the limits hold on its
#: grid (each interval's start, middle and end); the margin covers the rest.
_TOPP_MARGIN = 0.98


@dataclass(frozen=True)
class Profile:
    """A trapezoidal profile of the path parameter ``s`` from 0 to 1.

    Attributes:
        duration: Total time (s).
        accel_time: Time spent accelerating (= decelerating), s.
        speed: Peak ``ds/dt`` (1/s).
        accel: ``d2s/dt2`` while accelerating (1/s^2).
    """

    duration: float
    accel_time: float
    speed: float
    accel: float

    def at(self, t: np.ndarray) -> np.ndarray:
        """``s`` at times ``t`` (clipped to [0, duration]).

        Args:
            t: Times (s) since the start of the move.

        Returns:
            ``s`` in [0, 1], same shape as ``t``.
        """
        if self.duration <= 0.0:
            return np.ones_like(t, dtype=float)
        t = np.clip(t, 0.0, self.duration)
        ta, v, a = self.accel_time, self.speed, self.accel
        rise = 0.5 * a * t * t
        cruise = 0.5 * a * ta * ta + v * (t - ta)
        back = self.duration - t
        fall = 1.0 - 0.5 * a * back * back
        return np.where(t < ta, rise, np.where(t > self.duration - ta, fall, cruise))


def profile(delta: np.ndarray, vmax: np.ndarray, amax: np.ndarray,
            min_time: float = 0.0) -> Profile:
    """The minimum-time trapezoidal profile of a straight move by ``delta``.

    Args:
        delta: Displacement per axis.
        vmax: Speed limit per axis (> 0).
        amax: Acceleration limit per axis (> 0).
        min_time: Shortest allowed duration (s); a longer move is slowed down evenly.

    Returns:
        The profile (duration 0 for a move of length 0).
    """
    size = np.abs(np.asarray(delta, dtype=float))
    moving = size > 1e-12
    if not moving.any():
        return Profile(0.0, 0.0, 0.0, 0.0)
    v = float(np.min(np.asarray(vmax, dtype=float)[moving] / size[moving]))
    a = float(np.min(np.asarray(amax, dtype=float)[moving] / size[moving]))
    if v * v / a >= 1.0:  # never reaches the cruise speed: a triangle
        ta = math.sqrt(1.0 / a)
        duration = 2.0 * ta
        v = a * ta
    else:
        ta = v / a
        duration = 1.0 / v + ta
    if duration < min_time:
        # Same shape, slower: scale time by k (speed / k, acceleration / k^2).
        k = min_time / duration
        return Profile(min_time, ta * k, v / k, a / (k * k))
    return Profile(duration, ta, v, a)


def blend(points: list[np.ndarray], profiles: list[Profile | CurveTiming],
          overlap: float | Sequence[float], dt: float,
          shapes: list[Shape | None] | None = None) -> np.ndarray:
    """Sample a path through ``points`` whose consecutive moves overlap in time.

    Move ``k`` (from ``points[k]`` to ``points[k+1]``) starts ``overlap`` seconds
    (at most the shorter of the two accelerations) before move ``k - 1`` ends.

    Args:
        points: Waypoints, each of shape (dims,); at least two.
        profiles: One profile per move (``len(points) - 1``).
        overlap: Wanted overlap (s) between consecutive moves, or one per corner
            (``len(points) - 2`` values).
        dt: Sample period (the physics timestep).
        shapes: Per move, its curve (:func:`curve_move`) or None for the straight
            line; default all straight.

    Returns:
        Samples at ``dt, 2 dt, ...`` up to the end of the last move, shape
        (steps, dims); the last sample is ``points[-1]``.
    """
    laps = ([float(overlap)] * max(0, len(profiles) - 1) if isinstance(overlap, (int, float))
            else list(overlap))
    starts = move_starts(profiles, laps)
    end = max(s + p.duration for s, p in zip(starts, profiles, strict=True))
    n = max(1, math.ceil(end / dt - 1e-9))
    t = dt * np.arange(1, n + 1)
    out = np.repeat(points[0][None, :], n, axis=0).astype(float)
    for k, (start, prof) in enumerate(zip(starts, profiles, strict=True)):
        shape = shapes[k] if shapes is not None else None
        if shape is None:
            out += prof.at(t - start)[:, None] * (points[k + 1] - points[k])[None, :]
        else:
            out += shape(prof.at(t - start))
    out[-1] = points[-1]
    return out


def constant_speed(start: np.ndarray, goal: np.ndarray, duration: float,
                   dt: float) -> np.ndarray:
    """Samples of a constant-speed straight move (guarded approaches).

    Args:
        start: Start point.
        goal: End point.
        duration: Time the move takes (s).
        dt: Sample period.

    Returns:
        Samples at ``dt, 2 dt, ...``, shape (steps, dims), ending at ``goal``.
    """
    n = max(1, math.ceil(duration / dt - 1e-9))
    s = np.arange(1, n + 1, dtype=float) / n
    return start[None, :] + s[:, None] * (goal - start)[None, :]


def curve_move(knots: np.ndarray, vmax: np.ndarray,
               amax: np.ndarray) -> tuple[Shape, Profile | CurveTiming]:
    """A smooth move through ``knots`` (start, via points, end) and its fastest profile.

    The curve is a natural cubic spline through the knots, parameterised by chord length
    (``s`` from 0 to 1). Axis ``i`` moves at ``q_i'(s) ds/dt`` and accelerates at
    ``q_i''(s) (ds/dt)^2 + q_i'(s) d2s/dt2``: the timing is the time-optimal one
    (:class:`CurveTiming`), or, where that is no faster, the trapezoid of
    :func:`profile` under the largest ``|q_i'|``, slowed down evenly until the
    curvature term fits the acceleration limits too.

    Args:
        knots: Points (m, dims), m >= 2, the first the start and the last the end.
        vmax: Speed limit per axis.
        amax: Acceleration limit per axis.

    Returns:
        (shape, profile) for :func:`blend`.
    """
    knots = np.asarray(knots, dtype=float)
    chord = np.linalg.norm(np.diff(knots, axis=0), axis=1)
    total = float(chord.sum())
    if len(knots) < 3 or total <= 1e-12:
        delta = knots[-1] - knots[0]
        return (lambda s: s[:, None] * delta[None, :]), profile(delta, vmax, amax)
    spline = _NaturalSpline(np.concatenate([[0.0], np.cumsum(chord)]) / total, knots)
    us = np.linspace(0.0, 1.0, _CURVE_SAMPLES)
    d1 = np.abs(spline(us, 1)).max(axis=0)
    d2 = np.abs(spline(us, 2)).max(axis=0)
    prof = profile(d1, vmax, amax)
    # Scaling time by k divides the speed by k and both acceleration terms by k^2.
    need = float(((d2 * prof.speed ** 2 + d1 * prof.accel) / np.asarray(amax, float)).max())
    if need > 1.0:
        prof = profile(d1, vmax, amax, min_time=prof.duration * math.sqrt(need))
    start = knots[0]
    # The grid: _TOPP_STEPS even intervals, and at least 8 between two knots however
    # close (a short span of the spline can bend sharply).
    grid = np.unique(np.concatenate([
        np.linspace(a, b, max(8, math.ceil((b - a) * _TOPP_STEPS)) + 1)
        for a, b in itertools.pairwise(spline.u)]))
    timing = CurveTiming.of(spline, np.asarray(vmax, float), np.asarray(amax, float), grid)
    return (lambda s: spline(s) - start[None, :]), (timing if timing.duration < prof.duration
                                                    else prof)


class _NaturalSpline:
    """The natural cubic spline through ``(u[i], y[i])`` (zero curvature at both
    ends), and its first two derivatives; a few knots, so a dense solve is cheap.

    Args:
        u: Increasing parameters (m,), m >= 3.
        y: Values (m, dims).
    """

    def __init__(self, u: np.ndarray, y: np.ndarray) -> None:
        h = np.diff(u)
        slope = np.diff(y, axis=0) / h[:, None]
        m = len(u)
        # Second derivatives at the inner knots: the tridiagonal continuity system.
        a = np.zeros((m - 2, m - 2))
        idx = np.arange(m - 2)
        a[idx, idx] = 2.0 * (h[:-1] + h[1:])
        a[idx[1:], idx[:-1]] = h[1:-1]
        a[idx[:-1], idx[1:]] = h[1:-1]
        curv = np.zeros_like(y)
        curv[1:-1] = np.linalg.solve(a, 6.0 * np.diff(slope, axis=0))
        self.u, self.y, self.h, self.curv = u, y, h, curv
        self.b = slope - h[:, None] * (2.0 * curv[:-1] + curv[1:]) / 6.0

    def __call__(self, s: np.ndarray, derivative: int = 0) -> np.ndarray:
        """Values (or the ``derivative``-th derivative) at ``s`` (k,), shape (k, dims)."""
        i = np.clip(np.searchsorted(self.u, s, side="right") - 1, 0, len(self.h) - 1)
        t = (s - self.u[i])[:, None]
        c0, c1, h = self.curv[i], self.curv[i + 1], self.h[i][:, None]
        jerk = (c1 - c0) / h
        if derivative == 0:
            return self.y[i] + self.b[i] * t + c0 * t * t / 2.0 + jerk * t ** 3 / 6.0
        if derivative == 1:
            return self.b[i] + c0 * t + jerk * t * t / 2.0
        return c0 + jerk * t


class CurveTiming:
    """The time-optimal timing of a curve's path parameter ``s`` from rest to rest.

    Axis ``i`` of the curve ``q(s)`` moves at ``q_i'(s) ds/dt`` and accelerates at
    ``q_i''(s) (ds/dt)^2 + q_i'(s) d2s/dt2``. On a grid of ``s``, with ``x = (ds/dt)^2``
    and ``u = d2s/dt2`` constant over each interval (so ``x`` grows by ``2 u ds``), the
    speed limits bound ``x`` and the acceleration limits bound ``u`` to an interval
    that depends on ``x`` (empty above some ``x``: the curvature term alone would
    break a limit). A backward pass finds at each grid point the largest ``x`` from
    which the motion can still come to rest at the end (the controllable set, as in
    TOPP-RA), a forward pass accelerates as hard as allowed while staying in it.
    Both limits hold at the grid points with :data:`_TOPP_MARGIN` to spare.

    Attributes:
        duration: Total time (s).
        accel_time: The shorter of the time to the end of the first speed-up and
            the time from the start of the last slow-down (s): what a corner of a
            :func:`blend` may overlap, as :attr:`Profile.accel_time`.
    """

    def __init__(self, s: np.ndarray, times: np.ndarray, x: np.ndarray, u: np.ndarray) -> None:
        self._s, self._times, self._u = s, times, u
        self._sdot = np.sqrt(x)
        self.duration = float(times[-1])
        rising = np.flatnonzero(u > 0.0)
        if len(rising) == 0 or not math.isfinite(self.duration):
            self.accel_time = 0.0
        else:
            up = times[int(np.argmax(u <= 0.0))] if (u <= 0.0).any() else self.duration
            down = self.duration - times[rising[-1] + 1]
            self.accel_time = float(min(up, down))

    def at(self, t: np.ndarray) -> np.ndarray:
        """``s`` at times ``t`` (clipped to [0, duration]), same shape as ``t``."""
        t = np.clip(t, 0.0, self.duration)
        i = np.clip(np.searchsorted(self._times, t, side="right") - 1, 0, len(self._u) - 1)
        tau = t - self._times[i]
        return np.clip(self._s[i] + self._sdot[i] * tau + 0.5 * self._u[i] * tau * tau, 0.0, 1.0)

    @classmethod
    def of(cls, curve: Callable[[np.ndarray, int], np.ndarray], vmax: np.ndarray,
           amax: np.ndarray, grid: np.ndarray | None = None) -> CurveTiming:
        """The timing of ``curve(s, derivative)`` (s in [0, 1]) under the per-axis
        limits, on ``grid`` (increasing, from 0 to 1; default :data:`_TOPP_STEPS`
        even intervals); its duration is infinite where the grid leaves no way through."""
        s = np.linspace(0.0, 1.0, _TOPP_STEPS + 1) if grid is None else np.asarray(grid, float)
        steps = len(s) - 1
        h = np.diff(s)
        hh = np.append(h, h[-1])[:, None]
        d1, d2 = curve(s, 1), curve(s, 2)
        vm, am = _TOPP_MARGIN * vmax, _TOPP_MARGIN * amax
        mid = s[:-1] + 0.5 * h
        # The speed limits at each grid point and the middles of both its intervals.
        x_speed = 1.0 / np.maximum(((np.abs(d1) / vm) ** 2).max(axis=1), 1e-300)
        x_mid = 1.0 / np.maximum(((np.abs(curve(mid, 1)) / vm) ** 2).max(axis=1), 1e-300)
        x_speed = np.minimum(x_speed, np.minimum(np.append(x_mid, np.inf),
                                                 np.insert(x_mid, 0, np.inf)))
        # Interval j's u must fit the limits at its start (s_j, x_j), its middle and its
        # end: at s_j + f h, with x_j + 2 f h u, the acceleration is
        # q'' x_j + (q' + 2 f h q'') u there (the middle: where a joint turns back).
        m1, m2 = np.vstack([curve(mid, 1), d1[-1:]]), np.vstack([curve(mid, 2), d2[-1:]])
        e1, e2 = np.vstack([d1[1:], d1[-1:]]), np.vstack([d2[1:], d2[-1:]])
        d1 = np.concatenate([d1, m1 + hh * m2, e1 + 2.0 * hh * e2], axis=1)
        d2 = np.concatenate([d2, m2, e2], axis=1)
        am = np.concatenate([am, am, am])
        flat = np.abs(d1) < 1e-9
        p = np.where(flat, 1e-9, d1)
        half = am / np.abs(p)  # u lies within -k x +- half, per constraint
        k = d2 / p
        # x bounds: the speeds; some u for every pair of constraints; an axis at rest.
        gap = k[:, :, None] - k[:, None, :]
        pair = (half[:, :, None] + half[:, None, :]) / np.where(gap < 0.0, -gap, np.nan)
        x_pair = np.min(np.where(gap < 0.0, pair, np.inf), axis=(1, 2))
        x_still = np.where(flat, am / np.maximum(np.abs(d2), 1e-300), np.inf).min(axis=1)
        x_lim = np.minimum(np.minimum(x_speed, x_pair), x_still)
        # The next x from x: at most min_i (x c_i + b_i) (the largest u), at least
        # max_i (x c_i - b_i) (the smallest).
        c_all, b_all = (1.0 - 2.0 * hh * k).tolist(), (2.0 * hh * half).tolist()
        lim = x_lim.tolist()
        reach = [0.0] * (steps + 1)  # backward: the largest x that can still stop
        for j in range(steps - 1, 0, -1):
            nxt, best = reach[j + 1], lim[j]
            for c, b in zip(c_all[j], b_all[j], strict=True):
                if c > 0.0 and (nxt + b) / c < best:
                    best = (nxt + b) / c
            reach[j] = max(best, 0.0)
        x = [0.0] * (steps + 1)  # forward: as fast as the limits and the stop allow
        for j in range(steps - 1):
            xj = x[j]
            grow = min(xj * c + b for c, b in zip(c_all[j], b_all[j], strict=True))
            x[j + 1] = max(0.0, min(reach[j + 1], grow))
        xs = np.array(x)
        u = np.diff(xs) / (2.0 * h)
        root = np.sqrt(xs)
        with np.errstate(divide="ignore"):
            dt = np.where(root[:-1] + root[1:] > 0.0, 2.0 * h / (root[:-1] + root[1:]), np.inf)
        times = np.concatenate([[0.0], np.cumsum(dt)])
        return cls(s, times, xs, u)


def move_starts(profiles: list[Profile | CurveTiming], overlap: Sequence[float]) -> list[float]:
    """Start time (s) of each move of a :func:`blend`: each starts ``overlap``
    (per corner; at most the shorter of the two accelerations) before the
    previous one ends."""
    starts = [0.0]
    for (prev, nxt), wanted in zip(itertools.pairwise(profiles), overlap, strict=True):
        starts.append(starts[-1] + prev.duration - min(wanted, prev.accel_time, nxt.accel_time))
    return starts
