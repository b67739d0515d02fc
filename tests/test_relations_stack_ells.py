"""``stack`` of ells: a column standing in a corner marker, an ell carrying only
an ell no larger than itself (centred on it)."""

from __future__ import annotations

import numpy as np
import pytest

from factask.geometry import Pose
from factask.graph import Stack, StateVariable, SubtaskFactor, TaskGraph
from factask.scene.objects import objects_by_name
from factask.sim.layout.checks import check_task
from factask.sim.layout.reset import reset_layout

ELL = (0.08, 0.08, 0.04)


def _graph(variables: list[StateVariable], goal: Stack) -> TaskGraph:
    return TaskGraph(name="g", variables=variables,
                     factors=[SubtaskFactor(name="stack", description="a column", goal=goal)])


def _ells(*colors: str, size: tuple[float, float, float] = ELL) -> list[StateVariable]:
    return [StateVariable(name=f"{c}_ell", kind="ell", color=c, size=size) for c in colors]


def test_an_ell_carries_only_an_ell_no_larger() -> None:
    red, blue = _ells("red", "blue")
    small = _ells("green", size=(0.06, 0.06, 0.04))[0]
    big = _ells("yellow", size=(0.10, 0.08, 0.04))[0]
    block = StateVariable(name="block", kind="block")
    assert _graph([red, blue], Stack(objects=["red_ell", "blue_ell"])).problems() == []
    assert _graph([red, small], Stack(objects=["red_ell", "green_ell"])).problems() == []
    for top in (big, block):
        bad = _graph([red, top], Stack(objects=["red_ell", top.name]))
        assert any("carries only an ell" in p.message for p in bad.problems()), top.name
    on_base = _graph([red, block], Stack(objects=["block"], base="red_ell"))
    assert any("carries only an ell" in p.message for p in on_base.problems())
    # A block may carry an ell (its flat top holds anything that fits).
    assert _graph([block, red], Stack(objects=["block", "red_ell"])).problems() == []


def test_a_corner_or_an_ell_may_be_a_base_a_ball_may_not() -> None:
    corner = StateVariable(name="corner", kind="corner", size=(0.08, 0.08, 0.001))
    ball = StateVariable(name="ball", kind="ball", fixed=True)
    assert _graph([*_ells("red"), corner], Stack(objects=["red_ell"], base="corner")
                  ).problems() == []
    bad = _graph([*_ells("red"), ball], Stack(objects=["red_ell"], base="ball"))
    assert any("or a corner or ell" in p.message for p in bad.problems())


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_column_of_ells_stands_in_the_corner_each_on_the_one_below(seed: int) -> None:
    corner = StateVariable(name="corner", kind="corner", size=(0.08, 0.08, 0.001))
    graph = _graph([*_ells("red", "blue", "green"), corner],
                   Stack(objects=["red_ell", "blue_ell", "green_ell"], base="corner"))
    layout, solved = reset_layout(graph, np.random.default_rng(seed))
    poses = dict(layout)
    poses.update(solved["stack"].targets(objects_by_name(graph)))
    for k, name in enumerate(("red_ell", "blue_ell", "green_ell")):
        assert np.allclose(poses[name].pos[:2], layout["corner"].pos[:2])
        assert poses[name].yaw == pytest.approx(layout["corner"].yaw)
        assert poses[name].pos[2] == pytest.approx(0.02 + 0.04 * k)
    status = check_task(graph, solved, poses).factors["stack"]
    assert status.satisfied
    # Knock the middle ell off: it and the one above no longer count.
    p = poses["blue_ell"]
    poses["blue_ell"] = Pose(p.pos + np.array([0.1, 0.0, -0.04]), p.quat)
    status = check_task(graph, solved, poses).factors["stack"]
    assert not status.satisfied and status.progress == pytest.approx(1 / 3)
