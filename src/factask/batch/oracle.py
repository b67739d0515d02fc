"""The oracle in lockstep: one plan per world, executed together.

Each world gets the single env's scripted oracle (:class:`factask.sim.oracle.scripted.Oracle`,
unchanged), which reads a :class:`WorldView` — that world's objects, solved
targets, poses, held object and scalar status, as the oracle reads an env — and
plans its next action. The batch then runs every world's pick-and-place at once
(:func:`factask.batch.primitive.pick_and_place`) and re-checks every world. Worlds
that are done (success, the oracle gave up, the action budget used up, a physics
failure) stand still while the others go on.

Planning is Python, world by world (the oracle's own code); only the physics is
batched. Pushes (piles) and low carries (ropes) are not batched yet: a world whose
oracle asks for one stops with that reason.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, cast

import numpy as np

from factask.geometry import Pose
from factask.sim.layout.checks import TaskStatus, check_task
from factask.sim.oracle.scripted import Oracle, OracleAction
from factask.vocabulary.tolerances import SUCCESS_REWARD

if TYPE_CHECKING:
    from factask.batch.env import BatchEnv
    from factask.sim.env import FactaskEnv


class WorldView:
    """One world of a batch, read as the oracle reads a :class:`FactaskEnv`.

    Args:
        batch: The batch.
        world: The world's index.
    """

    def __init__(self, batch: BatchEnv, world: int) -> None:
        self.batch, self.world = batch, int(world)
        self.graph = batch.graph
        self.objects = batch.objects
        self._poses: dict[str, Pose] = {}
        self._held: set[str] = set()

    @property
    def solved(self) -> dict:
        """The world's solved factors (its own layout's targets)."""
        return self.batch.solved[self.world]

    def refresh(self, poses: np.ndarray, held: str | None) -> None:
        """Take this world's poses (n, 7) and held object from a batch snapshot."""
        self._poses = {n: Pose(p[:3], p[3:]) for n, p in
                       zip(self.batch.object_names, poses, strict=True)}
        self._held = {held} if held else set()

    def object_poses(self) -> dict[str, Pose]:
        """Every object's pose in this world (as of the last refresh)."""
        return dict(self._poses)

    def held_objects(self) -> set[str]:
        """The instance this world's cup holds (as of the last refresh)."""
        return set(self._held)

    def status(self) -> TaskStatus:
        """The scalar status of this world (milestones reached so far kept latched)."""
        reached = {n for n, r in zip(self.batch.factor_names, self.batch.reached[self.world],
                                     strict=True) if r}
        return check_task(self.graph, self.solved, self._poses, self._held, self.objects,
                          reached)


@dataclass(frozen=True)
class BatchEpisodeResult:
    """The oracle's episodes in every world.

    Attributes:
        success: Final total reward at least ``SUCCESS_REWARD`` (num_envs,).
        reward: Final total reward (num_envs,).
        actions: Actions each world took (num_envs,).
        failure: Why each world stopped short (None where it succeeded).
        sim_steps: Physics steps of the whole run (every world steps them).
    """

    success: np.ndarray
    reward: np.ndarray
    actions: np.ndarray
    failure: list[str | None]
    sim_steps: int


def run_oracle(batch: BatchEnv, max_actions: int | None = None) -> BatchEpisodeResult:
    """Run the oracle in every world from the batch's current (reset) state, in lockstep.

    Each world's oracle is seeded with the world's reset seed, as
    :func:`factask.sim.episode.run_episode` seeds its oracle with the episode's.

    Args:
        batch: A floating-cup batch, every world reset.
        max_actions: Action budget per world (default ``graph.max_actions()``).

    Returns:
        The :class:`BatchEpisodeResult`.
    """
    w = batch.num_envs
    views = [WorldView(batch, k) for k in range(w)]
    # The oracle reads only what a WorldView has (objects, solved, poses, held, status).
    oracles = [Oracle(cast("FactaskEnv", v), seed=int(batch.seeds[k]))
               for k, v in enumerate(views)]
    budget = batch.graph.max_actions() if max_actions is None else int(max_actions)
    done = np.zeros(w, dtype=bool)
    actions = np.zeros(w, dtype=int)
    failure: list[str | None] = [None] * w
    steps = 0
    status = batch.status()
    while not done.all():
        poses, held = batch.object_poses(), batch.held_objects()
        problems = batch.physics_failures()
        pick, place = np.array(batch.command), np.array(batch.command)
        active = np.zeros(w, dtype=bool)
        for k in np.flatnonzero(~done):
            if problems[k] is not None:
                done[k], failure[k] = True, problems[k]
                continue
            if status.success[k]:
                done[k] = True
                continue
            if actions[k] >= budget:
                done[k], failure[k] = True, f"action budget of {budget} used up"
                continue
            views[k].refresh(poses[k], held[k])
            planned = oracles[k].plan()
            if planned is None:
                done[k] = True
                failure[k] = oracles[k].failure or "the oracle stopped"
            elif not isinstance(planned, OracleAction):
                done[k] = True
                failure[k] = f"{type(planned).__name__} is not batched yet"
            else:
                pick[k], place[k], active[k] = planned.pick, planned.place, True
        if not active.any():
            break
        result = batch.pick_and_place(pick, place, active)
        steps += result.sim_steps
        actions += active
        status = batch.status()
    success = status.reward >= SUCCESS_REWARD
    failure = [None if s else (f or "did not succeed") for s, f in
               zip(success, failure, strict=True)]
    return BatchEpisodeResult(success, status.reward.copy(), actions, failure, steps)


__all__ = ["BatchEpisodeResult", "WorldView", "run_oracle"]
