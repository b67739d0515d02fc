"""benchmarks/physics_floor.py: the replay the env benchmark divides by is the run's
own physics (same steps, same end), not a cheaper stand-in."""

from __future__ import annotations

import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest

from factask.library import get_task
from factask.sim.env import FactaskEnv
from factask.sim.oracle.scripted import Oracle

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import physics_floor


@pytest.mark.parametrize("robot", ["floating", "arm"])
def test_replay_runs_the_recorded_steps_to_the_runs_end(robot: str) -> None:
    env = FactaskEnv(get_task("place-red-in-green"), robot=robot)
    env.reset(seed=0)
    action = Oracle(env).act()
    env.reset(seed=0)
    with physics_floor.record_inputs(env.model, env.data) as log:
        env.step(action)
    assert log.steps == env.history[-1].sim_steps > 100
    moved = float(np.abs(log.end_qpos - log.start[0][1:1 + env.model.nq]).max())
    weld = env.model.eq_obj2id.copy(), env.model.eq_data.copy()
    cost, drift = physics_floor.replay_time(log)
    # The model's suction weld is left as the run left it.
    assert np.array_equal(env.model.eq_obj2id, weld[0])
    assert np.array_equal(env.model.eq_data, weld[1])
    # The block was carried tens of centimetres; the replay ends where the run did.
    assert moved > 0.05
    assert drift < 1e-3
    assert 0.0 < cost.cpu < 1e-3


def test_record_inputs_restores_mj_step() -> None:
    env = FactaskEnv(get_task("place-red-in-green"), robot="floating")
    env.reset(seed=0)
    original = mujoco.mj_step
    with physics_floor.record_inputs(env.model, env.data):
        assert mujoco.mj_step is not original
    assert mujoco.mj_step is original
