"""Ropes: the kind (a chain of linked segments), ``rope_along``, the low carry, the oracle."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.geometry import Pose
from factask.graph import parse_graph
from factask.graph.taskgraph import TaskGraph
from factask.relations.rope import SLOT_PITCH, rope_slot_order, segment_scores
from factask.scene.objects import objects_by_name
from factask.sim.layout.checks import check_task
from factask.sim.layout.reset import reset_layout
from factask.sim.layout.sampling import sample_layout

TOL = 0.02


def _rope(count: int = 10, goal: dict | None = None, extra: list | None = None) -> TaskGraph:
    return parse_graph({
        "name": "rope_test",
        "variables": [{"name": "red_rope", "kind": "rope", "count": count, "color": "red"},
                      {"name": "green_line", "kind": "line", "color": "green"}, *(extra or [])],
        "factors": [{"name": "lay", "goal": goal or {
            "type": "rope_along", "objects": ["red_rope"], "along": "green_line",
            "tolerances": {"xy": TOL}}}],
    })


def _segments(env_or_poses, graph: TaskGraph) -> np.ndarray:
    poses = env_or_poses if isinstance(env_or_poses, dict) else env_or_poses.object_poses()
    return np.array([poses[i].pos for i in graph.variable("red_rope").instances])


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_rope_starts_straight_and_in_one_piece(seed: int) -> None:
    graph = _rope(20, extra=[{"name": "box", "kind": "box", "count": 2}])
    layout = sample_layout(graph, np.random.default_rng(seed))
    xy = _segments(layout, graph)[:, :2]
    gaps = np.linalg.norm(np.diff(xy, axis=0), axis=1)
    np.testing.assert_allclose(gaps, 0.014, atol=1e-9)  # one segment length apart
    d = np.diff(xy, axis=0)
    assert np.allclose(np.cross(np.c_[d[:-1], np.zeros(len(d) - 1)],
                                np.c_[d[1:], np.zeros(len(d) - 1)])[:, 2], 0.0, atol=1e-9)


def test_linked_segments_stay_linked_when_one_is_dragged_away() -> None:
    from factask.sim.env import FactaskEnv

    graph = _rope(20)
    env = FactaskEnv(graph)
    assert env.model.neq >= 19  # 19 links (and the suction weld)
    env.reset(seed=0)
    seg = env.object_poses()["red_rope__0"].pos
    _, _, _, _, info = env.step({"pick": np.array([seg[0], seg[1], seg[2] + 0.005, 0.0]),
                                 "place": np.array([seg[0], seg[1] + 0.15, 0.01, 0.0])})
    assert info["action_ok"], info["action_failure"]
    assert env.physics_failure() is None
    xyz = _segments(env, graph)
    gaps = np.linalg.norm(np.diff(xyz, axis=0), axis=1)
    assert np.all(gaps < 0.0145) and np.all(gaps > 0.01)  # links hold, no overlap
    assert xyz[:, 2].max() < 0.012  # the rope lies on the table


def _solved(graph: TaskGraph, seed: int = 0) -> tuple[dict, dict]:
    layout, solved = reset_layout(graph, np.random.default_rng(seed))
    poses = dict(layout)
    poses.update(solved["lay"].targets(objects_by_name(graph)))
    return solved, poses


def test_slots_run_along_the_line_a_little_closer_than_a_segment() -> None:
    graph = _rope(10)
    solved, poses = _solved(graph)
    slots = np.array([p.pos[:2] for p in solved["lay"].slots])
    np.testing.assert_allclose(np.linalg.norm(np.diff(slots, axis=0), axis=1),
                               0.014 * SLOT_PITCH, atol=1e-9)
    line = poses["green_line"]
    np.testing.assert_allclose(slots.mean(axis=0), line.pos[:2], atol=1e-9)


def test_either_end_may_go_first_and_progress_is_continuous() -> None:
    graph = _rope(10)
    solved, poses = _solved(graph)
    names = graph.variable("red_rope").instances
    flipped = dict(poses)
    for a, b in zip(names, names[::-1], strict=True):
        flipped[a] = poses[b]
    for p in (poses, flipped):
        st_ = check_task(graph, solved, p).factors["lay"]
        assert st_.satisfied and st_.progress == 1.0
    # One segment moving off its slot: progress falls linearly from tol to 2 tol.
    values = []
    for t in np.linspace(0.0, 0.05, 26):
        moved = dict(poses)
        p = poses[names[3]]
        moved[names[3]] = Pose(p.pos + np.array([0.0, t, 0.0]), p.quat)
        values.append(check_task(graph, solved, moved).factors["lay"].progress)
    assert max(abs(np.diff(values))) <= 0.002 / TOL / 10 + 1e-9
    assert values[-1] == pytest.approx(0.9) and values[0] == 1.0


@settings(max_examples=80, deadline=None)
@given(d=st.floats(0.0, 0.2), e=st.floats(-0.01, 0.01))
def test_segment_scores_are_lipschitz(d: float, e: float) -> None:
    a, b = segment_scores(np.array([d, max(0.0, d + e)]), TOL)
    assert 0.0 <= a <= 1.0 and abs(a - b) <= abs(e) / TOL + 1e-12


def test_the_oracle_takes_the_ends_then_the_farthest_segment() -> None:
    dist = {"a": 0.05, "b": 0.3, "c": 0.02}
    # Both ends are much nearer their slots than b: b first.
    assert rope_slot_order({"a": 0, "b": 4, "c": 9}, 10, dist) == "b"
    assert rope_slot_order({"a": 0, "b": 4}, 10, {"a": 0.2, "b": 0.3}) == "a"
    assert rope_slot_order({"a": 3, "b": 9}, 10, {"a": 0.3, "b": 0.2}) == "b"


def test_rope_along_needs_a_line_or_two_ends() -> None:
    with pytest.raises(Exception, match="needs `along`"):
        _rope(5, goal={"type": "rope_along", "objects": ["red_rope"]})
    with pytest.raises(Exception, match="one point per segment"):
        _rope(5, goal={"type": "rope_along", "objects": ["red_rope"],
                       "points": [{"x": 0.4, "y": 0.0}, {"x": 0.41, "y": 0.0}]})


def test_after_the_ends_a_fold_near_its_slot_goes_before_the_farthest_segment() -> None:
    targets = {"a": 0, "b": 4, "c": 7}
    dist = {"a": 0.01, "b": 0.03, "c": 0.2, "d": 0.01}
    bend = {"a": 10.0, "b": 170.0, "c": 90.0, "d": 120.0}
    # b: turned round near its slot (c is far off: not laid out yet, not a fold).
    assert rope_slot_order(targets, 10, dist, bend=bend) == "b"
    assert rope_slot_order(targets, 10, dist) == "c"
    # The ends still come first while far off.
    assert rope_slot_order({"a": 0, "c": 7}, 10, {"a": 0.15, "c": 0.2, "d": 0.0},
                           bend={"d": 170.0}) == "a"


def test_the_oracle_aims_taut_slots_drawn_together_towards_the_middle() -> None:
    from factask.sim.oracle.rope import aim_points

    taut = np.c_[np.arange(20) * 0.014, np.zeros(20)] + [0.4, 0.1]
    aims = aim_points(taut, 0.014)
    np.testing.assert_allclose(np.diff(aims[:, 0]), 0.014 * SLOT_PITCH, atol=1e-9)
    np.testing.assert_allclose(aims.mean(axis=0), taut.mean(axis=0), atol=1e-9)
    assert np.abs(aims - taut).max() < 0.011  # within Ravens' 2 cm, with room
    slack = np.c_[np.arange(20) * 0.014 * SLOT_PITCH, np.zeros(20)]
    np.testing.assert_allclose(aim_points(slack, 0.014), slack, atol=1e-12)
    # A bent run is drawn together along its length, staying on it.
    ell = np.r_[np.c_[np.arange(10) * 0.014, np.zeros(10)],
                np.c_[np.full(10, 0.126), 0.014 * np.arange(1, 11)]]
    on_run = aim_points(ell, 0.014)
    assert np.all((np.abs(on_run[:, 1]) < 1e-9) | (np.abs(on_run[:, 0] - 0.126) < 1e-9))


def test_points_and_one_direction_only() -> None:
    pts = [{"x": 0.4 + 0.014 * k, "y": 0.1} for k in range(10)]
    graph = _rope(10, goal={"type": "rope_along", "objects": ["red_rope"], "points": pts,
                            "either_end": False, "tolerances": {"xy": TOL}})
    layout, solved = reset_layout(graph, np.random.default_rng(0))
    slots = np.array([p.pos[:2] for p in solved["lay"].slots])
    np.testing.assert_allclose(slots, [[p["x"], p["y"]] for p in pts], atol=1e-9)
    names = graph.variable("red_rope").instances
    objs = objects_by_name(graph)
    on = dict(layout)
    on.update(solved["lay"].targets(objs))
    flipped = dict(on)
    for a, b in zip(names, names[::-1], strict=True):
        flipped[a] = on[b]
    assert check_task(graph, solved, on).factors["lay"].satisfied
    assert not check_task(graph, solved, flipped).factors["lay"].satisfied


@pytest.mark.parametrize(("side", "expect"), [
    ("+x", ((0.5 + 0.1, -0.13), (0.5 + 0.1, 0.13))), ("-y", ((0.37, -0.1), (0.63, -0.1))),
    ("diagonal", ((0.41, -0.09), (0.59, 0.09)))])
def test_a_run_on_an_edge_or_the_diagonal_of_a_region(side: str, expect: tuple) -> None:
    graph = parse_graph({
        "name": "rope_side",
        "variables": [{"name": "red_rope", "kind": "rope", "count": 20, "color": "red"},
                      {"name": "sq", "kind": "zone", "size": [0.2, 0.2, 0.001],
                       "initial": {"type": "pose", "x": 0.5, "y": 0.0}}],
        "factors": [{"name": "lay", "goal": {"type": "rope_along", "objects": ["red_rope"],
                                             "along": "sq", "side": side}}]})
    _, solved = reset_layout(graph, np.random.default_rng(0))
    slots = np.array([p.pos[:2] for p in solved["lay"].slots])
    ends = sorted([tuple(slots[0]), tuple(slots[-1])])
    np.testing.assert_allclose(ends, sorted(expect), atol=0.01)


def test_a_solid_start_anchor_keeps_the_rope_clear_of_it() -> None:
    from factask.relations.rope import ANCHOR_GAP

    graph = parse_graph({
        "name": "rope_blocks",
        "variables": [{"name": "red_rope", "kind": "rope", "count": 10, "color": "red"},
                      {"name": "a", "kind": "block", "fixed": True,
                       "initial": {"type": "pose", "x": 0.5, "y": -0.1}},
                      {"name": "b", "kind": "block", "fixed": True,
                       "initial": {"type": "pose", "x": 0.5, "y": 0.1}}],
        "factors": [{"name": "lay", "goal": {"type": "rope_along", "objects": ["red_rope"],
                                             "start": "a", "end": "b"}}]})
    _, solved = reset_layout(graph, np.random.default_rng(0))
    first = solved["lay"].slots[0].pos
    # Half a segment beyond the block's face and the gap.
    assert first[1] == pytest.approx(-0.1 + 0.02 + ANCHOR_GAP + 0.007 * SLOT_PITCH, abs=1e-6)


@pytest.mark.parametrize("seed", [0, 3, 5, 7])  # 5, 7 oscillated before (issue 15)
def test_the_oracle_lays_a_rope_along_a_line(seed: int) -> None:
    from factask.sim.episode import run_episode

    result = run_episode(_rope(20), seed, robot="floating")
    assert result.success, result.failure


def test_the_oracle_lays_a_rope_between_two_corner_markers() -> None:
    from factask.sim.episode import run_episode

    graph = parse_graph({
        "name": "rope_ends",
        "variables": [
            {"name": "red_rope", "kind": "rope", "count": 20, "color": "red"},
            {"name": "corner_a", "kind": "corner", "initial": {"type": "pose", "x": 0.45,
                                                              "y": -0.12, "yaw_deg": 0}},
            {"name": "corner_b", "kind": "corner", "initial": {"type": "pose", "x": 0.45,
                                                              "y": 0.13, "yaw_deg": 0}}],
        "factors": [{"name": "lay", "goal": {"type": "rope_along", "objects": ["red_rope"],
                                             "start": "corner_a", "end": "corner_b",
                                             "tolerances": {"xy": TOL}}}],
    })
    result = run_episode(graph, 0, robot="floating")
    assert result.success, result.failure


@pytest.mark.slow
def test_the_arm_lays_a_rope_along_a_line() -> None:
    from factask.sim.episode import run_episode

    result = run_episode(_rope(20), 1, robot="arm")
    assert result.success, result.failure


#: Seeded episodes of the stability sweep (issue 15: 100; fewer for a quick look).
STABILITY_EPISODES = int(os.environ.get("FACTASK_STABILITY_EPISODES", "100"))


@pytest.mark.slow
def test_ropes_stay_stable_over_many_seeded_episodes() -> None:
    from factask.sim.env import FactaskEnv
    from factask.sim.oracle.scripted import Oracle

    graph = _rope(20)
    env = FactaskEnv(graph)
    for seed in range(STABILITY_EPISODES):
        env.reset(seed=seed)
        oracle = Oracle(env, seed=seed)
        for _ in range(3):
            action = oracle.act()
            if action is None:
                break
            _, _, terminated, _, _ = env.step(action)
            assert env.physics_failure() is None, (seed, env.physics_failure())
            assert np.all(np.isfinite(env.data.qpos))
            xyz = _segments(env, graph)
            gaps = np.linalg.norm(np.diff(xyz, axis=0), axis=1)
            assert gaps.max() < 0.016 and xyz[:, 2].max() < 0.05, seed  # linked, on table
            if terminated:
                break
    assert math.isfinite(float(env.data.time))


def test_a_rope_goal_with_no_run_is_a_layout_error_even_unvalidated() -> None:
    """Validation refuses a rope_along with no along, start/end or points; a graph
    built without it (model_validate alone) fails its reset with a typed error,
    not an AssertionError inside the solver."""
    from factask.scene.collision import LayoutError
    from factask.sim.layout.reset import reset_layout

    graph = TaskGraph.model_validate({
        "name": "t", "variables": [{"name": "rope", "kind": "rope", "count": 10,
                                    "size": [0.014, 0.01, 0.01]}],
        "factors": [{"name": "f", "goal": {"type": "rope_along", "objects": ["rope"]}}]})
    with pytest.raises(LayoutError, match="needs 'along'"):
        reset_layout(graph, np.random.default_rng(0))
