"""The states file of one episode: everything needed to re-simulate and re-render it.

One ``.npz`` per episode (``states/episode_XXXXXX.npz`` beside the dataset) with:

* ``mjcf``: the compiled scene's MJCF text (re-render without factask's compiler);
* ``graph``: the task graph's JSON, ``robot``, ``seed`` (re-simulate with factask);
* ``qpos``, ``qvel`` (T + 1, nq / nv) float64, ``mocap_pos`` (T + 1, nmocap, 3),
  ``mocap_quat`` (T + 1, nmocap, 4): the state before each action and at the end;
* ``actions`` (T, 12) float64: each action encoded (:mod:`factask.datasets.actions`:
  the two poses, lift, hinge x y, the primitive's code); a file of layout 1 held
  (T, 8) picks and places, read as pick-and-places;
* the low-level stream, sampled while actions run (every few physics steps):
  ``control_step`` (n,) the action it belongs to, ``control_time`` (n,) simulated
  seconds, ``control`` (n, nu) the actuator commands (``data.ctrl``; the arm's joint
  targets, empty for the mocap cup), ``control_tip`` (n, 8) the suction tip's pose
  (x y z, quaternion w x y z) and suction on;
* with control frames (``factask collect --frames control``) also the state at each
  sample, to re-render the dataset's video frames: ``control_qpos`` (n, nq),
  ``control_mocap_pos`` (n, nmocap, 3), ``control_mocap_quat`` (n, nmocap, 4); empty
  (0 rows) otherwise.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import mujoco
import numpy as np

from factask.datasets.actions import upgrade_actions
from factask.vocabulary.errors import FactaskError

#: Version of the states file layout (2: every primitive's actions, 12 wide; 1: picks
#: and places, 8 wide, still read).
STATES_VERSION = 2
#: Older layouts :func:`read_states` reads.
_READABLE = (1, STATES_VERSION)
#: Per-sample states, written only with control frames (files without them read empty).
_CONTROL_STATES = ("control_qpos", "control_mocap_pos", "control_mocap_quat")


class StatesFileError(FactaskError, ValueError):
    """A states file that is missing, unreadable or of another layout."""


@dataclass
class EpisodeStates:
    """The simulator states of one episode (see the module docstring)."""

    mjcf: str
    graph: str
    robot: str
    seed: int
    qpos: np.ndarray
    qvel: np.ndarray
    mocap_pos: np.ndarray
    mocap_quat: np.ndarray
    actions: np.ndarray
    control_step: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int32))
    control_time: np.ndarray = field(default_factory=lambda: np.zeros(0))
    control: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    control_tip: np.ndarray = field(default_factory=lambda: np.zeros((0, 8)))
    control_qpos: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    control_mocap_pos: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 3)))
    control_mocap_quat: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 4)))

    @property
    def steps(self) -> int:
        """Actions taken (the states hold one more row)."""
        return len(self.actions)

    def apply(self, model: mujoco.MjModel, data: mujoco.MjData, t: int) -> None:
        """Put state ``t`` into ``data`` and compute positions (``mj_forward``)."""
        data.qpos[:] = self.qpos[t]
        data.qvel[:] = self.qvel[t]
        if model.nmocap:
            data.mocap_pos[:] = self.mocap_pos[t]
            data.mocap_quat[:] = self.mocap_quat[t]
        mujoco.mj_forward(model, data)

    def apply_control(self, model: mujoco.MjModel, data: mujoco.MjData, k: int) -> None:
        """Put control sample ``k``'s positions into ``data`` and compute them.

        Raises:
            StatesFileError: the file holds no per-sample states (decision frames).
        """
        if k >= len(self.control_qpos):
            raise StatesFileError(f"no state for control sample {k}: the episode has "
                                  f"{len(self.control_qpos)} (recorded with --frames control?)")
        data.qpos[:] = self.control_qpos[k]
        data.qvel[:] = 0.0
        if model.nmocap:
            data.mocap_pos[:] = self.control_mocap_pos[k]
            data.mocap_quat[:] = self.control_mocap_quat[k]
        mujoco.mj_forward(model, data)


def snapshot(data: mujoco.MjData) -> tuple[np.ndarray, ...]:
    """(qpos, qvel, mocap_pos, mocap_quat) copies of ``data`` now."""
    return (data.qpos.copy(), data.qvel.copy(), data.mocap_pos.copy(), data.mocap_quat.copy())


def write_states(path: Path, states: EpisodeStates) -> None:
    """Write ``states`` to ``path`` atomically (a temporary file, then a rename)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    with open(tmp, "wb") as fh:
        np.savez_compressed(
            fh, version=np.int64(STATES_VERSION), mjcf=np.str_(states.mjcf),
            graph=np.str_(states.graph), robot=np.str_(states.robot),
            seed=np.int64(states.seed), qpos=states.qpos, qvel=states.qvel,
            mocap_pos=states.mocap_pos, mocap_quat=states.mocap_quat, actions=states.actions,
            control_step=states.control_step, control_time=states.control_time,
            control=states.control, control_tip=states.control_tip,
            control_qpos=states.control_qpos, control_mocap_pos=states.control_mocap_pos,
            control_mocap_quat=states.control_mocap_quat)
    os.replace(tmp, path)


def read_states(path: Path) -> EpisodeStates:
    """Read a states file.

    Raises:
        StatesFileError: missing, unreadable, or another layout version.
    """
    try:
        with np.load(path, allow_pickle=False) as z:
            version = int(z["version"])
            if version not in _READABLE:
                raise StatesFileError(f"{path}: states layout {version}, this factask reads "
                                      f"{_READABLE} (fix: collect the dataset again)")
            actions = z["actions"] if version > 1 else upgrade_actions(z["actions"])
            return EpisodeStates(
                mjcf=str(z["mjcf"]), graph=str(z["graph"]), robot=str(z["robot"]),
                seed=int(z["seed"]), qpos=z["qpos"], qvel=z["qvel"],
                mocap_pos=z["mocap_pos"], mocap_quat=z["mocap_quat"], actions=actions,
                control_step=z["control_step"], control_time=z["control_time"],
                control=z["control"], control_tip=z["control_tip"],
                **{k: z[k] for k in _CONTROL_STATES if k in z.files})
    except (OSError, KeyError, ValueError) as exc:
        if isinstance(exc, StatesFileError):
            raise
        raise StatesFileError(f"cannot read states file {path}: {exc} (fix: give a "
                              "states/episode_XXXXXX.npz of a collected dataset)") from exc

