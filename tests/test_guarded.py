"""Work skipped when nothing can change: guarded descents test contacts only once a
contact is possible, and the env re-checks the task only when the state moved."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
from test_robot import BLOCK, build_scene

from factask.geometry import Pose
from factask.library import get_task
from factask.sim.build.compile import set_object_pose
from factask.sim.env import FactaskEnv


def _scene(kind: str, blocks: tuple[tuple[float, float], ...]):
    """:func:`test_robot.build_scene` with the robot at home."""
    model, data, robot = build_scene(kind, blocks)
    robot.reset()
    mujoco.mj_step(model, data, 50)
    return model, data, robot


def _stack_two(kind: str, on_step) -> tuple[np.ndarray, list[int]]:
    """Put block 1 on block 0, then block 2 on block 1 with a place pose 1 cm too low
    (the guarded descent must stop on contact); the final qpos and the steps taken."""
    _, data, robot = _scene(kind, ((0.5, 0.1), (0.4, -0.2), (0.6, -0.1)))
    steps = []
    for pick, place in (((0.4, -0.2, BLOCK), (0.5, 0.1, 2 * BLOCK + 0.005)),
                        ((0.6, -0.1, BLOCK), (0.5, 0.1, 3 * BLOCK - 0.01))):
        result = robot.pick_and_place(Pose.from_xyz_yaw(*pick), Pose.from_xyz_yaw(*place),
                                      on_step=on_step)
        assert result.ok, result.reason
        steps.append(result.sim_steps)
    return data.qpos.copy(), steps


def test_clearance_under_cup_and_under_held_block() -> None:
    """The gap below the cup (or the held block) down to what lies under it."""
    model, data, robot = _scene("floating", ((0.5, 0.1), (0.8, 0.5)))
    grip = robot.gripper
    data.mocap_pos[robot.mocap] = (0.5, 0.1, BLOCK + 0.03)
    mujoco.mj_forward(model, data)
    assert grip.clearance(held=False, margin=0.01) == pytest.approx(0.03, abs=5e-4)
    # Beside the block: down to the table.
    data.mocap_pos[robot.mocap] = (0.3, -0.3, 0.03)
    mujoco.mj_forward(model, data)
    assert grip.clearance(held=False, margin=0.01) == pytest.approx(0.03, abs=5e-4)
    assert grip.clearance(held=True, margin=0.01) == -np.inf  # nothing held
    # Holding block 1 above block 0: from the held block's bottom to block 0's top.
    z = BLOCK + 0.01
    while not grip.cup_in_contact():
        assert z > BLOCK - 0.005, "the cup never touched block 1"
        data.mocap_pos[robot.mocap] = (0.8, 0.5, z)
        mujoco.mj_step(model, data)
        z -= 0.0002
    assert robot.suction_on()
    data.mocap_pos[robot.mocap] = (0.5, 0.1, 2 * BLOCK + 0.02)
    mujoco.mj_step(model, data, 200)
    assert grip.clearance(held=True, margin=0.01) == pytest.approx(0.02, abs=2e-3)


@pytest.mark.parametrize("kind", ["floating", "arm"])
def test_guarded_descents_end_as_when_every_step_is_tested(kind: str) -> None:
    """With a callback every step is played one by one and every guarded step
    tested; without one, the steps before contact is possible are played in one
    go: the same physics, step for step."""
    fast, fast_steps = _stack_two(kind, None)
    slow, slow_steps = _stack_two(kind, lambda: None)
    assert fast_steps == slow_steps
    np.testing.assert_array_equal(fast, slow)


def test_status_is_kept_until_the_state_changes() -> None:
    """Between actions the env's status is the one checked after the last action;
    moving an object makes it check again."""
    env = FactaskEnv(get_task("place-red-in-green"))
    try:
        env.reset(seed=0)
        kept = env.status()
        assert env.status() is kept
        name = env.object_names[0]
        pose = env.object_poses()[name]
        set_object_pose(env.model, env.data, env.scene.objects[name],
                        Pose(pose.pos + np.array([0.0, 0.0, 0.05]), pose.quat))
        again = env.status()
        assert again is not kept
        assert again.reward == pytest.approx(kept.reward)
    finally:
        env.close()


def test_descent_over_nothing_runs_to_its_end() -> None:
    """Off the table nothing lies below the cup (an infinite clearance): the guarded
    descent plays to its end and reports no contact."""
    _, data, robot = _scene("floating", ((0.5, 0.1),))
    data.mocap_pos[robot.mocap] = (2.0, 2.0, 0.2)
    mujoco.mj_forward(robot.model, data)
    robot._hold_here()
    assert robot.gripper.clearance(held=False, margin=0.01) == np.inf
    assert robot._descend(np.array([2.0, 2.0, 0.1]), robot._cmd_yaw, held=False) is False
    assert data.mocap_pos[robot.mocap][2] == pytest.approx(0.1)

