"""The push oracle keeps clear of other goals' regions (``factask.sim.oracle.push``)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from factask.graph import parse_graph
from factask.graph.taskgraph import TaskGraph
from factask.scene.objects import Area
from factask.scene.routes import crosses
from factask.sim.oracle.push import (
    CLEARANCE,
    LEAD,
    entry_distance,
    obstacle_regions,
    plan_route,
)
from factask.sim.robots.spatula import BLADE_WIDTH

ZONE = Area(np.array([0.55, 0.3]), 0.0, np.array([0.075, 0.075]))
BACK = 0.02


def _grown(rect: Area) -> Area:
    return Area(rect.center, rect.yaw, rect.half + BLADE_WIDTH / 2 + CLEARANCE)


def _corridors(p: np.ndarray, via: np.ndarray | None, zone: Area) -> list[tuple]:
    """The first leg's corridor as the route planner checks it."""
    target = zone.center if via is None else via
    u = (target - p) / np.linalg.norm(target - p)
    end = p + u * entry_distance(zone, p, u, 0.0) if via is None else via + u * LEAD
    return [(p - u * BACK, end)]


def test_crosses_counts_the_inside_only() -> None:
    rect = Area(np.zeros(2), 0.3, np.array([0.05, 0.02]))
    assert crosses(np.array([-0.2, 0.0]), np.array([0.2, 0.0]), rect)
    assert not crosses(np.array([-0.2, 0.1]), np.array([0.2, 0.1]), rect)
    assert not crosses(np.array([-0.2, 0.0]), np.array([-0.1, 0.0]), rect)  # stops short


def test_without_regions_every_block_goes_straight_in() -> None:
    routes = plan_route(np.array([[0.5, -0.3], [0.4, 0.0]]), [ZONE], [], BACK)
    assert all(r is not None and r.legs == 1 and r.via is None for r in routes)


def test_a_region_on_the_straight_line_is_gone_around() -> None:
    block = np.array([0.5, -0.4])
    region = Area(np.array([0.54, -0.18]), 0.0, np.array([0.075, 0.075]))
    assert crosses(block, ZONE.center, _grown(region))  # the straight push would sweep it
    (route,) = plan_route(block[None], [ZONE], [region], BACK)
    assert route is not None and route.legs >= 2 and route.via is not None
    for a, b in _corridors(block, route.via, ZONE):
        assert not crosses(a, b, _grown(region))
    # From the waypoint, the rest of the route is clear too.
    (rest,) = plan_route(route.via[None], [ZONE], [region], BACK)
    assert rest is not None and rest.legs == route.legs - 1


def test_a_block_beside_a_region_may_leave_it_but_not_cross_it() -> None:
    region = Area(np.array([0.5, 0.0]), 0.0, np.array([0.05, 0.05]))
    near = np.array([0.5, 0.07])  # inside the grown region, outside the region
    (route,) = plan_route(near[None], [ZONE], [region], BACK)
    assert route is not None
    for a, b in _corridors(near, route.via, ZONE):
        assert not crosses(a, b, region)


@given(st.floats(0.3, 0.7), st.floats(-0.45, 0.45), st.floats(0.3, 0.7), st.floats(-0.3, 0.1))
def test_every_first_leg_keeps_clear_of_the_grown_regions(bx: float, by: float, rx: float,
                                                           ry: float) -> None:
    block = np.array([bx, by])
    region = Area(np.array([rx, ry]), 0.0, np.array([0.06, 0.06]))
    grown = _grown(region)
    if np.all(np.abs(block - region.center) < grown.half):
        return  # a block inside the grown region has its own rule (the test above)
    (route,) = plan_route(block[None], [ZONE], [region], BACK)
    if route is None:
        return
    for a, b in _corridors(block, route.via, ZONE):
        assert not crosses(a, b, grown)


def test_obstacles_are_other_piles_and_bodies_but_not_what_stands_in_the_own_zone() -> None:
    from factask.library import get_task
    from factask.scene.objects import objects_by_name
    from factask.sim.layout.reset import reset_layout

    graph = get_task("color-coordinated-insertion-and-sweeping")
    poses, solved = reset_layout(graph, np.random.default_rng(0))
    objs = objects_by_name(graph)
    red = next(s for name, s in solved.items() if "red" in name)
    regions = obstacle_regions(red, objs, poses, held=set())
    centres = [tuple(np.round(r.center, 6)) for r in regions]
    own_ell = tuple(np.round(poses["red_ell"].pos[:2], 6))
    assert own_ell not in centres  # the red fixture stands in the red zone: no obstacle
    for c in ("blue", "green"):
        assert tuple(np.round(poses[f"{c}_ell"].pos[:2], 6)) in centres
        pile = np.array([poses[i].pos[:2] for i in graph.variable(f"{c}_pile").instances])
        assert all(any(r.contains(pile[k:k + 1])[0] for r in regions)
                   for k in range(len(pile)))


def crossing_piles() -> TaskGraph:
    """Two piles and two zones: the red zone lies on the straight line from the blue
    pile to the blue zone (what CLIPort's sweep-and-sort layouts often give)."""
    def pose(x: float, y: float) -> dict:
        return {"type": "pose", "x": x, "y": y}

    big = [0.15, 0.15, 0.001]
    return parse_graph({
        "name": "crossing_piles",
        "variables": [
            {"name": "red_pile", "kind": "pile", "count": 12, "color": "red",
             "initial": pose(0.5, 0.0)},
            {"name": "red_zone", "kind": "zone", "color": "red", "size": big,
             "initial": pose(0.54, -0.2)},
            {"name": "blue_pile", "kind": "pile", "count": 12, "color": "blue",
             "initial": pose(0.5, -0.4)},
            {"name": "blue_zone", "kind": "zone", "color": "blue", "size": big,
             "initial": pose(0.53, 0.33)}],
        "factors": [
            {"name": "red", "weight": 0.5, "goal": {"type": "pile_in_zone", "objects": [
                "red_pile"], "zone": "red_zone", "fraction": 0.99}},
            {"name": "blue", "weight": 0.5, "goal": {"type": "pile_in_zone", "objects": [
                "blue_pile"], "zone": "blue_zone", "fraction": 0.99}}],
    })


@pytest.mark.parametrize("seed", [0, 1])
def test_the_second_pile_is_swept_around_the_first_ones_zone(seed: int) -> None:
    from factask.sim.env import FactaskEnv
    from factask.sim.oracle.scripted import Oracle

    env = FactaskEnv(crossing_piles())
    try:
        env.reset(seed=seed)
        oracle = Oracle(env, seed=seed)
        red_done = False
        for _ in range(30):
            action = oracle.plan()
            if action is None:
                break
            _, _, terminated, truncated, info = env.step(action.as_env_action())
            red_done = red_done or info["factors"]["red"] >= 1.0
            if red_done:  # once in, the red blocks stay in: no push sweeps them out
                assert info["factors"]["red"] >= 0.95, info["details"]
            if terminated or truncated:
                break
        assert env.status().success, oracle.failure
    finally:
        env.close()
