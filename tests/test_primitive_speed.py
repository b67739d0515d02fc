"""Issue 13's fast primitive: sleeping objects, the sloped travel line, rest tests."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from factask.geometry import Pose
from factask.library import get_task
from factask.sim.env import FactaskEnv
from factask.sim.robots.primitive import CLEARANCE, MIN_TRAVEL_HEIGHT


@pytest.fixture(scope="module")
def env() -> FactaskEnv:
    """A library task on the floating cup, reset (its objects resting)."""
    e = FactaskEnv(get_task("rainbow-stack"), robot="floating")
    e.reset(seed=0)
    return e


def _trees(env: FactaskEnv) -> np.ndarray:
    return np.array([env.model.body_treeid[h.body_id] for h in env.scene.objects.values()])


def test_resting_objects_sleep_and_a_sleeping_block_is_still_picked(env: FactaskEnv) -> None:
    assert env.model.opt.enableflags & int(mujoco.mjtEnableBit.mjENBL_SLEEP)
    env.reset(seed=0)
    for _ in range(20):  # a few more steps: the sleep countdown runs out
        mujoco.mj_step(env.model, env.data)
    assert (env.data.tree_asleep[_trees(env)] >= 0).all()
    name = next(iter(env.scene.objects))
    start = env.object_poses()[name]
    top = start.pos + np.array([0.0, 0.0, env.objects[name].half[2]])
    goal = np.array([0.5, 0.3, top[2]])
    result = env.robot.pick_and_place(Pose.from_xyz_yaw(*top, start.yaw),
                                      Pose.from_xyz_yaw(*goal, start.yaw))
    assert result.ok, result.reason
    moved = env.object_poses()[name].pos
    assert np.linalg.norm(moved[:2] - goal[:2]) < 0.005


def test_writing_a_pose_wakes_a_sleeping_object(env: FactaskEnv) -> None:
    from factask.sim.build.compile import set_object_pose

    env.reset(seed=0)
    for _ in range(20):
        mujoco.mj_step(env.model, env.data)
    name, handle = next(iter(env.scene.objects.items()))
    pose = env.object_poses()[name]
    set_object_pose(env.model, env.data, handle,
                    Pose.from_xyz_yaw(*(pose.pos + np.array([0, 0, 0.05])), pose.yaw))
    for _ in range(150):
        mujoco.mj_step(env.model, env.data)
    assert env.object_poses()[name].pos[2] == pytest.approx(pose.pos[2], abs=0.002)


def test_corridor_obstacles_and_travel_heights_clear_every_object(env: FactaskEnv) -> None:
    env.reset(seed=0)
    robot, gripper = env.robot, env.robot.gripper
    poses = env.object_poses()
    names = list(poses)
    up = np.array([0, 0, 0.03])
    start = poses[names[0]].pos + up
    goal = poses[names[1]].pos + up
    t_lo, t_hi, top = gripper.corridor_obstacles(start, goal, 0.05)
    assert len(top) >= 2 and (t_lo <= t_hi).all()
    assert ((t_lo >= 0) & (t_hi <= 1)).all()
    assert max(top) == pytest.approx(gripper.obstacle_top(start, goal, 0.05))
    h0, h1 = robot._travel_heights(start, goal)
    assert min(h0, h1) >= MIN_TRAVEL_HEIGHT
    # The straight line from (start, h0) to (goal, h1) is CLEARANCE above each object
    # wherever the object lies under it (nothing is held: no hang).
    for lo, hi, z in zip(t_lo, t_hi, top, strict=True):
        for t in (lo, hi):
            assert h0 + t * (h1 - h0) >= z + CLEARANCE - 1e-9


def test_rest_test_weighs_turning_by_the_object_size(env: FactaskEnv) -> None:
    env.reset(seed=0)
    gripper = env.robot.gripper
    dof = gripper.object_dofs[:6]
    env.data.qvel[dof] = 0.0
    env.data.qvel[dof[3]] = 0.1  # 0.1 rad/s: points 5 cm out move at 5 mm/s
    assert gripper.objects_resting(0.01)
    assert not gripper.objects_resting(0.004)
    env.data.qvel[dof] = 0.0
    assert not gripper.held_can_roll()  # nothing held
