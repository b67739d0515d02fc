"""Goal checks (factask.sim.layout.checks): progress, satisfaction, tolerances, matches."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_layout import GRAPHS, at_targets, make_graph

from factask.geometry import Pose, quat_from_yaw, quat_mul
from factask.graph import TaskGraph
from factask.relations.solving import SolvedFactor
from factask.sim.layout.checks import CheckError, check_factor, check_task
from factask.sim.layout.reset import reset_layout


def _setup(graph: TaskGraph, seed: int = 0
           ) -> tuple[dict[str, Pose], dict[str, SolvedFactor], dict[str, Pose]]:
    layout, solved = reset_layout(graph, np.random.default_rng(seed))
    return layout, solved, at_targets(graph, layout, solved)


def _moved(pose: Pose, dx: float = 0.0, dy: float = 0.0, dz: float = 0.0,
           dyaw_deg: float = 0.0) -> Pose:
    quat = quat_mul(quat_from_yaw(math.radians(dyaw_deg)), pose.quat)
    return Pose(pose.pos + np.array([dx, dy, dz]), quat)


def _tilted(pose: Pose, deg: float) -> Pose:
    half = math.radians(deg) / 2
    return Pose(pose.pos, quat_mul(np.array([math.cos(half), math.sin(half), 0.0, 0.0]),
                                   pose.quat))


@settings(max_examples=15)
@given(st.integers(0, 10_000), st.sampled_from(sorted(GRAPHS)))
def test_objects_at_their_targets_satisfy_everything(seed: int, name: str) -> None:
    g = GRAPHS[name]
    layout, solved, final = _setup(g, seed)
    status = check_task(g, solved, final)
    assert status.success, {k: v.detail for k, v in status.factors.items()}
    assert math.isclose(status.reward, 1.0)
    initial = check_task(g, solved, layout)
    assert not any(s.satisfied for s in initial.factors.values())
    assert initial.reward < 1.0


def test_stack_loses_progress_when_its_top_falls() -> None:
    g = GRAPHS["stack"]
    _, solved, final = _setup(g, 1)
    top = final["c"]
    fallen = dict(final, c=Pose(np.array([top.pos[0] + 0.06, top.pos[1], 0.02]), top.quat))
    st_ = check_factor(g, solved["f"], fallen)
    assert math.isclose(st_.progress, 2 / 3) and not st_.satisfied
    assert "c:" in st_.detail
    # The bottom knocked away: nothing above it counts either (no latching).
    bottom = final["a"]
    knocked = dict(final, a=_moved(bottom, dx=0.1))
    assert check_factor(g, solved["f"], knocked).progress == 0.0
    # Lying on its side at the right place is not placed.
    tipped = dict(final, c=_tilted(final["c"], 90.0))
    assert not check_factor(g, solved["f"], tipped).satisfied


def test_square_yaw_symmetry_and_round_objects() -> None:
    g = make_graph(
        [{"name": "cube", "kind": "block"}, {"name": "can", "kind": "cylinder"}],
        [{"name": "f", "goal": {"type": "at_pose", "objects": ["cube"],
                                "poses": [{"x": 0.5, "y": 0.2, "yaw_deg": 10}]}},
         {"name": "g", "goal": {"type": "at_pose", "objects": ["can"],
                                "poses": [{"x": 0.5, "y": -0.2}]}}])
    _, solved, final = _setup(g)
    for deg, ok in ((90.0, True), (180.0, True), (-90.0, True), (45.0, False), (20.0, False)):
        poses = dict(final, cube=_moved(final["cube"], dyaw_deg=deg))
        assert check_factor(g, solved["f"], poses).satisfied is ok, deg
    poses = dict(final, cube=_moved(final["cube"], dyaw_deg=45.0))
    assert "yaw 45 deg off" in check_factor(g, solved["f"], poses).detail
    for deg in (45.0, 17.0, 133.0):
        poses = dict(final, can=_moved(final["can"], dyaw_deg=deg))
        assert check_factor(g, solved["g"], poses).satisfied


def test_rectangle_has_180_degree_symmetry_and_check_yaw_false() -> None:
    g = make_graph(
        [{"name": "bar", "kind": "box", "size": [0.08, 0.03, 0.03]},
         {"name": "free", "kind": "box", "size": [0.08, 0.03, 0.03]}],
        [{"name": "f", "goal": {"type": "at_pose", "objects": ["bar"],
                                "poses": [{"x": 0.4, "y": 0.2}]}},
         {"name": "g", "goal": {"type": "at_pose", "objects": ["free"], "check_yaw": False,
                                "poses": [{"x": 0.6, "y": -0.2}]}}])
    _, solved, final = _setup(g)
    assert check_factor(g, solved["f"], dict(final, bar=_moved(final["bar"],
                                                                dyaw_deg=180))).satisfied
    assert not check_factor(g, solved["f"], dict(final, bar=_moved(final["bar"],
                                                                    dyaw_deg=90))).satisfied
    assert check_factor(g, solved["g"], dict(final, free=_moved(final["free"],
                                                                 dyaw_deg=60))).satisfied


def test_xy_and_height_tolerances_come_from_the_relation() -> None:
    def graph(xy: float) -> TaskGraph:
        return make_graph([{"name": "b", "kind": "block"}],
                          [{"name": "f", "goal": {"type": "at_pose", "objects": ["b"],
                                                  "tolerances": {"xy": xy},
                                                  "poses": [{"x": 0.5, "y": 0.0}]}}])
    for xy, ok in ((0.01, False), (0.05, True)):
        g = graph(xy)
        _, solved, final = _setup(g)
        st_ = check_factor(g, solved["f"], dict(final, b=_moved(final["b"], dx=0.03)))
        assert st_.satisfied is ok
    g = graph(0.01)
    _, solved, final = _setup(g)
    st_ = check_factor(g, solved["f"], dict(final, b=_moved(final["b"], dx=0.023)))
    assert "2.3 cm from target (tolerance 1.0 cm)" in st_.detail
    lifted = check_factor(g, solved["f"], dict(final, b=_moved(final["b"], dz=0.05)))
    assert not lifted.satisfied and "above" in lifted.detail


def test_in_zone_half_outside_fails_and_inside_passes() -> None:
    g = GRAPHS["in_zone"]
    layout, solved, final = _setup(g, 2)
    zone = layout["zone"]
    centred = dict(final, blocks__0=Pose(np.array([*zone.pos[:2], 0.02]), zone.quat))
    assert check_factor(g, solved["f"], centred).progress == 1.0
    # Half of the block beyond the zone's edge (in the zone's own frame).
    edge = zone.pos[:2] + np.array([math.cos(zone.yaw), math.sin(zone.yaw)]) * 0.075
    half_out = dict(final, blocks__0=Pose(np.array([*edge, 0.02]), zone.quat))
    st_ = check_factor(g, solved["f"], half_out)
    assert not st_.satisfied and math.isclose(st_.progress, 2 / 3)
    assert "blocks__0" in st_.detail and "inside zone" in st_.detail


def test_matches_restrict_which_object_takes_which_slot() -> None:
    def graph(matches: list[list[int]] | None) -> TaskGraph:
        goal = {"type": "at_pose", "objects": ["red", "blue"],
                "poses": [{"x": 0.4, "y": 0.2}, {"x": 0.6, "y": -0.2}]}
        if matches is not None:
            goal["matches"] = matches
        return make_graph([{"name": "red", "kind": "block", "color": "red"},
                           {"name": "blue", "kind": "block", "color": "blue"}],
                          [{"name": "f", "goal": goal}])
    for matches, expected in (([[1, 0], [0, 1]], 0.0), (None, 1.0)):
        g = graph(matches)
        _, solved, final = _setup(g)
        swapped = dict(final, red=final["blue"], blue=final["red"])
        assert check_factor(g, solved["f"], swapped).progress == expected
        assert check_factor(g, solved["f"], final).satisfied


def test_one_object_per_slot() -> None:
    g = GRAPHS["circle"]
    _, solved, final = _setup(g, 3)
    crowded = dict(final, blocks__1=final["blocks__0"])
    assert math.isclose(check_factor(g, solved["f"], crowded).progress, 5 / 6)


def test_unordered_stack_accepts_any_order() -> None:
    g = GRAPHS["on_stack_base"]
    _, solved, final = _setup(g, 4)
    swapped = dict(final, tower__0=final["tower__1"], tower__1=final["tower__0"])
    assert check_factor(g, solved["f3"], swapped).satisfied
    g2 = GRAPHS["stack"]
    _, solved2, final2 = _setup(g2, 4)
    swapped2 = dict(final2, a=final2["b"], b=final2["a"])
    # Ordered: the bottom slot is taken by the wrong block, so nothing above counts.
    assert check_factor(g2, solved2["f"], swapped2).progress == 0.0


def test_held_objects_never_count() -> None:
    g = GRAPHS["in_zone"]
    _, solved, final = _setup(g, 5)
    st_ = check_factor(g, solved["f"], final, held={"blocks__2"})
    assert not st_.satisfied and "held" in st_.detail
    g = GRAPHS["stack"]
    _, solved, final = _setup(g, 5)
    assert not check_factor(g, solved["f"], final, held={"c"}).satisfied


def test_on_counts_anywhere_on_the_support_but_not_beside_it() -> None:
    g = GRAPHS["on_stack_base"]
    _, solved, final = _setup(g, 6)
    box = final["box"]
    shifted = dict(final, cubes__0=Pose(np.array([*box.pos[:2], 0.05 + 0.005 + 0.02]),
                                        final["cubes__0"].quat))
    # kit top 0.005 + box 0.05: a cube at the box centre rests on it
    assert check_factor(g, solved["f2"], shifted).satisfied
    off = dict(final, cubes__0=Pose(box.pos + np.array([0.3, 0.0, 0.02 - box.pos[2]])))
    st_ = check_factor(g, solved["f2"], off)
    assert not st_.satisfied and "cubes__0" in st_.detail
    floating = dict(final, cubes__0=_moved(final["cubes__0"], dz=0.05))
    assert "above" in check_factor(g, solved["f2"], floating).detail


def test_bridge_must_rest_on_the_pillars() -> None:
    g = GRAPHS["bridge"]
    _, solved, final = _setup(g, 7)
    assert check_factor(g, solved["f2"], final).satisfied
    dropped = dict(final, bar=_moved(final["bar"], dz=-0.06))
    assert not check_factor(g, solved["f2"], dropped).satisfied
    # Pillars knocked apart: the bar's row factor fails.
    pushed = dict(final, pillars__0=_moved(final["pillars__0"], dx=0.05))
    assert not check_factor(g, solved["f1"], pushed).satisfied


def test_inside_needs_floor_and_rim() -> None:
    g = GRAPHS["inside"]
    layout, solved, final = _setup(g, 8)
    assert check_factor(g, solved["f1"], final).satisfied
    above = dict(final, balls__0=_moved(final["balls__0"], dz=0.06))
    st_ = check_factor(g, solved["f1"], above)
    assert not st_.satisfied and "rim" in st_.detail
    beside = dict(final, cyl__0=_moved(layout["cont"], dx=0.2))
    assert not check_factor(g, solved["f2"], beside).satisfied


def test_reward_is_weighted_progress() -> None:
    g = GRAPHS["row_on_row"]
    _, solved, final = _setup(g, 9)
    poses = dict(final, top__0=_moved(final["top__0"], dx=0.2))
    status = check_task(g, solved, poses)
    assert not status.success
    assert math.isclose(status.reward, 0.5 * 1.0 + 0.5 * 0.5)


def test_missing_pose_or_factor_is_a_clear_error() -> None:
    g = GRAPHS["stack"]
    _, solved, final = _setup(g)
    del final["b"]
    with pytest.raises(CheckError, match="'b'"):
        check_task(g, solved, final)
    with pytest.raises(CheckError, match="no solved targets"):
        check_task(g, {}, final)
