"""Rules of relation solving and checking found by review: interchangeable
instances, finite poses, row direction and support, workspace height."""

from __future__ import annotations

import numpy as np
import pytest

from factask.geometry import Pose
from factask.graph import Row, Stack, StateVariable, SubtaskFactor, TaskGraph
from factask.library import get_task
from factask.scene.collision import LayoutError
from factask.scene.objects import objects_by_name
from factask.sim.layout.checks import CheckError, check_task
from factask.sim.layout.reset import reset_layout
from factask.vocabulary.world import WORKSPACE_Z


def _at_targets(graph: TaskGraph, seed: int = 0):
    layout, solved = reset_layout(graph, np.random.default_rng(seed))
    poses = dict(layout)
    objs = objects_by_name(graph)
    for s in solved.values():
        poses.update(s.targets(objs))
    return solved, poses


@pytest.mark.parametrize(("task", "a", "b"), [
    ("stack-boxes-column", "boxes__0", "boxes__1"),
    ("build-bridge", "yellow_pillars__0", "yellow_pillars__1"),
    ("stack-three-layer-red-wall", None, None),
])
def test_identical_instances_are_interchangeable_in_ordered_goals(task, a, b) -> None:
    graph = get_task(task)
    solved, poses = _at_targets(graph)
    if a is None:  # swap the first two instances of the first multi-instance variable
        v = next(v for v in graph.variables if v.count > 1)
        a, b = v.instances[:2]
    poses[a], poses[b] = poses[b], poses[a]
    status = check_task(graph, solved, poses)
    assert status.success and status.reward == pytest.approx(1.0)


def test_order_between_variables_still_matters() -> None:
    red = StateVariable(name="red", kind="block", color="red")
    blue = StateVariable(name="blue", kind="block", color="blue")
    g = TaskGraph(name="t", variables=[red, blue], factors=[
        SubtaskFactor(name="s", goal=Stack(objects=["red", "blue"]))]).ensure_valid()
    solved, poses = _at_targets(g)
    poses["red"], poses["blue"] = poses["blue"], poses["red"]
    assert not check_task(g, solved, poses).success


def test_non_finite_poses_are_an_error_not_a_success() -> None:
    graph = get_task("stack-boxes-column")
    solved, poses = _at_targets(graph)
    nan = Pose(np.full(3, np.nan), np.full(4, np.nan))
    assert not nan.finite
    with pytest.raises(CheckError, match="not finite"):
        check_task(graph, solved, {n: nan for n in poses})


def test_row_along_a_line_runs_towards_plus_x_whatever_the_line_yaw() -> None:
    graph = get_task("align-boxes-on-line")
    factor = next(f for f in graph.factors if isinstance(f.goal, Row) and f.goal.along)
    objs = objects_by_name(graph)
    for seed in range(8):
        _, solved = reset_layout(graph, np.random.default_rng(seed))
        s = solved[factor.name]
        first, last = (s.target_pose(objs[s.objects[0]], 0),
                       s.target_pose(objs[s.objects[-1]], len(s.objects) - 1))
        d = last.pos[:2] - first.pos[:2]
        assert d[0] > 1e-9 or (abs(d[0]) <= 1e-9 and d[1] > 0), (seed, d)


def test_row_that_cannot_rest_on_the_row_below_is_infeasible() -> None:
    base = StateVariable(name="base", kind="block", color="red")
    top = StateVariable(name="top", kind="block", color="blue", count=2)
    g = TaskGraph(name="t", variables=[base, top], factors=[
        SubtaskFactor(name="b", weight=0.5, goal=Row(objects=["base"])),
        SubtaskFactor(name="r", weight=0.5, goal=Row(objects=["top"], on="base")),
    ]).ensure_valid()
    with pytest.raises(LayoutError, match="unsupported"):
        reset_layout(g, np.random.default_rng(0))


def test_targets_above_the_workspace_are_infeasible() -> None:
    blocks = StateVariable(name="blocks", kind="block", count=16)
    g = TaskGraph(name="t", variables=[blocks], factors=[
        SubtaskFactor(name="s", goal=Stack(objects=["blocks"]))]).ensure_valid()
    with pytest.raises(LayoutError, match="above the workspace"):
        reset_layout(g, np.random.default_rng(0))
    assert WORKSPACE_Z[1] < 16 * 0.04  # 64 cm > the 60 cm the arm allows
