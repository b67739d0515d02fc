"""CLIPort-style task classes import, compile and are completed by the oracle on MuJoCo."""

from __future__ import annotations

from pathlib import Path

import pytest

from factask.compat.cliport import import_cliport
from factask.sim.episode import evaluate_task

TASK_FILES = sorted((Path(__file__).parent / "cliport_tasks").glob("*.py"))


def test_there_are_at_least_twelve_example_classes() -> None:
    assert len(TASK_FILES) >= 12


@pytest.mark.parametrize("path", TASK_FILES, ids=[p.stem for p in TASK_FILES])
def test_cliport_class_is_completed_by_the_oracle(path: Path) -> None:
    graph = import_cliport(path, seed=0).graph
    result = evaluate_task(graph, episodes=2, seed=0, robot="floating")
    failures = [(e.seed, e.failure, e.details) for e in result.episodes if not e.success]
    assert result.completed, failures
