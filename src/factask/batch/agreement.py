"""The batched oracle held to the single one: the same task and seeds, both ways.

:func:`compare_task` runs :func:`factask.batch.oracle.run_oracle` on a batch whose
worlds are reset with seeds ``s0, s1, ...`` and :func:`factask.sim.episode.run_episode`
on each of those seeds, and reports, per seed, whether they agree on success and on
the number of actions. ``tests/test_batch_library.py`` runs it over the library and
``scripts/batch_agreement.py`` writes the whole table (docs/batch.md explains every
difference).

A task is *batched* when none of its goals asks for an action the lockstep
primitive does not run yet: pushes (``pile_in_zone``) and low carries
(``rope_along``) are single-env only.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import asdict, dataclass

from factask.batch.planner import NOT_BATCHED
from factask.graph.taskgraph import TaskGraph


def batched(graph: TaskGraph) -> bool:
    """Whether the batched oracle runs every goal of ``graph`` (see :data:`NOT_BATCHED`)."""
    return not any(f.goal.kind() in NOT_BATCHED for f in graph.factors)


@dataclass(frozen=True)
class SeedAgreement:
    """One seed of one task, both ways.

    Attributes:
        task: The task's name.
        seed: The reset seed.
        batch_success: The batched oracle's success in the world of this seed.
        batch_actions: Its actions there.
        batch_failure: Its reason for stopping short, or None.
        single_success: ``run_episode``'s success on the seed.
        single_actions: Its actions.
        single_failure: Its reason, or None.
        seconds: Wall time of both runs of the task, shared by its seeds.
    """

    task: str
    seed: int
    batch_success: bool
    batch_actions: int
    batch_failure: str | None
    single_success: bool
    single_actions: int
    single_failure: str | None
    seconds: float

    @property
    def agrees(self) -> bool:
        """Same success and the same number of actions."""
        return (self.batch_success == self.single_success
                and self.batch_actions == self.single_actions)

    def to_dict(self) -> dict[str, object]:
        """A JSON-ready row (``agrees`` included)."""
        return {**asdict(self), "agrees": self.agrees}


def compare_task(name: str, graph: TaskGraph, seeds: Sequence[int] = (0, 1),
                 device: str = "cpu") -> list[SeedAgreement]:
    """Run the batched oracle (one world per seed) and the single oracle on each seed.

    Args:
        name: The task's name (for the rows).
        graph: The task (floating cup; batched: see :func:`batched`).
        seeds: Reset seeds, one world each.
        device: The Warp device.

    Returns:
        One :class:`SeedAgreement` per seed.

    Raises:
        BatchBackendMissing: the ``gpu`` extra is not installed.
    """
    from factask.batch.env import BatchEnv
    from factask.batch.oracle import run_oracle
    from factask.sim.episode import run_episode

    start = time.perf_counter()
    batch = BatchEnv(graph, len(seeds), device=device)
    batch.reset(seed=[int(s) for s in seeds])
    result = run_oracle(batch)
    singles = [run_episode(graph, int(s)) for s in seeds]
    took = time.perf_counter() - start
    return [SeedAgreement(name, int(s), bool(result.success[k]), int(result.actions[k]),
                          result.failure[k], bool(one.success), int(one.steps), one.failure,
                          round(took, 2))
            for k, (s, one) in enumerate(zip(seeds, singles, strict=True))]


__all__ = ["NOT_BATCHED", "SeedAgreement", "batched", "compare_task"]
