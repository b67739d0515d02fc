"""Replay a recorded episode from its states file.

* :func:`resimulate` runs the episode again (the graph, robot and seed of the file, then
  its recorded actions) and returns the states it passes through; factask's physics is
  deterministic, so they equal the recorded ones bit for bit (:func:`compare_states`).
* :func:`render_states` re-renders the recorded states from the stored MJCF at any
  cameras and resolution, without factask's compiler or a re-simulation.
"""

from __future__ import annotations

from collections.abc import Sequence

import mujoco
import numpy as np

from factask.datasets.actions import decode_action
from factask.datasets.states import EpisodeStates, snapshot
from factask.graph.taskgraph import parse_graph
from factask.sim.render.cameras import CameraRig, CameraSpec


def resimulate(states: EpisodeStates) -> EpisodeStates:
    """The states of the episode run again from its graph, robot, seed and actions.

    Raises:
        ActionEncodingError: an action that encodes no primitive (a corrupt file).
    """
    from factask.sim.env import FactaskEnv

    graph = parse_graph(states.graph)
    env = FactaskEnv(graph, robot=states.robot)
    try:
        env.reset(seed=states.seed)
        snaps = [snapshot(env.data)]
        for a in states.actions:
            env.step(decode_action(a))  # any primitive (factask.datasets.actions)
            snaps.append(snapshot(env.data))
    finally:
        env.close()
    return EpisodeStates(
        mjcf=env.scene.xml, graph=states.graph, robot=states.robot, seed=states.seed,
        qpos=np.stack([s[0] for s in snaps]), qvel=np.stack([s[1] for s in snaps]),
        mocap_pos=np.stack([s[2] for s in snaps]), mocap_quat=np.stack([s[3] for s in snaps]),
        actions=states.actions.copy())


def compare_states(a: EpisodeStates, b: EpisodeStates) -> list[str]:
    """Where two episodes' states differ at all (empty: bit-identical)."""
    out = []
    for key in ("qpos", "qvel", "mocap_pos", "mocap_quat", "actions"):
        x, y = getattr(a, key), getattr(b, key)
        if x.shape != y.shape:
            out.append(f"{key}: shape {x.shape} != {y.shape}")
        elif not np.array_equal(x, y):
            rows = np.unique(np.nonzero(x != y)[0])
            out.append(f"{key}: differs at steps {rows[:10].tolist()} "
                       f"(max |diff| {np.max(np.abs(x - y)):.3g})")
    return out


def render_states(states: EpisodeStates, cameras: Sequence[CameraSpec],
                  steps: Sequence[int] | None = None,
                  control: bool = False) -> dict[str, np.ndarray]:
    """Images of recorded states from the stored MJCF.

    Args:
        states: The episode's states.
        cameras: The cameras (any pose, intrinsics and size).
        steps: State indices (default: every frame of the dataset: 0 .. T - 1, or every
            control sample with ``control``).
        control: Render the control samples' states (a ``--frames control`` dataset)
            instead of the states before each decision.

    Returns:
        Camera name -> (len(steps), height, width, 3) uint8.

    Raises:
        StatesFileError: ``control`` for a file without per-sample states.
    """
    model = mujoco.MjModel.from_xml_string(states.mjcf)
    data = mujoco.MjData(model)
    count = len(states.control_step) if control else states.steps
    steps = list(range(count)) if steps is None else list(steps)
    apply = states.apply_control if control else states.apply
    with CameraRig(model, tuple(cameras), np.full(model.ngeom, -1)) as rig:
        out: dict[str, list[np.ndarray]] = {c.name: [] for c in cameras}
        for t in steps:
            apply(model, data, t)
            for c in cameras:
                out[c.name].append(rig.rgb(data, c.name))
    return {k: (np.stack(v) if v else np.zeros((0, c.height, c.width, 3), np.uint8))
            for (k, v), c in zip(out.items(), cameras, strict=True)}
