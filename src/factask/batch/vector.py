"""The batch as a gymnasium ``VectorEnv``: the single env's spaces, one action per world.

:class:`BatchVectorEnv` wraps a :class:`~factask.batch.env.BatchEnv` (floating cup)
so that a vectorised policy sees what it sees from ``num_envs`` copies of the
gymnasium id's env (``gymnasium.make("factask/<task>-v0")``, state mode): the same
observation and action spaces (batched; the state keys with ``factor_progress``,
``instruction`` and ``goal``), an action = one suction pick-and-place per world (run
in lockstep), the reward = each world's change of total reward, ``terminated`` on
success or a physics failure, ``truncated`` when the world's action budget is spent.
Finished worlds reset on the next step (gymnasium's ``NEXT_STEP`` autoreset: that step returns
their first observation, reward 0, neither flag) from fresh seeds drawn from the
seed given to :meth:`BatchVectorEnv.reset`.

The gymnasium ids' ``vector_entry_point`` makes it:
``gymnasium.make_vec("factask/<task>-v0", num_envs=N, device="cpu")``
(:func:`factask.registration.make_vector_env`).

Not yet: pushes and low carries, observation modes other than ``state``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from factask.batch.env import BatchEnv, make_batch
from factask.graph.taskgraph import TaskGraph
from factask.sim.render.observations import ObservationWrapper, encode_text
from factask.vocabulary.errors import InvalidValueError


class BatchVectorEnv(VectorEnv):
    """``num_envs`` worlds of one task as a gymnasium vector env (see the module doc).

    Args:
        task: A task graph or a library task's name.
        num_envs: Number of worlds.
        device: ``"cpu"``, ``"cuda"``, ``"cuda:N"`` or None (a GPU if there is one).
        **kwargs: Passed to :class:`~factask.batch.env.BatchEnv`.

    Raises:
        BatchBackendMissing, DeviceUnavailableError: see :func:`make_batch`.
    """

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP}  # noqa: RUF012 (gymnasium's)

    def __init__(self, task: TaskGraph | str, num_envs: int, device: str | None = None,
                 **kwargs: Any) -> None:
        self.batch: BatchEnv = make_batch(task, num_envs, device=device, **kwargs)
        self.num_envs = self.batch.num_envs
        single = self.batch.cpu_env
        # The state-mode wrapper of the id's env: its space and its goal rule, per world.
        self._language = ObservationWrapper(single)
        self._instruction = encode_text(self._language.instruction)
        self.single_observation_space = self._language.observation_space
        self.single_action_space = single.action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.budget = self.batch.graph.max_actions()
        self._actions = np.zeros(self.num_envs, dtype=int)
        self._total = np.zeros(self.num_envs)
        self._autoreset = np.zeros(self.num_envs, dtype=bool)

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None
              ) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        """Reset every world (or ``options["reset_mask"]``'s); world i gets seed
        ``seed + i`` (fresh seeds if None), and later autoresets draw from ``seed``.

        Returns:
            (observation, info with ``total_reward``, ``success`` and ``seeds``).
        """
        mask = np.ones(self.num_envs, dtype=bool)
        if options and "reset_mask" in options:
            mask = np.asarray(options["reset_mask"], dtype=bool)
        if seed is not None:
            self.batch._seed_rng = np.random.default_rng(seed)
        obs = self.batch.reset(seed=seed, worlds=mask)
        self._actions[mask] = 0
        self._autoreset[mask] = False
        status = self.batch.status()
        self._total[mask] = status.reward[mask]
        return self._observe(obs, status), {"total_reward": status.reward,
                                            "success": status.success,
                                            "seeds": self.batch.seeds.copy()}

    def step(self, actions: dict[str, np.ndarray]
             ) -> tuple[dict[str, np.ndarray], np.ndarray, np.ndarray, np.ndarray,
                        dict[str, Any]]:
        """One pick-and-place per world (``actions["pick"]``, ``actions["place"]``:
        (num_envs, 4) each); worlds that finished last step reset instead.

        Returns:
            (observation, reward, terminated, truncated, info); info has
            ``total_reward``, ``success``, ``action_ok``, ``failure`` per world.

        Raises:
            InvalidValueError: actions without ``pick`` and ``place``, or malformed.
        """
        if not isinstance(actions, dict) or not {"pick", "place"} <= set(actions):
            raise InvalidValueError("actions must be a dict with 'pick' and 'place', "
                                    f"(num_envs, 4) each; got {type(actions).__name__}")
        fresh = self._autoreset.copy()
        if fresh.any():
            seeds = self.batch._seed_rng.integers(0, 2**31 - 1, size=int(fresh.sum()))
            self.batch.reset(seed=seeds, worlds=fresh)
            self._actions[fresh] = 0
        act = ~fresh
        result = self.batch.pick_and_place(actions["pick"], actions["place"], act)
        status = self.batch.status()
        failures = self.batch.physics_failures()
        failed = np.array([f is not None for f in failures])
        reward = np.where(act, status.reward - self._total, 0.0)
        self._total = status.reward.copy()
        self._actions += act
        terminated = act & (status.success | failed)
        truncated = act & ~terminated & (self._actions >= self.budget)
        self._autoreset = terminated | truncated
        info = {"total_reward": status.reward, "success": status.success,
                "action_ok": result.ok, "failure": failures, "actions": self._actions.copy()}
        return self._observe(self.batch.observe(), status), reward, terminated, truncated, info

    def _observe(self, obs: dict[str, np.ndarray], status: Any) -> dict[str, np.ndarray]:
        """The batch's state keys with each world's factor progress, instruction, goal."""
        names = list(status.factor_names)
        order = [names.index(n) for n in self._language.factor_names]
        goals = [encode_text(self._language.current_goal(
            {"satisfied": dict(zip(names, row.tolist(), strict=True))}))
            for row in status.satisfied]
        return obs | {
            "factor_progress": np.clip(status.progress[:, order], 0.0, 1.0).astype(np.float64),
            "instruction": np.repeat(self._instruction[None], self.num_envs, axis=0),
            "goal": np.stack(goals)}

    def close_extras(self, **kwargs: Any) -> None:
        """Release the batch's single env."""
        self.batch.close()


def make_vector(task: TaskGraph | str, num_envs: int, device: str | None = None,
                **kwargs: Any) -> BatchVectorEnv:
    """A :class:`BatchVectorEnv` of ``task`` (see there)."""
    return BatchVectorEnv(task, num_envs, device=device, **kwargs)


__all__ = ["BatchVectorEnv", "make_vector"]
