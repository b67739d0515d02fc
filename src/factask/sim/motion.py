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
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np


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


def blend(points: list[np.ndarray], profiles: list[Profile], overlap: float,
          dt: float) -> np.ndarray:
    """Sample a path through ``points`` whose consecutive moves overlap in time.

    Move ``k`` (from ``points[k]`` to ``points[k+1]``) starts ``overlap`` seconds
    (at most the shorter of the two accelerations) before move ``k - 1`` ends.

    Args:
        points: Waypoints, each of shape (dims,); at least two.
        profiles: One profile per move (``len(points) - 1``).
        overlap: Wanted overlap (s) between consecutive moves.
        dt: Sample period (the physics timestep).

    Returns:
        Samples at ``dt, 2 dt, ...`` up to the end of the last move, shape
        (steps, dims); the last sample is ``points[-1]``.
    """
    starts = [0.0]
    for prev, nxt in itertools.pairwise(profiles):
        lap = min(overlap, prev.accel_time, nxt.accel_time)
        starts.append(starts[-1] + prev.duration - lap)
    end = max(s + p.duration for s, p in zip(starts, profiles, strict=True))
    n = max(1, math.ceil(end / dt - 1e-9))
    t = dt * np.arange(1, n + 1)
    out = np.repeat(points[0][None, :], n, axis=0).astype(float)
    for k, (start, prof) in enumerate(zip(starts, profiles, strict=True)):
        out += prof.at(t - start)[:, None] * (points[k + 1] - points[k])[None, :]
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
