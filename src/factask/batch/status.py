"""A whole task's status in every world: factor progress, reward, success, milestones.

The batched twin of :func:`factask.sim.layout.checks.check_task`: every factor is
re-checked in every world from the current poses (:mod:`factask.batch.checks`),
milestones latch per world exactly as :func:`~factask.sim.layout.checks.latch_milestones`
latches them, reward = sum of weight x progress (clipped to [0, 1]), success =
every final factor satisfied and every milestone reached. A world whose poses
are not finite (the simulation failed there) gets reward 0 and no success, as the
single env's failed state does.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from factask.batch.checks import BatchFactorStatus, check_factor_batch
from factask.batch.scene import BatchScene
from factask.batch.targets import BatchTargets
from factask.graph.order import topological_order
from factask.graph.taskgraph import TaskGraph
from factask.relations.status import CheckError


@dataclass(frozen=True)
class BatchTaskStatus:
    """How far the task is in every world.

    Attributes:
        factor_names: The factors, in graph order (the columns below).
        reward: Weighted sum of factor progress (W,), in [0, 1].
        success: Every final factor satisfied and every milestone reached (W,).
        progress: Factor progress (W, F) (a waiting factor 0, a latched milestone 1).
        satisfied: Factor satisfied (W, F).
        reached: Factors reached so far (W, F): pass it to the next check.
        finite: Worlds whose poses were finite (W,); elsewhere everything is 0.
        factors: Each factor's live status as its relation found it (before latching).
    """

    factor_names: tuple[str, ...]
    reward: np.ndarray
    success: np.ndarray
    progress: np.ndarray
    satisfied: np.ndarray
    reached: np.ndarray
    finite: np.ndarray
    factors: Mapping[str, BatchFactorStatus]


def latch_milestones_batch(graph: TaskGraph, progress: np.ndarray, satisfied: np.ndarray,
                           reached: np.ndarray) -> np.ndarray:
    """Latch milestones in order in every world, rewriting ``progress`` and
    ``satisfied`` (W, F) in place (the rules of
    :func:`~factask.sim.layout.checks.latch_milestones`).

    Args:
        graph: The task graph (valid: its order is acyclic).
        progress: Live progress per world and factor (graph order); rewritten.
        satisfied: Live satisfied; rewritten.
        reached: Factors reached at earlier checks (W, F).

    Returns:
        The factors reached now (W, F), a superset of ``reached``.
    """
    names = graph.factor_names()
    col = {n: k for k, n in enumerate(names)}
    d = graph.dependency_graph()
    now = np.array(reached, dtype=bool, copy=True)
    w = progress.shape[0]
    # Per factor: (W, F) mask of milestones before it (anywhere upstream) not reached.
    pending: dict[str, np.ndarray] = {}
    for name in topological_order(d, names):
        k = col[name]
        milestone = graph.factor(name).milestone
        preds = [col[p] for p in d.predecessors(name)]
        mask = np.zeros((w, len(names)), dtype=bool)
        for p in preds:
            mask |= pending[names[p]]
            if graph.factor(names[p]).milestone:
                mask[:, p] |= ~now[:, p]
        pending[name] = mask
        waiting = ~now[:, preds].all(axis=1) if preds else np.zeros(w, dtype=bool)
        latched = now[:, k] if milestone else np.zeros(w, dtype=bool)
        wait = (waiting if milestone else mask.any(axis=1)) & ~latched
        live_ok = satisfied[:, k] & ~waiting & ~latched & ~wait
        progress[latched, k] = 1.0
        satisfied[latched, k] = True
        progress[wait, k] = 0.0
        satisfied[wait, k] = False
        now[live_ok, k] = True
    return now


def check_task_batch(graph: TaskGraph, targets: Mapping[str, BatchTargets], scene: BatchScene,
                     reached: np.ndarray | None = None) -> BatchTaskStatus:
    """Reward and success of the whole task in every world (every factor re-checked).

    Args:
        graph: The task graph.
        targets: Factor name -> its stacked solved targets, for every factor.
        scene: Every world's poses.
        reached: Factors reached at earlier checks (W, F) in graph order (default none).

    Returns:
        The :class:`BatchTaskStatus`.

    Raises:
        CheckError: a factor has no targets, or the scene lacks an instance.
        InvalidValueError: a relation without a batched check.
    """
    names = tuple(graph.factor_names())
    w = scene.num_worlds
    live: dict[str, BatchFactorStatus] = {}
    for f in graph.factors:
        if f.name not in targets:
            raise CheckError(f"factor {f.name!r} has no solved targets in the batch")
        live[f.name] = check_factor_batch(f.goal, targets[f.name], scene)
    progress = np.stack([live[n].progress for n in names], axis=1).astype(float)
    satisfied = np.stack([live[n].satisfied for n in names], axis=1).astype(bool)
    before = np.zeros((w, len(names)), dtype=bool) if reached is None else \
        np.asarray(reached, dtype=bool)
    if graph.milestones():
        now = latch_milestones_batch(graph, progress, satisfied, before)
    else:
        now = satisfied.copy()
    weights = np.array([f.weight for f in graph.factors], dtype=float)
    reward = np.clip((progress * weights).sum(axis=1), 0.0, 1.0)
    final = np.array([not f.milestone for f in graph.factors], dtype=bool)
    success = np.where(final, satisfied, now).all(axis=1) & (len(names) > 0)
    finite = scene.finite()
    reward = np.where(finite, reward, 0.0)
    success &= finite
    progress[~finite] = 0.0
    satisfied[~finite] = False
    return BatchTaskStatus(names, reward, success, progress, satisfied, now, finite, live)


__all__ = ["BatchTaskStatus", "check_task_batch", "latch_milestones_batch"]
