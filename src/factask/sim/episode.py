"""Oracle episodes and the research's success definitions.

* An **episode** succeeds when its total reward reaches
  :data:`~factask.vocabulary.tolerances.SUCCESS_REWARD` (0.99).
* A **task** is completed when at least
  :data:`~factask.vocabulary.tolerances.COMPLETION_FRACTION` (half) of its episodes succeed.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from factask.graph.taskgraph import TaskGraph
from factask.vocabulary.errors import FactaskError
from factask.vocabulary.tolerances import COMPLETION_FRACTION, SUCCESS_REWARD


@dataclass
class EpisodeResult:
    """One oracle episode.

    Attributes:
        seed: Reset seed.
        reward: Final total reward in [0, 1].
        success: ``reward >= SUCCESS_REWARD`` (the research's definition).
        all_satisfied: Every factor satisfied at once at the end (factask's own,
            stricter success: a factor of tiny weight can fail while reward >= 0.99).
        steps: Pick-and-place actions taken.
        factors: Factor name -> final progress.
        failure: Why the episode did not end with every factor satisfied (the
            oracle's reason, a physics failure, the action budget, a layout
            error), or None.
        details: Factor name -> what is still off.
        sim_seconds: Simulated seconds the actions took.
    """

    seed: int
    reward: float
    success: bool
    steps: int
    factors: dict[str, float] = field(default_factory=dict)
    failure: str | None = None
    details: dict[str, str] = field(default_factory=dict)
    sim_seconds: float = 0.0
    all_satisfied: bool = False

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


@dataclass
class TaskResult:
    """Several oracle episodes of one task."""

    task: str
    episodes: list[EpisodeResult]

    @property
    def success_rate(self) -> float:
        return sum(e.success for e in self.episodes) / len(self.episodes) if self.episodes else 0.0

    @property
    def completed(self) -> bool:
        return bool(self.episodes) and self.success_rate >= COMPLETION_FRACTION

    def to_dict(self) -> dict[str, Any]:
        return {"task": self.task, "episodes": [e.to_dict() for e in self.episodes],
                "success_rate": self.success_rate, "completed": self.completed}


ActionCallback = Callable[[int, Any, dict[str, Any]], None]


def run_episode(graph: TaskGraph, seed: int, robot: str = "floating",
                video: str | Path | None = None,
                on_action: ActionCallback | None = None,
                env: Any = None) -> EpisodeResult:
    """Run the oracle for one episode.

    Args:
        graph: The task.
        seed: Reset seed.
        robot: A name of the robot registry (:mod:`factask.sim.robots.registry`).
        video: Write a GIF/MP4 of the episode here (the front view, framed from the
            scene's bounds after the reset: :func:`factask.sim.render.offscreen.framed_camera`).
        on_action: Called after each action with (action index, planned action, info).
        env: Reuse this :class:`~factask.sim.env.FactaskEnv` (must be of ``graph``).

    Returns:
        The result; layout and physics failures are recorded in ``failure``, not raised.

    Raises:
        GraphValidationError, CompileError: the graph cannot be compiled (only when
            ``env`` is not given).
    """
    from factask.sim.env import FactaskEnv
    from factask.sim.oracle.scripted import Oracle

    own_env = env is None
    if env is None:
        env = FactaskEnv(graph, robot=robot)
    recorder = None
    try:
        try:
            _, info = env.reset(seed=seed)
        except FactaskError as exc:
            return EpisodeResult(seed, 0.0, False, 0, failure=f"reset: {exc}")
        if video is not None:
            from factask.sim.render.offscreen import VideoRecorder, framed_camera

            # Framed once, after the reset: the robot (an arm's base too) and every
            # object stay whole, and the view holds still through the episode.
            width, height = env.render_size
            view = framed_camera(env.model, env.data, "front", aspect=width / height)
            recorder = VideoRecorder(video)
            recorder.append(env.render_rgb(camera=view))
            counter = {"n": 0}

            def frame() -> None:
                counter["n"] += 1
                if counter["n"] % 6 == 0:  # one frame every 60 physics steps (0.12 s)
                    recorder.append(env.render_rgb(camera=view))

            env.frame_callback = frame
        oracle = Oracle(env, seed=seed)
        failure = info.get("failure")
        sim_seconds = 0.0
        terminated = truncated = failure is not None
        while not (terminated or truncated):
            planned = oracle.plan()
            if planned is None:
                failure = oracle.failure
                break
            _, _, terminated, truncated, info = env.step(planned.as_env_action())
            sim_seconds += env.history[-1].sim_steps * env.model.opt.timestep
            if on_action is not None:
                on_action(env.actions_taken, planned, info)
            failure = info.get("failure")
        if truncated and not info.get("success"):
            failure = failure or f"action budget of {graph.max_actions()} used up"
        reward = float(info.get("total_reward", 0.0))
        all_satisfied = bool(info.get("success"))
        return EpisodeResult(
            seed=seed, reward=reward, success=reward >= SUCCESS_REWARD,
            steps=env.actions_taken, factors=dict(info.get("factors", {})),
            failure=None if all_satisfied else (failure or "not every factor is satisfied"),
            details={k: v for k, v in info.get("details", {}).items() if v},
            sim_seconds=sim_seconds, all_satisfied=all_satisfied,
        )
    finally:
        if recorder is not None:
            env.frame_callback = None
            recorder.append(env.render_rgb(camera=view))
            recorder.close()
        if own_env:
            env.close()


def evaluate_task(graph: TaskGraph, episodes: int = 10, seed: int = 0,
                  robot: str = "floating",
                  on_episode: Callable[[EpisodeResult], None] | None = None) -> TaskResult:
    """Oracle episodes with seeds ``seed, seed + 1, ...`` on one compiled environment."""
    from factask.sim.env import FactaskEnv

    env = FactaskEnv(graph, robot=robot)
    try:
        results = []
        for k in range(episodes):
            r = run_episode(graph, seed + k, robot=robot, env=env)
            results.append(r)
            if on_episode is not None:
                on_episode(r)
        return TaskResult(graph.name, results)
    finally:
        env.close()


def check_runtime(graph: TaskGraph, seed: int = 0, robot: str = "floating") -> str | None:
    """None if the graph compiles, resets and steps without error, else why not.

    The step is one oracle action (or, if the oracle has nothing to do, the robot
    picking at an empty spot).
    """
    from factask.sim.env import FactaskEnv
    from factask.sim.oracle.scripted import Oracle

    try:
        env = FactaskEnv(graph, robot=robot)
    except FactaskError as exc:
        return f"compile: {exc}"
    try:
        _, info = env.reset(seed=seed)
        if info.get("failure"):
            return f"reset: {info['failure']}"
        planned = Oracle(env, seed=seed).plan()
        action = planned.as_env_action() if planned is not None else {
            "pick": [0.5, 0.0, 0.0, 0.0], "place": [0.5, 0.0, 0.05, 0.0]}
        _, _, _, _, info = env.step(action)
        if info.get("failure"):
            return f"step: {info['failure']}"
        return None
    except FactaskError as exc:
        return f"reset: {exc}"
    finally:
        env.close()


def summarize(results: Sequence[TaskResult]) -> dict[str, Any]:
    """Totals over tasks: tasks_total, tasks_completed, episode_success_rate."""
    episodes = [e for r in results for e in r.episodes]
    return {
        "tasks_total": len(results),
        "tasks_completed": sum(r.completed for r in results),
        "episode_success_rate": (sum(e.success for e in episodes) / len(episodes)
                                 if episodes else 0.0),
    }
