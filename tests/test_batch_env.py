"""The batched env (factask.batch) on Warp's CPU device: typed errors for a missing
extra or GPU, seeded resets equal to the single env's, reset of chosen worlds,
stepping every world, status per world.

Kernel compilation happens once per machine (Warp caches it in the user's cache
folder); the tests share one small batch and run in one xdist group so one worker
compiles. A few worlds only: the CPU device is for correctness, not speed.
"""

from __future__ import annotations

import importlib.util
import math
import sys

import gymnasium as gym
import mujoco
import numpy as np
import pytest

from factask.batch import (
    BatchBackendMissing,
    DeviceUnavailableError,
    make_batch,
    resolve_device,
)
from factask.batch.device import load_backend
from factask.batch.env import BatchEnv
from factask.batch.oracle import run_oracle
from factask.batch.vector import BatchVectorEnv
from factask.graph import TaskGraph
from factask.library import get_task
from factask.sim.env import FactaskEnv, ResetNeededError
from factask.sim.episode import run_episode
from factask.sim.render.observations import decode_text
from factask.vocabulary.errors import InvalidValueError

pytestmark = pytest.mark.xdist_group("warp")
if importlib.util.find_spec("mujoco_warp") is None or importlib.util.find_spec("warp") is None:
    pytest.skip("the gpu extra is not installed (make test installs it)",
                allow_module_level=True)

SEEDS = [4, 9, 4]


def small_task() -> TaskGraph:
    """A small library task (a block, a bowl, the floating cup): few bodies, so the CPU
    device steps it quickly."""
    return get_task("put-block-in-bowl")


@pytest.fixture(scope="module")
def batch() -> BatchEnv:
    env = make_batch(small_task(), len(SEEDS), device="cpu")
    env.reset(seed=SEEDS)
    yield env
    env.close()


def test_a_missing_extra_is_a_typed_error(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "mujoco_warp", None)  # import fails as if not installed
    with pytest.raises(BatchBackendMissing, match=r"factask\[gpu\]") as info:
        make_batch(small_task(), 2, device="cpu")
    assert isinstance(info.value, ImportError)


def test_the_first_cpu_batch_says_once_that_kernels_compile(monkeypatch, capsys) -> None:
    """The first batched step on a CPU waits minutes for Warp's compiler: say so once
    (issue 37, item 14), not on a GPU, not twice."""
    from factask.batch import device

    monkeypatch.setattr(device, "_COMPILE_NOTICE_GIVEN", False)
    device.announce_cpu_compile("cuda:0")
    assert capsys.readouterr().err == ""
    device.announce_cpu_compile("cpu")
    device.announce_cpu_compile("cpu")
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and "compiles Warp's kernels the first time" in err[0]


def test_asking_for_a_gpu_that_is_not_there_is_a_typed_error() -> None:
    wp, _ = load_backend()
    if wp.get_cuda_device_count() > 0:
        count = wp.get_cuda_device_count()
        with pytest.raises(DeviceUnavailableError):
            resolve_device(f"cuda:{count}")
        return
    for name in ("cuda", "cuda:0", "CUDA:1"):
        with pytest.raises(DeviceUnavailableError, match="no CUDA GPU") as info:
            resolve_device(name)
        assert isinstance(info.value, RuntimeError)
    with pytest.raises(DeviceUnavailableError):
        make_batch(small_task(), 2, device="cuda")
    assert resolve_device(None) == "cpu"
    for bad in ("tpu", "cuda:x"):
        with pytest.raises(InvalidValueError):
            resolve_device(bad)


def test_a_world_reset_with_seed_s_starts_from_the_single_envs_seed_s_state(
        batch: BatchEnv) -> None:
    obs = batch.observe()
    single = FactaskEnv(small_task())
    for w, seed in enumerate(SEEDS):
        single_obs, _ = single.reset(seed=seed)
        assert batch.seeds[w] == seed
        assert set(batch.initial_layouts[w]) == set(single.initial_layout)
        for name, pose in single.initial_layout.items():
            got = batch.initial_layouts[w][name]
            assert np.array_equal(got.pos, pose.pos) and np.array_equal(got.quat, pose.quat)
        for name, s in single.solved.items():
            assert all(np.array_equal(a.pos, b.pos) for a, b in
                       zip(batch.solved[w][name].slots, s.slots, strict=True))
        # The settled state itself, in Warp's float32.
        assert np.allclose(obs["object_poses"][w], single_obs["object_poses"], atol=1e-6)
        assert np.allclose(obs["ee_pose"][w], single_obs["ee_pose"], atol=1e-6)
        qpos = batch.wp_data.qpos.numpy()[w]
        assert np.allclose(qpos, single.data.qpos.astype(np.float32), atol=1e-6)
    single.close()
    # One seed, one state: worlds 0 and 2 are the same world.
    assert np.array_equal(obs["object_poses"][0], obs["object_poses"][2])


def test_the_batch_status_is_the_single_envs_status(batch: BatchEnv) -> None:
    status = batch.status(latch=False)
    single = FactaskEnv(small_task())
    for w, seed in enumerate(SEEDS):
        _, info = single.reset(seed=seed)
        assert math.isclose(float(status.reward[w]), info["total_reward"], abs_tol=1e-9)
        assert bool(status.success[w]) == info["success"]
        for k, name in enumerate(status.factor_names):
            assert math.isclose(float(status.progress[w, k]), info["factors"][name],
                                abs_tol=1e-9)
    single.close()


def _cpu_rollout(seed: int, commands: np.ndarray) -> np.ndarray:
    """The single env from seed ``seed``, its cup moved along ``commands`` (one mocap
    pose per physics step), as the batch steps it: object poses after."""
    env = FactaskEnv(small_task())
    env.reset(seed=seed)
    m, d = env.model, env.data
    cup = env.robot.mocap  # type: ignore[attr-defined]
    for x, y, z, yaw in commands:
        d.mocap_pos[cup] = (x, y, z)
        d.mocap_quat[cup] = (math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2))
        mujoco.mj_step(m, d)
    out = env._obs()["object_poses"]
    env.close()
    return out


def test_stepping_moves_every_world_as_cpu_mujoco_does(batch: BatchEnv) -> None:
    batch.reset(seed=SEEDS)
    home = batch.home_command()
    assert home.shape == (len(SEEDS), 4)
    # Each world's cup goes its own way: down towards the table, sideways, turning.
    target = home + np.array([[0.2, 0.05, -0.3, 0.3], [0.25, -0.1, -0.35, -0.5],
                              [0.1, 0.0, -0.2, 0.0]])
    steps = 40
    path = home[:, None, :] + (target - home)[:, None, :] * np.linspace(0, 1, steps)[None, :,
                                                                                       None]
    for k in range(steps):
        batch.step(path[:, k], substeps=1)
    ee = batch.observe()["ee_pose"]
    cup_pos = batch.wp_data.mocap_pos.numpy()[:, batch._cup_mocap]
    assert np.allclose(cup_pos, target[:, :3], atol=1e-6)
    # The tip follows the mocap cup (the last step's kinematics saw the last command).
    assert np.allclose(ee[:, :3], path[:, -1, :3], atol=1e-6)
    poses = batch.object_poses()
    for w, seed in enumerate(SEEDS):
        want = _cpu_rollout(seed, path[w])
        assert np.allclose(poses[w], want, atol=2e-5), np.abs(poses[w] - want).max()


def test_resetting_chosen_worlds_leaves_the_others_alone(batch: BatchEnv) -> None:
    batch.reset(seed=SEEDS)
    batch.step(batch.home_command(), substeps=5)
    before = batch.wp_data.qpos.numpy().copy()
    times = batch.wp_data.time.numpy().copy()
    batch.reset(seed=[11], worlds=[1])
    after = batch.wp_data.qpos.numpy()
    assert np.array_equal(after[[0, 2]], before[[0, 2]])
    assert np.array_equal(batch.wp_data.time.numpy()[[0, 2]], times[[0, 2]])
    single = FactaskEnv(small_task())
    single_obs, _ = single.reset(seed=11)
    assert np.allclose(batch.observe()["object_poses"][1], single_obs["object_poses"],
                       atol=1e-6)
    assert batch.seeds.tolist() == [SEEDS[0], 11, SEEDS[2]]
    single.close()
    # A boolean mask works as well as indices; one seed, one state.
    batch.reset(seed=[4, 4], worlds=np.array([True, False, True]))
    poses = batch.observe()["object_poses"]
    assert np.array_equal(poses[0], poses[2])
    assert batch.seeds.tolist() == [4, 11, 4]


def test_bad_commands_and_steps_before_reset_are_refused(batch: BatchEnv) -> None:
    with pytest.raises(InvalidValueError):
        batch.step(np.zeros((len(SEEDS), 3)))
    with pytest.raises(InvalidValueError):
        batch.step(np.full((len(SEEDS), 4), np.nan))
    with pytest.raises(InvalidValueError):
        batch.reset(seed=[1, 2], worlds=[0])
    with pytest.raises(InvalidValueError):
        batch.reset(seed=1, worlds=[7])
    fresh = make_batch(small_task(), 2, device="cpu")
    with pytest.raises(ResetNeededError):
        fresh.step(np.zeros((2, 4)))
    with pytest.raises(ResetNeededError):
        fresh.status()
    fresh.close()


def _move(batch: BatchEnv, start: np.ndarray, end: np.ndarray, steps: int) -> None:
    for s in np.linspace(0.0, 1.0, steps):
        batch.step(start + s * (end - start))


def test_suction_grasps_lifts_and_lets_go_per_world(batch: BatchEnv) -> None:
    batch.reset(seed=SEEDS)
    block = batch.object_names.index("blue_block")
    half = float(batch.objects["blue_block"].half[2])
    start = batch.object_poses()[:, block, :3].copy()
    home = batch.home_command()
    # Worlds 0 and 2 press the cup onto their block's top; world 1 stops 5 cm above it.
    above = home.copy()
    above[:, :2] = start[:, :2]
    above[:, 2] = start[:, 2] + half + 0.05
    touch = above.copy()
    touch[[0, 2], 2] = start[[0, 2], 2] + half - 0.001
    _move(batch, home, above, 60)
    _move(batch, above, touch, 30)
    held = batch.suction_on()
    assert held.tolist() == [True, False, True]
    assert batch.held_objects() == ["blue_block", None, "blue_block"]
    assert batch.observe()["suction"][:, 0].tolist() == [1.0, 0.0, 1.0]
    _assert_device_observation_is_the_hosts(batch)
    assert batch.scene().held[:, block].tolist() == [True, False, True]
    lifted = touch.copy()
    lifted[:, 2] += 0.1
    _move(batch, touch, lifted, 60)
    z = batch.object_poses()[:, block, 2]
    assert np.allclose(z[[0, 2]], start[[0, 2], 2] + 0.1, atol=0.01)  # carried up
    assert abs(z[1] - start[1, 2]) < 1e-3  # untouched
    # A held object never counts (the single env's rule), whatever its pose.
    assert not batch.status(latch=False).success.any()
    batch.suction_off(worlds=[0])
    batch.step(lifted, substeps=150)
    z = batch.object_poses()[:, block, 2]
    assert z[0] < start[0, 2] + 0.03  # let go: fell back towards the table
    assert z[2] > start[2, 2] + 0.08  # still held
    assert batch.held_objects() == [None, None, "blue_block"]
    batch.reset(seed=SEEDS)
    assert batch.held_objects() == [None, None, None]


def _assert_device_observation_is_the_hosts(batch: BatchEnv) -> None:
    host, device = batch.observe(), batch.observe_device()
    assert set(device) == set(host)
    for key, value in host.items():
        assert np.allclose(device[key].numpy(), value, atol=2e-6), key


def test_observations_and_rewards_are_device_arrays_shared_without_a_copy(
        batch: BatchEnv) -> None:
    """DLPack (what wp.to_torch and JAX use) hands the device arrays over as they are:
    the consumer's view shows the next gather without another conversion."""
    from factask.batch.interop import status_arrays  # imports Warp: after the skip

    batch.reset(seed=SEEDS)
    _assert_device_observation_is_the_hosts(batch)
    device = batch.observe_device()
    poses, ee = np.from_dlpack(device["object_poses"]), np.from_dlpack(device["ee_pose"])
    assert poses.ctypes.data == device["object_poses"].ptr
    assert poses.shape == (len(SEEDS), len(batch.object_names), 7)
    assert ee.shape == (len(SEEDS), 7)
    z0 = ee[:, 2].copy()
    cmd = batch.home_command()
    cmd[:, 2] -= 0.05
    batch.step(cmd, substeps=40)
    batch.observe_device()
    # The views taken before the step show the new gather: the same memory.
    assert np.all(ee[:, 2] < z0 - 0.01)
    assert np.allclose(ee, batch.observe()["ee_pose"], atol=2e-6)
    assert np.allclose(poses, batch.observe()["object_poses"], atol=2e-6)
    status = batch.status()
    arrays = status_arrays(status, batch.device)
    assert np.array_equal(np.from_dlpack(arrays["reward"]), status.reward.astype(np.float32))
    assert np.array_equal(arrays["success"].numpy(), status.success)
    assert arrays["progress"].shape == status.progress.shape


def test_no_world_reports_a_physics_failure_and_nan_is_one(batch: BatchEnv) -> None:
    batch.reset(seed=SEEDS)
    batch.step(batch.home_command(), substeps=3)
    assert batch.physics_failures() == [None] * len(SEEDS)
    qpos = batch.wp_data.qpos.numpy().copy()
    qpos[1, 0] = np.nan
    batch.wp_data.qpos.assign(qpos)
    failures = batch.physics_failures()
    assert failures[0] is None and failures[2] is None and "not finite" in failures[1]
    assert not batch.status(latch=False).finite[1]
    batch.reset(seed=SEEDS)
    assert batch.physics_failures() == [None] * len(SEEDS)


def test_a_contact_decimetres_deep_is_a_physics_failure(batch: BatchEnv) -> None:
    # The narrowphase failure the batch guards against (factask.batch.model): finite
    # positions, a contact far deeper than any resting one. Made here by pushing
    # world 1's block 5 cm into the table top.
    batch.reset(seed=SEEDS)
    batch.step(batch.home_command(), substeps=2)
    assert batch.physics_failures() == [None] * len(SEEDS)
    block = next(n for n in batch.object_names if batch.objects[n].kind == "block")
    adr = batch.cpu_env.scene.objects[block].qpos_adr
    qpos = batch.wp_data.qpos.numpy().copy()
    qpos[1, adr + 2] -= 0.05
    batch.wp_data.qpos.assign(qpos)
    batch.step(batch.command, substeps=1)
    failures = batch.physics_failures()
    assert failures[0] is None and failures[2] is None
    assert failures[1] is not None and "deep" in failures[1]
    batch.reset(seed=SEEDS)
    assert batch.physics_failures() == [None] * len(SEEDS)


def test_the_batch_table_top_is_a_plane_at_the_scene_tables_top_face(batch: BatchEnv) -> None:
    scene_model = batch.cpu_env.scene.model
    table = mujoco.mj_name2id(batch.model, mujoco.mjtObj.mjOBJ_GEOM, "table")
    assert scene_model.geom_type[table] == mujoco.mjtGeom.mjGEOM_BOX
    assert batch.model.geom_type[table] == mujoco.mjtGeom.mjGEOM_PLANE
    top = scene_model.geom_pos[table][2] + scene_model.geom_size[table][2]
    assert batch.model.geom_pos[table][2] == pytest.approx(top, abs=1e-12)
    assert batch.model.ngeom == scene_model.ngeom and batch.model.nbody == scene_model.nbody


@pytest.mark.slow  # the arm's kernels: about 100 s more compilation on a cold cache
def test_an_arm_batch_holds_its_home_pose_as_cpu_mujoco_does() -> None:
    arm = make_batch(small_task(), 2, device="cpu", robot="arm")
    arm.reset(seed=[3, 5])
    home = arm.home_command()
    assert home.shape == (2, arm.model.nu)
    arm.step(home, substeps=30)
    single = FactaskEnv(small_task(), robot="arm")
    single.reset(seed=5)
    for _ in range(30):
        mujoco.mj_step(single.model, single.data)
    assert np.allclose(arm.wp_data.qpos.numpy()[1], single.data.qpos, atol=2e-5)
    assert np.allclose(arm.observe()["ee_pose"][1], single._obs()["ee_pose"], atol=1e-5)
    single.close()
    arm.close()


def test_a_pick_and_place_in_lockstep_does_what_the_single_env_does(batch: BatchEnv) -> None:
    batch.reset(seed=SEEDS)
    mover = batch.graph.factors[0].goal.objects[0]
    k = batch.object_names.index(mover)
    actions = _place_actions(batch)
    pick, place = actions["pick"], actions["place"]
    pick[1, 2] = 0.2  # world 1 reaches into the air above its block
    result = batch.pick_and_place(pick, place)
    assert result.ok.tolist() == [True, False, True]
    assert result.reasons[1].startswith("nothing to grasp") and result.sim_steps > 0
    status = batch.status()
    assert status.success.tolist() == [True, False, True]
    assert batch.held_objects() == [None, None, None]
    single = FactaskEnv(small_task())
    single.reset(seed=SEEDS[0])
    _, _, _, _, info = single.step({"pick": pick[0], "place": place[0]})
    assert info["action_ok"] and info["success"]
    # Where the single env put the block, the batch put it too (not the same motion:
    # within a few millimetres).
    here = batch.object_poses()[0, k, :3]
    assert np.allclose(here, single.object_poses()[mover].pos, atol=0.005)
    single.close()
    with pytest.raises(InvalidValueError):
        batch.pick_and_place(pick[:2], place)


def test_the_oracle_in_lockstep_succeeds_where_the_cpu_oracle_does(batch: BatchEnv) -> None:
    batch.reset(seed=SEEDS)
    result = run_oracle(batch)
    for w, seed in enumerate(SEEDS):
        cpu = run_episode(small_task(), seed=seed)
        assert bool(result.success[w]) == cpu.success, (seed, result.failure[w], cpu.failure)
        assert result.actions[w] == cpu.steps
    assert result.success.all() and result.failure == [None] * len(SEEDS)
    # Every action planned once, as array work over the worlds (nothing in this task
    # needs the scalar oracle's fallback), one timing per lockstep action.
    assert result.planned_arrays + result.planned_fallback == result.actions.sum()
    assert result.planned_fallback == 0
    assert len(result.planning_seconds) == result.actions.max()


def _place_actions(batch: BatchEnv) -> dict[str, np.ndarray]:
    """Each world's block of the task's first factor, from where it is to its target."""
    factor = batch.graph.factors[0]
    mover = factor.goal.objects[0]
    k = batch.object_names.index(mover)
    half = float(batch.objects[mover].half[2])
    pos = batch.object_poses()[:, k, :3]
    target = np.array([batch.solved[w][factor.name].targets(batch.objects)[mover].pos
                       for w in range(batch.num_envs)])
    zeros = np.zeros(batch.num_envs)
    return {"pick": np.c_[pos[:, :2], pos[:, 2] + half, zeros],
            "place": np.c_[target[:, :2], target[:, 2] + half, zeros]}


def test_the_vector_env_steps_rewards_terminates_and_autoresets() -> None:
    env = BatchVectorEnv(small_task(), 2, device="cpu")
    obs, info = env.reset(seed=4)
    assert env.observation_space.contains(obs) and info["seeds"].tolist() == [4, 5]
    single = FactaskEnv(small_task())
    assert env.single_action_space == single.action_space
    actions = _place_actions(env.batch)
    actions["pick"][1, 2] = 0.2  # world 1 grasps nothing
    obs, reward, terminated, truncated, info = env.step(actions)
    assert np.allclose(reward, [1.0, 0.0]) and terminated.tolist() == [True, False]
    assert not truncated.any() and info["action_ok"].tolist() == [True, False]
    # World 0 starts again (reward 0, no flags) while world 1 acts.
    before = env.batch.seeds.copy()
    obs, reward, terminated, truncated, info = env.step(_place_actions(env.batch))
    assert env.batch.seeds[0] != before[0] and env.batch.seeds[1] == before[1]
    assert reward[0] == 0.0 and not terminated[0] and not truncated[0]
    assert terminated[1] and math.isclose(float(reward[1]), 1.0)
    assert env.observation_space.contains(obs)
    with pytest.raises(InvalidValueError):
        env.step({"pick": actions["pick"]})
    env.close()
    single.close()


def test_make_vec_with_an_id_gives_the_batch_with_the_ids_spaces() -> None:
    """gymnasium.make_vec takes the ids' vector entry point by default; its spaces are
    the id's env's (state mode) batched; sync mode still gives single envs."""
    gid = "factask/put-block-in-bowl-v0"
    env = gym.make_vec(gid, num_envs=2, device="cpu")
    single = gym.make(gid)
    try:
        assert isinstance(env.unwrapped, BatchVectorEnv) and env.num_envs == 2
        assert env.single_observation_space == single.observation_space
        assert env.single_action_space == single.action_space
        obs, _ = env.reset(seed=4)
        assert env.observation_space.contains(obs)
        one, _ = single.reset(seed=4)
        assert decode_text(obs["instruction"][0]) == decode_text(one["instruction"])
        assert decode_text(obs["goal"][1]) == decode_text(single.reset(seed=5)[0]["goal"]) != ""
        obs, _, terminated, _, _ = env.step(_place_actions(env.unwrapped.batch))
        assert terminated.all() and np.allclose(obs["factor_progress"], 1.0)
        assert [decode_text(g) for g in obs["goal"]] == ["", ""]
    finally:
        env.close()
        single.close()
    with pytest.raises(InvalidValueError, match="vectorization_mode"):
        gym.make_vec(gid, num_envs=2, device="cpu", obs_mode="rgbd")
    sync = gym.make_vec(gid, num_envs=2, vectorization_mode="sync")
    assert sync.single_observation_space == single.observation_space
    sync.close()


def test_a_task_with_drawers_is_refused_by_the_batch_with_a_typed_error() -> None:
    with pytest.raises(InvalidValueError,
                       match=r"drawers, doors and switches .* not in the batched env"):
        make_batch("open-drawer", 1, device="cpu")


def test_a_contact_overflow_is_a_physics_failure_and_bowls_fit_the_default() -> None:
    # A scene of bowls (a floor and sixteen wall geoms each, all resting on the table):
    # the default capacity holds its contacts; a small one overflows and says so.
    task = "color-coordinated-block-bowl-sorting"
    roomy = make_batch(task, 1, device="cpu")
    roomy.reset(seed=0)
    roomy.step(roomy.home_command(), 3)
    assert roomy.physics_failures() == [None]
    tight = make_batch(task, 1, device="cpu", nconmax=32, njmax=192)
    tight.reset(seed=0)
    tight.step(tight.home_command(), 3)
    failure = tight.physics_failures()[0]
    assert failure is not None and "contacts" in failure
    tight.reset(seed=0)  # a reset of every world starts the count again
    assert tight.physics_failures() == [None]


def test_a_shelf_is_fixed_geometry_the_batch_runs_its_tasks_as_the_single_env() -> None:
    # A shelf and its levels are fixed bodies (no joint): the batch takes them, and
    # the lockstep oracle puts the blocks on both levels where the CPU oracle does.
    task = "put-blocks-on-two-shelf-levels"
    seeds = [0, 3]
    env = make_batch(task, len(seeds), device="cpu")
    try:
        env.reset(seed=seeds)
        result = run_oracle(env)
        for w, seed in enumerate(seeds):
            cpu = run_episode(get_task(task), seed=seed)
            assert bool(result.success[w]) == cpu.success, (seed, result.failure[w])
        assert result.success.all(), result.failure
    finally:
        env.close()
