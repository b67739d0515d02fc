"""Control-rate frames: one LeRobot frame per low-level command sample.

``factask collect --frames control`` records an episode as the stream of low-level
commands the robot's controller receives, sampled every
:data:`~factask.sim.robots.primitive.DEFAULT_CALLBACK_EVERY` physics steps while actions run
(50 Hz at the 2 ms timestep), the layout LeRobot's own robot datasets use (one frame
per control period, ``action`` the command for the next period). Frame k holds:

* ``observation.state``: the suction tip's pose and suction at sample k;
* ``observation.environment_state``: every object's pose at sample k;
* ``action``: the low-level command in force at sample k + 1, i.e. where the
  controller sends the robot during the next period (the last frame repeats its own):
  the floating cup's commanded tip pose (it is a mocap body: the command is applied
  exactly, so the command equals the tip's pose one period later) or an arm's joint
  position targets (``data.ctrl``), then suction on;
* ``action.primitive``: the decision it belongs to, encoded as a decision frame's
  ``action`` (:mod:`factask.datasets.actions`: the two poses, lift, hinge, the
  primitive's code), and ``decision_index`` which decision that is;
* ``next.total_reward`` / ``next.factor_rewards``: the task's status as the env checks
  it, once per decision: the status before the decision on its samples, the status
  after it on the decision's last sample; ``next.reward`` is the change of
  ``next.total_reward`` from the frame before (so the rewards add up to the episode's
  reward gain); ``next.done`` on the episode's last frame when the env ended it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from factask.datasets.actions import ACTION_WIDTH
from factask.vocabulary.errors import FactaskError

#: The frame modes of a collection: one frame per decision, or per control sample.
FRAME_MODES = ("decision", "control")
#: Names of a floating cup's low-level command: the commanded tip pose, suction.
FLOATING_COMMAND_NAMES = ["cmd_x", "cmd_y", "cmd_z", "cmd_qw", "cmd_qx", "cmd_qy", "cmd_qz",
                          "cmd_suction"]


class FrameModeError(FactaskError, ValueError):
    """A frame mode or rate that cannot be recorded as asked."""


def check_frame_mode(frames: str) -> None:
    """Raise :class:`FrameModeError` unless ``frames`` is one of :data:`FRAME_MODES`."""
    if frames not in FRAME_MODES:
        raise FrameModeError(f"frames {frames!r}: use one of {', '.join(FRAME_MODES)}")


def control_fps(timestep: float) -> int:
    """Samples per second of the low-level stream at a physics ``timestep`` (s).

    Raises:
        FrameModeError: the rate is not a whole number of frames per second (LeRobot's
            ``fps`` is an integer and timestamps are frame_index / fps).
    """
    from factask.sim.robots.primitive import DEFAULT_CALLBACK_EVERY

    rate = 1.0 / (timestep * DEFAULT_CALLBACK_EVERY)
    if abs(rate - round(rate)) > 1e-6:
        raise FrameModeError(f"a timestep of {timestep} s samples commands at {rate:.4g} Hz, "
                             "not a whole number of frames per second")
    return round(rate)


def default_control_fps() -> int:
    """The command rate of scenes compiled at the default timestep (50)."""
    from factask.sim.build.compile import DEFAULT_TIMESTEP

    return control_fps(DEFAULT_TIMESTEP)


def command_names(robot: str) -> list[str]:
    """Names of ``action`` in control frames for a robot of the registry.

    Raises:
        RobotError: no robot of that name.
    """
    from factask.sim.robots.arm import JOINT_NAMES
    from factask.sim.robots.registry import robot_entry

    if robot_entry(robot).arm is None:
        return list(FLOATING_COMMAND_NAMES)
    return [f"{j}_target" for j in JOINT_NAMES] + ["cmd_suction"]


@dataclass
class ControlStream:
    """What the recorder samples every control period (lists, one item per sample)."""

    step: list[int] = field(default_factory=list)
    time: list[float] = field(default_factory=list)
    ctrl: list[np.ndarray] = field(default_factory=list)
    tip: list[list[float]] = field(default_factory=list)
    # Control-frame recordings only: the state to re-render each sample, the objects.
    qpos: list[np.ndarray] = field(default_factory=list)
    mocap_pos: list[np.ndarray] = field(default_factory=list)
    mocap_quat: list[np.ndarray] = field(default_factory=list)
    objects: list[np.ndarray] = field(default_factory=list)


@dataclass
class DecisionRows:
    """Per decision: the status before and after it, its goal and the env's end flag."""

    total_before: list[float] = field(default_factory=list)
    factors_before: list[list[float]] = field(default_factory=list)
    total_after: list[float] = field(default_factory=list)
    factors_after: list[list[float]] = field(default_factory=list)
    goal: list[str] = field(default_factory=list)
    done: list[bool] = field(default_factory=list)


def control_columns(stream: ControlStream, rows: DecisionRows, actions: Sequence[np.ndarray],
                    nu: int, env_width: int, n_factors: int) -> dict[str, Any]:
    """The per-frame arrays of a control-frame episode (see the module docstring).

    Args:
        stream: The sampled stream (with ``objects``).
        rows: One entry per decision.
        actions: Each decision, encoded (:func:`~factask.datasets.actions.encode_action`).
        nu: The robot's actuators (the command is ``ctrl``); 0: the floating cup.
        env_width: 7 x the task's objects.
        n_factors: Factors of the task.

    Returns:
        Keys ``state``, ``environment_state``, ``action``, ``primitive``, ``decision``,
        ``reward``, ``total_reward``, ``factor_rewards``, ``done``, ``goal``.
    """
    n = len(stream.step)
    dec = np.asarray(stream.step, np.int64).reshape(n)
    tip = np.asarray(stream.tip, np.float64).reshape(n, 8)
    command = (np.concatenate([np.asarray(stream.ctrl, np.float64).reshape(n, nu),
                               tip[:, 7:]], axis=1) if nu else tip)
    # The command in force at the next sample; the last frame holds its own.
    action = np.concatenate([command[1:], command[-1:]]) if n else command
    last_of_decision = np.append(dec[1:] != dec[:-1], True) if n else np.zeros(0, bool)
    total = np.asarray([rows.total_after[d] if last else rows.total_before[d]
                        for d, last in zip(dec, last_of_decision, strict=True)], np.float64)
    factors = np.asarray([rows.factors_after[d] if last else rows.factors_before[d]
                          for d, last in zip(dec, last_of_decision, strict=True)], np.float64)
    start = rows.total_before[0] if rows.total_before else 0.0
    reward = np.diff(total, prepend=start)
    done = np.zeros(n, bool)
    if n:
        done[-1] = rows.done[-1]
    primitive = (np.asarray(actions, np.float64).reshape(-1, ACTION_WIDTH)[dec] if n
                 else np.zeros((0, ACTION_WIDTH)))
    return {
        "state": tip.astype(np.float32),
        "environment_state": np.asarray(stream.objects, np.float32).reshape(n, env_width),
        "action": action.astype(np.float32),
        "primitive": primitive.astype(np.float32),
        "decision": dec,
        "reward": reward.astype(np.float32),
        "total_reward": total.astype(np.float32),
        "factor_rewards": factors.astype(np.float32).reshape(n, n_factors),
        "done": done,
        "goal": [rows.goal[d] for d in dec],
    }
