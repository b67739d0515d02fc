"""Policy evaluation: a policy over tasks x test seeds, success rates with 95 % intervals.

A policy is given as text: ``oracle`` or ``random`` (the two reference policies), or
``module:callable``. The callable is either a function ``obs -> action`` or an object
with ``act(obs) -> action`` (and optionally ``reset(seed)``, called before each
episode); a class or zero-argument factory is instantiated first. An action is the
env's ``{"pick": (x, y, z, yaw), "place": (...)}``; ``None`` ends the episode.

Per episode: success once (the task was complete at any step), success at the end,
final total reward, actions. Per task: the two success rates with Wilson 95 % intervals
and the mean total reward with a normal 95 % interval.
"""

from __future__ import annotations

import importlib
import inspect
import math
import os
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from factask.datasets.parallel import run_jobs
from factask.datasets.splits import split_seeds
from factask.vocabulary.errors import FactaskError

#: The reference policies.
REFERENCE_POLICIES = ("oracle", "random")
#: z of the 95 % normal quantile.
Z95 = 1.959963984540054

Policy = Callable[[dict[str, Any]], dict[str, Any] | None]


class PolicyError(FactaskError, ValueError):
    """A policy that cannot be loaded or called."""


@dataclass
class EpisodeOutcome:
    """One evaluated episode."""

    task: str
    seed: int
    success_once: bool
    success_at_end: bool
    total_reward: float
    actions: int
    failure: str | None = None


@dataclass
class TaskScore:
    """One task's results with 95 % intervals (low, high)."""

    task: str
    episodes: int
    success_once: float
    success_once_ci: tuple[float, float]
    success_at_end: float
    success_at_end_ci: tuple[float, float]
    mean_reward: float
    mean_reward_ci: tuple[float, float]

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def wilson_interval(successes: int, n: int, z: float = Z95) -> tuple[float, float]:
    """Wilson score interval of a success rate (exact-ish at small n, never outside [0, 1])."""
    if n == 0:
        return (0.0, 1.0)
    p = successes / n
    denom = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / denom
    # Rounded: p = 0 or 1 would otherwise leave a 1e-17 residue at the bound.
    return (round(max(0.0, centre - half), 12), round(min(1.0, centre + half), 12))


def mean_interval(values: Sequence[float], z: float = Z95) -> tuple[float, float]:
    """Normal 95 % interval of a mean (zero width for fewer than two values)."""
    arr = np.asarray(values, dtype=float)
    if len(arr) < 2:
        m = float(arr.mean()) if len(arr) else 0.0
        return (m, m)
    half = z * float(arr.std(ddof=1)) / math.sqrt(len(arr))
    return (float(arr.mean()) - half, float(arr.mean()) + half)


def score(task: str, outcomes: Sequence[EpisodeOutcome]) -> TaskScore:
    """Aggregate one task's outcomes."""
    n = len(outcomes)
    once = sum(o.success_once for o in outcomes)
    end = sum(o.success_at_end for o in outcomes)
    rewards = [o.total_reward for o in outcomes]
    return TaskScore(task, n, once / n if n else 0.0, wilson_interval(once, n),
                     end / n if n else 0.0, wilson_interval(end, n),
                     float(np.mean(rewards)) if n else 0.0, mean_interval(rewards))


# ---------------------------------------------------------------- policies
class _Oracle:
    """The scripted oracle as a policy (it reads the env, not the observation)."""

    def __init__(self, env: Any) -> None:
        self.env = env
        self.oracle: Any = None

    def reset(self, seed: int) -> None:
        from factask.sim.oracle.scripted import Oracle

        self.oracle = Oracle(self.env.unwrapped, seed=seed)

    def act(self, obs: dict[str, Any]) -> dict[str, Any] | None:
        return self.oracle.act()


class _Random:
    """Uniform pick and place over the workspace (seeded per episode)."""

    def __init__(self, env: Any) -> None:
        self.space = env.action_space

    def reset(self, seed: int) -> None:
        self.space.seed(seed)

    def act(self, obs: dict[str, Any]) -> dict[str, Any] | None:
        return self.space.sample()


def load_policy(spec: str, env: Any) -> Any:
    """The policy object of ``spec`` for ``env`` (see the module docstring).

    Raises:
        PolicyError: not a reference policy and not an importable ``module:callable``.
    """
    if spec == "oracle":
        return _Oracle(env)
    if spec == "random":
        return _Random(env)
    module_name, _, attr = spec.partition(":")
    if not module_name or not attr:
        raise PolicyError(f"policy {spec!r}: give 'oracle', 'random' or module:callable "
                          "(fix: e.g. my_policies:GraspNet)")
    try:
        obj: Any = getattr(importlib.import_module(module_name), attr)
    except (ImportError, AttributeError) as exc:
        raise PolicyError(f"policy {spec!r}: cannot import it ({exc})") from exc
    if inspect.isclass(obj):
        obj = obj()
    if not (hasattr(obj, "act") or callable(obj)):
        raise PolicyError(f"policy {spec!r}: neither callable nor an object with act(obs)")
    return obj


def run_policy_episode(env: Any, policy: Any, task: str, seed: int) -> EpisodeOutcome:
    """One episode of ``policy`` on an observation-mode env (``factask.make``)."""
    try:
        obs, info = env.reset(seed=seed)
    except FactaskError as exc:
        return EpisodeOutcome(task, seed, False, False, 0.0, 0, f"reset: {exc}")
    if hasattr(policy, "reset"):
        policy.reset(seed)
    act = policy.act if hasattr(policy, "act") else policy
    once = bool(info.get("success"))
    steps, failure = 0, info.get("failure")
    done = failure is not None or once
    while not done:
        action = act(obs)
        if action is None:
            break
        obs, _, terminated, truncated, info = env.step(action)
        steps += 1
        once = once or bool(info.get("success"))
        failure = info.get("failure")
        done = terminated or truncated
    return EpisodeOutcome(task, seed, once, bool(info.get("success")),
                          float(info.get("total_reward", 0.0)), steps, failure)


def video_path(video_dir: str, task: str, seed: int) -> Path:
    """Where the video of one evaluated episode goes."""
    slug = "".join(ch if ch.isalnum() or ch in "-_" else "_" for ch in task)[-60:]
    return Path(video_dir) / f"{slug}-seed{seed}.mp4"


def evaluate_task_seeds(policy_spec: str, task: str, seeds: Sequence[int],
                        robot: str = "floating", obs_mode: str = "state",
                        image_size: tuple[int, int] | None = None,
                        video_dir: str | None = None, videos: int = 0
                        ) -> list[EpisodeOutcome]:
    """Evaluate a policy on one task's seeds in this process (the worker's entry point).

    Args:
        video_dir: Write MP4s of the first ``videos`` episodes here (front camera).
    """
    from factask.registration import make_env

    env = make_env(task, robot=robot, obs_mode=obs_mode, image_size=image_size)
    try:
        policy = load_policy(policy_spec, env)
        outcomes = []
        for k, seed in enumerate(seeds):
            recording = None
            if video_dir is not None and k < videos:
                from factask.viz import EpisodeVideo

                recording = EpisodeVideo(video_path(video_dir, task, seed), fps=10.0)
                recording.attach(env.unwrapped)
            try:
                outcomes.append(run_policy_episode(env, policy, task, seed))
            finally:
                if recording is not None:
                    recording.finish()
        return outcomes
    finally:
        env.close()


def evaluate_policy(policy_spec: str, tasks: Sequence[str], episodes: int,
                    split: str = "test", robot: str = "floating", obs_mode: str = "state",
                    workers: int | None = None, image_size: tuple[int, int] | None = None,
                    on_episodes: Callable[[list[EpisodeOutcome]], None] | None = None,
                    video_dir: str | None = None, videos: int = 0,
                    ray_address: str | None = None
                    ) -> tuple[list[EpisodeOutcome], list[TaskScore]]:
    """Evaluate a policy on every task's first ``episodes`` seeds of ``split``.

    Args:
        policy_spec: "oracle", "random" or "module:callable".
        tasks: Library names, ids or graph files.
        episodes: Seeds per task.
        split: The seed split (test by default, as CLIPort reports).
        robot: Robot registry name.
        obs_mode: Observation mode the policy sees.
        workers: Processes (default: cores); tasks run in parallel.
        image_size: Camera size for image modes.
        on_episodes: Called with each task's outcomes as it finishes.
        video_dir: Folder of episode videos (:func:`video_path` names them).
        videos: Episodes per task to film (the first ones).
        ray_address: Run the tasks on Ray ("auto", "local" or an address).

    Returns:
        (outcomes in task then seed order, one score per task).

    Raises:
        PolicyError: the policy cannot be loaded (checked before any worker starts).
    """
    if policy_spec not in REFERENCE_POLICIES:
        load_policy(policy_spec, None)  # fail early, in this process
    seeds = split_seeds(split, episodes)
    if video_dir is not None:
        Path(video_dir).mkdir(parents=True, exist_ok=True)
    args = (robot, obs_mode, image_size, video_dir, videos)
    per_task = run_jobs(evaluate_task_seeds, [(policy_spec, t, seeds, *args) for t in tasks],
                        workers=workers or os.cpu_count() or 1, ray_address=ray_address,
                        on_done=lambda _i, out: on_episodes(out) if on_episodes else None)
    results = dict(zip(tasks, per_task, strict=True))
    outcomes = [o for t in tasks for o in results[t]]
    return outcomes, [score(t, results[t]) for t in tasks]
