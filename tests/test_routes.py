"""The route planner round rectangles (factask.scene.routes), which the oracle's pushes
and rope carries share: geometry, waypoints, and the search (fewest legs, then cheapest)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from factask.scene.objects import Area
from factask.scene.routes import (
    RouteMap,
    crosses,
    gap_to,
    grown,
    inside,
    keeps_clearance,
    ring_points,
)

CLEAR = 0.02
STEP = 0.004


def _rect(x: float, y: float, hx: float, hy: float, yaw: float = 0.0) -> Area:
    return Area(np.array([x, y]), yaw, np.array([hx, hy]))


def _to(goal: np.ndarray, rects: list[Area]):
    def leg(q: np.ndarray) -> tuple[float, int]:
        ok = keeps_clearance(q, goal, rects, CLEAR, STEP)
        return (float(np.linalg.norm(goal - q)), 0) if ok else (math.inf, 0)
    return leg


def _clear(rects: list[Area]):
    return lambda p, q: keeps_clearance(p, q, rects, CLEAR, STEP)


def _plan(a: np.ndarray, b: np.ndarray, rects: list[Area], leg_cost: float = 0.0):
    nodes = ring_points([grown(r, CLEAR) for r in rects], 0.01, edges=True)
    return RouteMap(nodes, _to(b, rects), _clear(rects), leg_cost).route_from(
        a, _to(b, rects), _clear(rects))


def test_geometry_of_one_rectangle() -> None:
    r = _rect(0.0, 0.0, 0.1, 0.05, yaw=math.pi / 2)  # turned: 0.05 along x, 0.1 along y
    assert inside(r, np.array([0.0, 0.09])) and not inside(r, np.array([0.09, 0.0]))
    assert crosses(np.array([-0.2, 0.0]), np.array([0.2, 0.0]), r)
    assert not crosses(np.array([-0.2, 0.2]), np.array([0.2, 0.2]), r)
    assert math.isclose(gap_to(np.array([0.15, 0.0]), [r]), 0.1)
    assert gap_to(np.array([0.0, 0.0]), [r]) == 0.0 and gap_to(np.zeros(2), []) == math.inf
    assert len(ring_points([r], 0.01, edges=False)) == 4
    ring = ring_points([r], 0.01, edges=True)
    assert len(ring) == 8 and all(math.isclose(gap_to(p, [r]), 0.01) or gap_to(p, [r]) > 0.01
                                  for p in ring)


def test_a_clear_line_is_one_leg_and_a_blocked_one_goes_round() -> None:
    a, b = np.array([0.3, 0.0]), np.array([0.7, 0.0])
    straight = _plan(a, b, [_rect(0.5, 0.3, 0.04, 0.04)])
    assert straight is not None and straight.legs == 1 and straight.via is None
    round_ = _plan(a, b, [_rect(0.5, 0.0, 0.04, 0.04)])
    assert round_ is not None and round_.legs >= 2 and round_.via is not None
    assert round_.length > 0.4  # longer than the straight line it avoids


def test_a_wall_with_no_gap_has_no_route() -> None:
    wall = [_rect(0.5, 0.0, 0.01, 1.0)]  # a long thin wall across the way, no end in reach
    nodes = [p for p in ring_points([grown(r, CLEAR) for r in wall], 0.01, edges=True)
             if abs(p[1]) < 0.5]  # only waypoints beside the wall, none round its ends
    a, b = np.array([0.3, 0.0]), np.array([0.7, 0.0])
    routes = RouteMap(nodes, _to(b, wall), _clear(wall))
    assert routes.route_from(a, _to(b, wall), _clear(wall)) is None


def test_fewer_legs_win_over_a_shorter_way_and_the_leg_cost_counts() -> None:
    # Two goals: one straight but far, one near behind a block.
    rects = [_rect(0.5, 0.0, 0.04, 0.04)]
    far, near = np.array([0.3, 0.6]), np.array([0.62, 0.0])

    def two_goals(q: np.ndarray) -> tuple[float, int]:
        best = (math.inf, 0)
        for k, g in enumerate((far, near)):
            if keeps_clearance(q, g, rects, CLEAR, STEP):
                best = min(best, (float(np.linalg.norm(g - q)), k))
        return best

    nodes = ring_points([grown(r, CLEAR) for r in rects], 0.01, edges=True)
    route = RouteMap(nodes, two_goals, _clear(rects)).route_from(
        np.array([0.38, 0.0]), two_goals, _clear(rects))
    assert route is not None and route.legs == 1 and route.goal == 0  # straight to the far one
    costly = RouteMap(nodes, _to(near, rects), _clear(rects), leg_cost=0.05).route_from(
        np.array([0.38, 0.0]), _to(near, rects), _clear(rects))
    free = RouteMap(nodes, _to(near, rects), _clear(rects)).route_from(
        np.array([0.38, 0.0]), _to(near, rects), _clear(rects))
    assert costly is not None and free is not None
    assert math.isclose(costly.length - free.length, 0.05 * (costly.legs - 1))


@given(x=st.floats(0.4, 0.6), y=st.floats(-0.1, 0.1), yaw=st.floats(-math.pi, math.pi),
       hx=st.floats(0.01, 0.08), hy=st.floats(0.01, 0.08), ang=st.floats(-math.pi, math.pi))
def test_every_leg_of_a_route_is_clear(x: float, y: float, yaw: float, hx: float, hy: float,
                                       ang: float) -> None:
    rects = [_rect(x, y, hx, hy, yaw)]
    u = np.array([math.cos(ang), math.sin(ang)])
    reach = math.hypot(hx, hy) + 0.06
    a, b = np.array([x, y]) - reach * u, np.array([x, y]) + reach * u
    clear = _clear(rects)
    here, legs = a, 0
    while True:  # follow the first waypoints until the goal is in sight
        route = _plan(here, b, rects)
        assert route is not None, "a lone rectangle always has a way round"
        legs += 1
        if route.via is None:
            assert clear(here, b)
            break
        assert clear(here, route.via)
        assert legs <= 4, "each waypoint brings the goal closer in legs"
        here = route.via
