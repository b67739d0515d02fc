"""Routes round rectangles on the table: the one planner the oracle's pushes and rope
carries share.

A route runs from a start to a goal, straight or through waypoints set round
rectangular obstacles (:class:`~factask.scene.objects.Area`: centre, yaw, half
extents; a disk counts as its bounding square). Two things are the caller's:

* **which legs are clear**: a push's corridor may not run through a grown rectangle
  (:func:`crosses`); a carried rope segment's line keeps a clearance from every
  footprint (:func:`keeps_clearance`, sampled, its ends aside);
* **where a route may end**: a zone entered (the nearest of several), a point reached.

:class:`RouteMap` searches the waypoints' visibility graph from the goals backwards
(Dijkstra; each leg costs its length plus ``leg_cost``; a leg is checked only when it
could improve a waypoint), then :meth:`RouteMap.route_from` takes, from a start, the
route with the fewest legs and the cheapest among those. Only the first waypoint
matters to the caller: one action goes there, the next plans on from where it ends.

Pure NumPy, like the rest of :mod:`factask.scene`.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from factask.scene.objects import Area, yaw_rotation_2d

#: A goal leg from a point: (its length, which goal), or (inf, _) when none is clear.
GoalLeg = Callable[[np.ndarray], tuple[float, int]]
#: Whether the straight leg between two points is clear.
LegClear = Callable[[np.ndarray, np.ndarray], bool]


# ------------------------------------------------------------------ geometry
def grown(rect: Area, by: float) -> Area:
    """``rect`` as a rectangle (a disk: its bounding square) with every side moved out by ``by``."""
    return Area(rect.center, rect.yaw, rect.half + by)


def inside(rect: Area, p: np.ndarray) -> bool:
    """``p`` strictly inside ``rect`` (as a rectangle)."""
    local = np.abs((p - rect.center) @ yaw_rotation_2d(rect.yaw))
    return bool(np.all(local < rect.half))


def crosses(a: np.ndarray, b: np.ndarray, rect: Area) -> bool:
    """True when the segment ``a``-``b`` runs through the inside of ``rect`` (a
    disk taken as its bounding square); touching its edge does not count."""
    rot = yaw_rotation_2d(rect.yaw)
    p, d = (a - rect.center) @ rot, (b - a) @ rot
    t0, t1 = 0.0, 1.0
    for i in range(2):
        h = float(rect.half[i])
        if abs(d[i]) < 1e-12:
            if abs(p[i]) >= h:
                return False
            continue
        lo, hi = sorted(((-h - p[i]) / d[i], (h - p[i]) / d[i]))
        t0, t1 = max(t0, lo), min(t1, hi)
    return t1 - t0 > 1e-9


def gap_to(point: np.ndarray, rects: Sequence[Area]) -> float:
    """The distance (m) from an (x, y) point to the nearest rectangle (0 inside one;
    inf without any)."""
    out = math.inf
    for rect in rects:
        local = yaw_rotation_2d(-rect.yaw) @ (np.asarray(point, dtype=float) - rect.center)
        out = min(out, float(np.linalg.norm(np.maximum(np.abs(local) - rect.half, 0.0))))
    return out


def keeps_clearance(a: np.ndarray, b: np.ndarray, rects: Sequence[Area], clearance: float,
                    step: float) -> bool:
    """True when the straight line from ``a`` to ``b`` keeps ``clearance`` from every
    rectangle, checked every ``step`` metres with its first and last step aside (an
    end may lie close to an object, as a rope's end beside its anchor does)."""
    steps = max(1, math.ceil(float(np.linalg.norm(b - a)) / step))
    return all(gap_to(a + (b - a) * k / steps, rects) >= clearance for k in range(1, steps))


def ring_points(rects: Sequence[Area], out: float | np.ndarray, edges: bool) -> list[np.ndarray]:
    """Points round each rectangle, ``out`` beyond its sides: its four corners, and with
    ``edges`` its four edge middles too (corners and middles in row order, x outer)."""
    signs = (-1, 0, 1) if edges else (-1, 1)
    points = []
    for rect in rects:
        reach, rot = rect.half + out, yaw_rotation_2d(rect.yaw)
        points += [rect.center + rot @ (reach * np.array([sx, sy]))
                   for sx in signs for sy in signs if sx or sy]
    return points


# -------------------------------------------------------------------- search
@dataclass(frozen=True)
class Route:
    """A way from a start to a goal.

    Attributes:
        legs: Straight legs (1: straight to the goal).
        length: Its cost: the legs' lengths plus ``leg_cost`` per waypoint.
        via: The first waypoint (x, y), or None for the straight way.
        goal: Which goal it ends at (the caller's index).
    """

    legs: int
    length: float
    via: np.ndarray | None
    goal: int


class RouteMap:
    """Waypoints and each one's cheapest way on to a goal (Dijkstra from the goals).

    Args:
        nodes: The waypoints (x, y).
        goal_leg: A waypoint's straight leg to a goal (see :data:`GoalLeg`).
        clear: Whether the leg between two waypoints is clear.
        leg_cost: What each leg costs beyond its length (m): fewer turns are worth it.
    """

    def __init__(self, nodes: Sequence[np.ndarray], goal_leg: GoalLeg, clear: LegClear,
                 leg_cost: float = 0.0) -> None:
        self.nodes, self.leg_cost = list(nodes), float(leg_cost)
        n = len(self.nodes)
        ends = [goal_leg(v) for v in self.nodes]
        self.cost = [c for c, _ in ends]
        self.goal = [k for _, k in ends]
        self.legs = [1] * n
        heap = [(c, j) for j, c in enumerate(self.cost) if c < math.inf]
        heapq.heapify(heap)
        done = [False] * n
        while heap:
            c, j = heapq.heappop(heap)
            if done[j] or c > self.cost[j]:
                continue
            done[j] = True
            for i in range(n):
                if i == j or done[i]:
                    continue
                cand = c + float(np.linalg.norm(self.nodes[j] - self.nodes[i])) + self.leg_cost
                if cand < self.cost[i] and clear(self.nodes[i], self.nodes[j]):
                    self.cost[i], self.legs[i], self.goal[i] = cand, self.legs[j] + 1, self.goal[j]
                    heapq.heappush(heap, (cand, i))

    def route_from(self, start: np.ndarray, goal_leg: GoalLeg, clear: LegClear,
                   min_leg: float = 0.0) -> Route | None:
        """The route from ``start`` with the fewest legs, the cheapest among those.

        Args:
            start: Where it starts (x, y).
            goal_leg: The start's straight leg to a goal (the start may see the
                obstacles differently from the waypoints: from inside a grown one).
            clear: Whether the leg from the start to a waypoint is clear.
            min_leg: Waypoints closer than this to the start are not taken (m).

        Returns:
            The route, or None when no goal can be reached.
        """
        start = np.asarray(start, dtype=float)
        best: Route | None = None
        straight, k = goal_leg(start)
        if straight < math.inf:
            best = Route(1, straight, None, k)
        for j, v in enumerate(self.nodes):
            if self.cost[j] == math.inf or float(np.linalg.norm(v - start)) < min_leg:
                continue
            total = float(np.linalg.norm(v - start)) + self.leg_cost + self.cost[j]
            if (best is None or (self.legs[j] + 1, total) < (best.legs, best.length)) \
                    and clear(start, v):
                best = Route(self.legs[j] + 1, total, v, self.goal[j])
        return best
