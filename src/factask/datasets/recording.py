"""Record one episode: per-frame state, action, rewards, language, camera images, states.

By default a frame is one decision: the observation *before* an action, the action, and
what it led to (LeRobot's ``next.*`` convention). An episode of T actions has T frames;
the states file holds T + 1 states (the last one after the final action). With
``frames="control"`` a frame is one sample of the low-level command stream instead
(:mod:`factask.datasets.control_frames`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from factask.datasets.actions import ACTION_NAMES, ACTION_WIDTH, encode_action
from factask.datasets.control_frames import (
    ControlStream,
    DecisionRows,
    FrameModeError,
    check_frame_mode,
    control_columns,
    control_fps,
)
from factask.datasets.states import EpisodeStates, snapshot
from factask.sim.env import FactaskEnv
from factask.sim.render.cameras import CameraRig
from factask.vocabulary.errors import FactaskError
from factask.vocabulary.tolerances import SUCCESS_REWARD

#: Names of ``observation.state``: the suction tip's pose and whether it holds.
STATE_NAMES = ["ee_x", "ee_y", "ee_z", "ee_qw", "ee_qx", "ee_qy", "ee_qz", "suction"]
__all__ = ["ACTION_NAMES", "STATE_NAMES", "EpisodeRecord", "PolicyFactory", "oracle_policy",
           "record_episode", "record_episodes"]

#: A policy for recording: (env, seed) -> a callable giving the next action or None.
PolicyFactory = Callable[[FactaskEnv, int], Callable[[], dict[str, np.ndarray] | None]]


@dataclass
class EpisodeRecord:
    """One recorded episode (arrays have one row per frame)."""

    task: str
    instruction: str
    seed: int
    success: bool
    final_reward: float
    state: np.ndarray
    environment_state: np.ndarray
    action: np.ndarray
    reward: np.ndarray
    total_reward: np.ndarray
    factor_rewards: np.ndarray
    done: np.ndarray
    goal: list[str]
    images: dict[str, np.ndarray]
    states: EpisodeStates
    failure: str | None = None
    factor_names: list[str] = field(default_factory=list)
    #: Control frames only: each frame's decision, encoded (n, ACTION_WIDTH), its index (n,).
    primitive: np.ndarray | None = None
    decision: np.ndarray | None = None

    @property
    def length(self) -> int:
        """Frames."""
        return len(self.action)


def oracle_policy(env: FactaskEnv, seed: int) -> Callable[[], dict[str, np.ndarray] | None]:
    """The scripted oracle, seeded like :func:`~factask.sim.episode.run_episode`."""
    from factask.sim.oracle.scripted import Oracle

    return Oracle(env, seed=seed).act


def _current_goal(env: FactaskEnv, info: dict[str, Any]) -> str:
    satisfied = info.get("satisfied", {})
    goals = {f.name: f.description or "" for f in env.graph.factors}
    for name in env.graph.factor_order():
        if not satisfied.get(name, False):
            return goals[name]
    return ""


def record_episode(env: FactaskEnv, seed: int, rig: CameraRig | None = None,
                   policy: PolicyFactory = oracle_policy, frames: str = "decision",
                   fps: int | None = None) -> EpisodeRecord:
    """Run one episode and record it.

    Args:
        env: The environment (compiled once, reused across episodes).
        seed: Reset seed.
        rig: Cameras to record (None: no images).
        policy: Makes the episode's policy (default: the oracle).
        frames: "decision" (a frame per action) or "control" (a frame per sample of
            the low-level command stream, with camera images at each sample).
        fps: Control frames only: the dataset's fps, which must be the stream's rate.

    Returns:
        The record; a layout or physics failure ends it early (``failure`` says why).

    Raises:
        FrameModeError: an unknown ``frames``, or an ``fps`` that is not the stream's rate.
    """
    check_frame_mode(frames)
    control = frames == "control"
    if control and fps is not None and fps != control_fps(env.model.opt.timestep):
        raise FrameModeError(f"control frames come at {control_fps(env.model.opt.timestep)} "
                             f"per second, not {fps} (fix: leave --fps out)")
    failure: str | None = None
    obs: dict[str, np.ndarray] = {}
    try:
        obs, info = env.reset(seed=seed)
    except FactaskError as exc:
        info, failure = {}, f"reset: {exc}"
    names = env.graph.factor_names()
    act = policy(env, seed) if failure is None else (lambda: None)
    rows: dict[str, list[Any]] = {k: [] for k in (
        "state", "env", "action", "reward", "total", "factors", "done", "goal")}
    images: dict[str, list[np.ndarray]] = {c.name: [] for c in rig.cameras} if rig else {}
    snaps = [snapshot(env.data)]
    actions: list[np.ndarray] = []
    stream = ControlStream()
    decisions = DecisionRows()

    def sample() -> None:
        # The low-level command stream, every few physics steps while an action runs.
        stream.step.append(len(actions))
        stream.time.append(float(env.data.time))
        stream.ctrl.append(env.data.ctrl.copy())
        tip = env.robot.ee_pose()
        stream.tip.append([*tip.to_list(), 1.0 if env.robot.grasped() is not None else 0.0])
        if control:
            _, _, mocap_pos, mocap_quat = snapshot(env.data)
            stream.qpos.append(env.data.qpos.copy())
            stream.mocap_pos.append(mocap_pos)
            stream.mocap_quat.append(mocap_quat)
            poses = env.object_poses()
            stream.objects.append(np.concatenate([poses[o].to_list()
                                                  for o in env.object_names] or [[]]))
            for cam in images:
                images[cam].append(rig.rgb(env.data, cam))  # type: ignore[union-attr]

    env.frame_callback = sample
    failure = failure or info.get("failure")
    while failure is None:
        action = act()
        if action is None:
            break
        goal = _current_goal(env, info)
        for cam in images if not control else ():
            images[cam].append(rig.rgb(env.data, cam))  # type: ignore[union-attr]
        vec = encode_action(action)  # every primitive (factask.datasets.actions)
        rows["state"].append(np.concatenate([obs["ee_pose"], obs["suction"]]))
        rows["env"].append(obs["object_poses"].reshape(-1))
        decisions.total_before.append(float(info.get("total_reward", 0.0)))
        decisions.factors_before.append([info.get("factors", {}).get(n, 0.0) for n in names])
        obs, reward, terminated, truncated, info = env.step(action)
        rows["action"].append(vec)
        rows["reward"].append(reward)
        rows["total"].append(info["total_reward"])
        rows["factors"].append([info["factors"].get(n, 0.0) for n in names])
        rows["done"].append(terminated or truncated)
        rows["goal"].append(goal)
        actions.append(vec)
        snaps.append(snapshot(env.data))
        failure = info.get("failure")
        if terminated or truncated:
            break
    env.frame_callback = None
    decisions.total_after, decisions.factors_after = rows["total"], rows["factors"]
    decisions.goal, decisions.done = rows["goal"], rows["done"]
    final = float(info.get("total_reward", 0.0))
    t = len(actions)
    n_env = 7 * len(env.object_names)

    def arr(key: str, width: int | None, dtype: Any = np.float32) -> np.ndarray:
        shape = (t,) if width is None else (t, width)
        return np.asarray(rows[key], dtype=dtype).reshape(shape)

    states = _episode_states(env, seed, snaps, actions, stream)
    shapes = {c.name: (c.height, c.width, 3) for c in rig.cameras} if rig else {}
    record = EpisodeRecord(
        task=env.graph.name, instruction=env.graph.description or env.graph.name, seed=seed,
        success=final >= SUCCESS_REWARD, final_reward=final,
        state=arr("state", len(STATE_NAMES)), environment_state=arr("env", n_env),
        action=arr("action", ACTION_WIDTH), reward=arr("reward", None),
        total_reward=arr("total", None),
        factor_rewards=arr("factors", len(names)), done=arr("done", None, bool),
        goal=list(rows["goal"]),
        images={k: (np.stack(v) if v else np.zeros((0, *shapes[k]), np.uint8))
                for k, v in images.items()},
        states=states, failure=failure, factor_names=names)
    if control:
        cols = control_columns(stream, decisions, actions, nu=int(env.model.nu),
                               env_width=n_env, n_factors=len(names))
        record.state, record.environment_state = cols["state"], cols["environment_state"]
        record.action, record.primitive, record.decision = (
            cols["action"], cols["primitive"], cols["decision"])
        record.reward, record.total_reward = cols["reward"], cols["total_reward"]
        record.factor_rewards, record.done = cols["factor_rewards"], cols["done"]
        record.goal = cols["goal"]
    return record


def _episode_states(env: FactaskEnv, seed: int, snaps: list[tuple[np.ndarray, ...]],
                    actions: list[np.ndarray], stream: ControlStream) -> EpisodeStates:
    m, n = env.model, len(stream.step)
    return EpisodeStates(
        mjcf=env.scene.xml, graph=env.graph.to_json(indent=None), robot=env.robot_kind,
        seed=seed, qpos=np.stack([s[0] for s in snaps]), qvel=np.stack([s[1] for s in snaps]),
        mocap_pos=np.stack([s[2] for s in snaps]), mocap_quat=np.stack([s[3] for s in snaps]),
        actions=np.asarray(actions, dtype=np.float64).reshape(len(actions), ACTION_WIDTH),
        control_step=np.asarray(stream.step, np.int32),
        control_time=np.asarray(stream.time, np.float64),
        control=np.asarray(stream.ctrl, np.float64).reshape(n, m.nu),
        control_tip=np.asarray(stream.tip, np.float64).reshape(-1, 8),
        control_qpos=np.asarray(stream.qpos, np.float64).reshape(-1, m.nq),
        control_mocap_pos=np.asarray(stream.mocap_pos, np.float64).reshape(-1, m.nmocap, 3),
        control_mocap_quat=np.asarray(stream.mocap_quat, np.float64).reshape(-1, m.nmocap, 4))


def record_episodes(env: FactaskEnv, seeds: Sequence[int], rig: CameraRig | None = None,
                    policy: PolicyFactory = oracle_policy, frames: str = "decision",
                    fps: int | None = None) -> list[EpisodeRecord]:
    """:func:`record_episode` for each seed, on one env."""
    return [record_episode(env, s, rig, policy, frames, fps) for s in seeds]
