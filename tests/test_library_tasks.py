"""Every registered library task, one by one: it builds, resets and checks (fast),
and the oracle completes it with both robots (slow).

The fast test does not run the oracle: it samples a layout, solves every goal,
checks that nothing holds yet, then puts every object on its solved target and
checks that the whole task holds there (so a task whose goals contradict each
other, or whose targets its own check rejects, fails here in milliseconds). It
also compiles the MuJoCo scene and resets it.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from factask.geometry import Pose
from factask.graph import TaskGraph
from factask.library import get_task, task_names
from factask.library.tags import task_tags
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.layout.checks import check_task
from factask.sim.layout.reset import reset_layout


def _params() -> list[Any]:
    return [pytest.param(name, id=name) for name in task_names()]


def _final_poses(graph: TaskGraph, poses: dict, solved: dict) -> dict:
    """The start poses with every object moved to its target in the factors that
    must hold at the end (later factors win, as the oracle would leave them)."""
    final = dict(poses)
    where = dict(poses)  # every object's latest target, milestones included
    riders: dict[str, tuple[str, np.ndarray]] = {}  # in a drawer: (drawer, offset)
    for name in graph.factor_order():
        s = solved[name]
        for i, obj in enumerate(s.objects):
            slot = s.assignment[i]
            where[obj] = s.slots[slot]
            host = s.supports[slot] if s.supports else None
            if host in graph.variable_names() and graph.variable(host).kind == "drawer":
                riders[obj] = (host, where[obj].pos - where[host].pos)
            if not graph.factor(name).milestone:
                final[obj] = s.slots[slot]
    # What rests in a drawer rides with it when a later goal slides it.
    for obj, (host, offset) in riders.items():
        final[obj] = Pose(final[host].pos + offset, final[obj].quat)
    return final


@pytest.mark.parametrize("name", _params())
def test_task_builds_resets_and_checks(name: str) -> None:
    graph = get_task(name)
    assert graph.problems() == []
    tags = task_tags(name, graph)
    assert tags[0].startswith("family:") and f"objects:{graph.movable_object_count()}" in tags

    poses, solved = reset_layout(graph, np.random.default_rng(0))
    assert set(solved) == set(graph.factor_names())
    start = check_task(graph, solved, poses)
    assert not start.success, f"{name}: a goal already holds at reset"

    final = _final_poses(graph, poses, solved)
    done = check_task(graph, solved, final, reached=set(graph.milestones()))
    failing = {f: s.detail for f, s in done.factors.items() if not s.satisfied}
    assert done.success, f"{name}: objects on their targets, yet {failing}"

    env = FactaskEnv(graph, robot="floating")
    try:
        env.reset(seed=0)
        assert not env.status().success
        assert set(env.object_poses()) >= {v.name for v in graph.variables if v.count == 1}
    finally:
        env.close()


@pytest.mark.slow
@pytest.mark.parametrize("robot", ["floating", "arm"])
@pytest.mark.parametrize("name", _params())
def test_oracle_completes_task(name: str, robot: str) -> None:
    graph = get_task(name)
    for seed in (0, 1):
        r = run_episode(graph, seed, robot=robot)
        assert r.success, (f"{name} with {robot}, seed {seed}: reward {r.reward:.3f}, "
                           f"failure {r.failure}, {r.details}")
        assert r.failure is None and r.steps <= graph.max_actions()
        assert all(p == pytest.approx(1.0) for p in r.factors.values()), r.factors
