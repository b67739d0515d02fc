"""gymnasium ids, factask.make and the observation modes (state, rgbd, heightmap)."""

from __future__ import annotations

import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import factask
import factask.sim
from factask.library import task_names
from factask.registration import TaskSpecError, env_id
from factask.sim.render.cameras import CameraError, CameraRig, points_from_depth, ravens_cameras
from factask.sim.render.heightmaps import PIXEL_SIZE, HeightmapGrid
from factask.sim.render.observations import MAX_TEXT_BYTES, decode_text, encode_text
from factask.vocabulary.errors import InvalidValueError

TASK = "place-red-in-green"
TINY = (32, 24)


def test_every_library_task_has_an_id() -> None:
    ids = set(gym.envs.registry)
    missing = [t for t in task_names() if env_id(t) not in ids]
    assert not missing
    assert env_id("stack-block-pyramid") == "factask/stack-block-pyramid-v0"


@pytest.mark.parametrize("mode", ["state", "rgbd", "heightmap"])
def test_check_env_passes_for_every_obs_mode(mode: str) -> None:
    env = factask.make(TASK, obs_mode=mode, image_size=TINY)
    try:
        with warnings.catch_warnings():
            # check_env prefers the raw env; the obs modes are a wrapper by design.
            warnings.simplefilter("ignore", UserWarning)
            check_env(env)
    finally:
        env.close()


def test_gym_make_with_an_id_observes_language_and_progress() -> None:
    env = gym.make(env_id(TASK), robot="floating", obs_mode="rgbd", image_size=TINY)
    try:
        obs, info = env.reset(seed=3)
        graph = env.unwrapped.graph
        assert decode_text(obs["instruction"]) == graph.description == info["instruction"]
        first = graph.factor_order()[0]
        goals = {f.name: f.description for f in graph.factors}
        assert decode_text(obs["goal"]) == goals[first] == info["goal"]
        assert obs["factor_progress"].shape == (len(graph.factors),)
        assert set(obs["images"]) == {"front", "left", "right"}
        front = obs["images"]["front"]
        assert front["rgb"].shape == (TINY[1], TINY[0], 3)
        assert front["depth"].dtype == np.float32
        labels = env.get_wrapper_attr("segmentation_labels")
        seen = set(np.unique(front["segmentation"])) - {0}
        assert seen and seen <= set(labels)
        variables = {v.name for v in graph.variables}
        assert {labels[i]["variable"] for i in seen} <= variables
    finally:
        env.close()


def test_text_is_cut_at_a_character_and_round_trips() -> None:
    assert decode_text(encode_text("put the block é")) == "put the block é"
    long = "é" * MAX_TEXT_BYTES
    assert len(decode_text(encode_text(long)).encode()) <= MAX_TEXT_BYTES


def test_ravens_cameras_back_project_the_table_to_z_zero() -> None:
    """Intrinsics and poses agree with the renderer: table pixels land on z = 0 and an
    object's pixels around its true position."""
    env = factask.make(TASK)
    try:
        env.reset(seed=0)
        base = env.unwrapped
        poses = base.object_poses()
        with CameraRig(base.model, ravens_cameras(80, 60), base.scene.geom_object) as rig:
            for cam in rig.cameras:
                depth = rig.depth(base.data, cam.name)
                seg = rig.segmentation(base.data, cam.name)
                pts = points_from_depth(depth, cam)
                table = (seg == 0) & (np.abs(pts[..., 1]) < 0.4) & \
                    (np.abs(pts[..., 0] - 0.5) < 0.2)
                assert np.abs(np.median(pts[..., 2][table])) < 1e-3, cam.name
                k = int(np.bincount(seg[seg > 0]).argmax())
                name = base.object_names[k - 1]
                centre = pts[seg == k].mean(axis=0)
                assert np.linalg.norm(centre[:2] - poses[name].pos[:2]) < 0.04, cam.name
    finally:
        env.close()


def test_heightmap_grid_is_cliports() -> None:
    grid = HeightmapGrid()
    assert grid.pixel_size == PIXEL_SIZE == 0.003125
    assert grid.shape == (320, 160)
    env = factask.make(TASK, obs_mode="heightmap", image_size=(160, 120))
    try:
        obs, _ = env.reset(seed=0)
        height = obs["heightmap"]["height"]
        assert height.shape == (320, 160) and 0.0 < height.max() < 0.3
        # Some object is seen where it stands.
        base = env.unwrapped
        sizes = {n: o.size for n, o in base.objects.items()}
        hits = 0
        for name, pose in base.object_poses().items():
            col = int((pose.pos[0] - grid.x[0]) / PIXEL_SIZE)
            row = int((pose.pos[1] - grid.y[0]) / PIXEL_SIZE)
            patch = height[max(row - 3, 0):row + 4, max(col - 3, 0):col + 4]
            hits += bool(patch.size and abs(patch.max() - sizes[name][2]) < 0.02)
        assert hits >= 1
    finally:
        env.close()


def test_bad_options_name_the_field() -> None:
    with pytest.raises(InvalidValueError, match="obs_mode"):
        factask.make(TASK, obs_mode="pixels")
    with pytest.raises(CameraError, match="size"):
        factask.make(TASK, obs_mode="rgbd", image_size=(0, 10))
    with pytest.raises(TaskSpecError, match="cannot read"):
        factask.make("missing-file.json")


def test_make_takes_a_graph_and_a_file(tmp_path) -> None:
    graph = factask.get_task(TASK)
    path = tmp_path / "task.json"
    path.write_text(graph.to_json())
    for spec in (graph, str(path), env_id(TASK)):
        env = factask.make(spec)
        assert env.unwrapped.graph.name == graph.name
        env.close()


def _make_state_env() -> gym.Env:
    return gym.make(env_id(TASK), obs_mode="state")


def test_async_vector_env_with_an_id() -> None:
    envs = gym.vector.AsyncVectorEnv([_make_state_env, _make_state_env])
    try:
        obs, info = envs.reset(seed=[1, 2])
        assert obs["object_poses"].shape[0] == 2
        assert decode_text(obs["goal"][0]) == info["goal"][0] != ""
        assert not np.array_equal(obs["object_poses"][0], obs["object_poses"][1])
        action = envs.action_space.sample()
        obs, reward, _, _, _ = envs.step(action)
        assert reward.shape == (2,) and obs["factor_progress"].shape[0] == 2
    finally:
        envs.close()
