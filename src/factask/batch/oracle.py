"""The oracle in lockstep: every world's next action planned at once, executed together.

Each loop plans every running world's next action with
:class:`~factask.batch.planner.LockstepPlanner` — the single env's scripted oracle's
rules written as array work over worlds, a world whose step needs more (an obstacle
to move, a receptacle taken by its rim, ...) planned alone by its own scalar
:class:`~factask.sim.oracle.scripted.Oracle` — then runs every world's pick-and-place
at once (:func:`factask.batch.primitive.pick_and_place`) and re-checks every world.
Worlds that are done (success, the oracle gave up, the action budget used up, a
physics failure) stand still while the others go on.

Pushes (piles) and low carries (ropes) are not batched yet: a world whose oracle
asks for one stops with that reason.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from factask.batch.planner import LockstepPlanner, WorldView
from factask.vocabulary.tolerances import SUCCESS_REWARD

if TYPE_CHECKING:
    from factask.batch.env import BatchEnv


@dataclass(frozen=True)
class BatchEpisodeResult:
    """The oracle's episodes in every world.

    Attributes:
        success: Final total reward at least ``SUCCESS_REWARD`` (num_envs,).
        reward: Final total reward (num_envs,).
        actions: Actions each world took (num_envs,).
        failure: Why each world stopped short (None where it succeeded).
        sim_steps: Physics steps of the whole run (every world steps them).
        planning_seconds: Host time spent planning each lockstep action (every world's).
        planned_arrays: Actions planned as array work over worlds.
        planned_fallback: Actions the scalar oracle planned for one world alone.
    """

    success: np.ndarray
    reward: np.ndarray
    actions: np.ndarray
    failure: list[str | None]
    sim_steps: int
    planning_seconds: tuple[float, ...] = ()
    planned_arrays: int = 0
    planned_fallback: int = 0


def planner_for(batch: BatchEnv) -> LockstepPlanner:
    """A :class:`LockstepPlanner` for the batch's worlds as they were last reset (each
    world's scalar oracle seeded with its reset seed, as
    :func:`factask.sim.episode.run_episode` seeds its oracle)."""
    return LockstepPlanner(batch.graph, batch.objects, batch.object_names, batch.solved,
                           [int(s) for s in batch.seeds])


def run_oracle(batch: BatchEnv, max_actions: int | None = None) -> BatchEpisodeResult:
    """Run the oracle in every world from the batch's current (reset) state, in lockstep.

    Args:
        batch: A floating-cup batch, every world reset.
        max_actions: Action budget per world (default ``graph.max_actions()``).

    Returns:
        The :class:`BatchEpisodeResult`.
    """
    w = batch.num_envs
    planner = planner_for(batch)
    budget = batch.graph.max_actions() if max_actions is None else int(max_actions)
    done = np.zeros(w, dtype=bool)
    actions = np.zeros(w, dtype=int)
    failure: list[str | None] = [None] * w
    steps = 0
    timings: list[float] = []
    status = batch.status()
    while not done.all():
        problems = batch.physics_failures()
        for k in np.flatnonzero(~done):
            if problems[k] is not None:
                done[k], failure[k] = True, problems[k]
            elif actions[k] >= budget and not status.success[k]:
                done[k], failure[k] = True, f"action budget of {budget} used up"
        if done.all():
            break
        start = time.perf_counter()
        plan = planner.plan(batch.scene(), status, ~done)
        took = time.perf_counter() - start
        for k in np.flatnonzero(plan.stop):
            done[k], failure[k] = True, plan.failure[k]
        if not plan.act.any():
            break
        timings.append(took)
        result = batch.pick_and_place(plan.pick, plan.place, plan.act)
        steps += result.sim_steps
        actions += plan.act
        status = batch.status()
    success = status.reward >= SUCCESS_REWARD
    failure = [None if s else (f or "did not succeed") for s, f in
               zip(success, failure, strict=True)]
    return BatchEpisodeResult(success, status.reward.copy(), actions, failure, steps,
                              tuple(timings), planner.planned_arrays, planner.planned_fallback)


__all__ = ["BatchEpisodeResult", "WorldView", "planner_for", "run_oracle"]
