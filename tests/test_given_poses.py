"""Poses an author gives are facts: fixed starts and ``at_pose`` targets are used as
given wherever they are physically possible (Ravens accepts any pose whose centre
lies in its workspace), and refused — with the reason — only where they are not."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import make_graph

from factask.scene.collision import LayoutError
from factask.sim.layout.reset import reset_layout
from factask.sim.layout.sampling import sample_layout
from factask.vocabulary.world import WORKSPACE_X, WORKSPACE_Y

BLOCK = 0.04


def test_a_fixed_object_whose_footprint_crosses_the_workspace_edge_is_kept() -> None:
    # Centre 1 cm inside the workspace edge: the 0.12 m fixture reaches 5 cm past it.
    x = WORKSPACE_X[1] - 0.01
    graph = make_graph(
        [{"name": "fixture", "kind": "fixture", "fixed": True,
          "initial": {"type": "pose", "x": x, "y": 0.0}},
         {"name": "block", "kind": "block"}],
        [{"name": "f", "goal": {"type": "at_pose", "objects": ["block"],
                                "poses": [{"x": 0.5, "y": 0.2}]}}])
    layout = sample_layout(graph, np.random.default_rng(0))
    assert layout["fixture"].pos[0] == pytest.approx(x)


def test_a_fixed_object_hanging_off_the_table_is_refused_with_the_reason() -> None:
    graph = make_graph(
        [{"name": "pallet", "kind": "pallet", "size": [0.5, 0.5, 0.02], "fixed": True,
          "initial": {"type": "pose", "x": 0.5, "y": WORKSPACE_Y[1]}},
         {"name": "block", "kind": "block"}],
        [{"name": "f", "goal": {"type": "at_pose", "objects": ["block"],
                                "poses": [{"x": 0.5, "y": -0.2}]}}])
    with pytest.raises(LayoutError, match=r"pallet.*hanging off the table"):
        sample_layout(graph, np.random.default_rng(0))


def _row(spacing: float) -> list[dict[str, float]]:
    return [{"x": 0.5 + k * spacing, "y": 0.0} for k in range(3)]


@pytest.mark.parametrize("gap", [0.0, 0.002, 0.01])
def test_author_targets_closer_than_the_clearance_are_used_as_given(gap: float) -> None:
    graph = make_graph([{"name": "blocks", "kind": "block", "count": 3}],
                       [{"name": "f", "goal": {"type": "at_pose", "objects": ["blocks"],
                                               "poses": _row(BLOCK + gap)}}])
    _, solved = reset_layout(graph, np.random.default_rng(0))
    xs = sorted(p.pos[0] for p in solved["f"].slots)
    assert np.allclose(np.diff(xs), BLOCK + gap)


def test_author_targets_inside_one_another_are_refused() -> None:
    graph = make_graph([{"name": "blocks", "kind": "block", "count": 3}],
                       [{"name": "f", "goal": {"type": "at_pose", "objects": ["blocks"],
                                               "poses": _row(BLOCK - 0.01)}}])
    with pytest.raises(LayoutError, match="collides"):
        reset_layout(graph, np.random.default_rng(0))


def test_an_author_target_at_the_workspace_edge_is_kept() -> None:
    x = WORKSPACE_X[0] + 0.005  # the block reaches 1.5 cm out of the workspace
    graph = make_graph([{"name": "block", "kind": "block"}],
                       [{"name": "f", "goal": {"type": "at_pose", "objects": ["block"],
                                               "poses": [{"x": x, "y": 0.1}]}}])
    _, solved = reset_layout(graph, np.random.default_rng(0))
    assert solved["f"].slots[0].pos[0] == pytest.approx(x)
