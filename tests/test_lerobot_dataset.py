"""factask collect writes a LeRobot v3.0 dataset that a format-only reader accepts, and
factask replay reproduces its states bit for bit."""

from __future__ import annotations

import ast
import json
from pathlib import Path

import numpy as np
import pytest
from lerobot_v3_reader import decode_video, episode_video, load_dataset
from typer.testing import CliRunner

import factask.sim  # noqa: F401  (headless GL backend before MuJoCo's GL loads)
from factask.cli import app
from factask.datasets.actions import ACTION_NAMES, ACTION_WIDTH
from factask.datasets.control_frames import (
    FLOATING_COMMAND_NAMES,
    ControlStream,
    DecisionRows,
    control_columns,
    default_control_fps,
)
from factask.datasets.replay import compare_states, render_states, resimulate
from factask.datasets.shards import CollectConfig, CollectError, collect
from factask.datasets.splits import MAX_VAL_EPISODES, TEST_START, split_of_seed, split_seeds
from factask.datasets.states import StatesFileError, read_states
from factask.sim.render.cameras import ravens_cameras
from factask.vocabulary.errors import InvalidValueError

SIZE = (64, 48)
TASKS = ("place-red-in-green", "align-box-corner")


@pytest.fixture(scope="module")
def dataset(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("ds") / "demo"
    config = CollectConfig(tasks=TASKS, episodes=2, image_size=SIZE, shard_size=1)
    summary = collect(config, root, workers=1)
    assert summary.episodes_kept >= 3
    return root


def test_the_reader_imports_nothing_of_factask() -> None:
    tree = ast.parse((Path(__file__).parent / "lerobot_v3_reader.py").read_text())
    names = [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    names += [n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    assert not [m for m in names if m.startswith("factask")]


def test_a_format_only_reader_loads_the_dataset(dataset: Path) -> None:
    ds = load_dataset(dataset)
    info = ds["info"]
    assert info["codebase_version"] == "v3.0" and info["fps"] == 1
    feats = info["features"]
    for key in ("observation.state", "observation.environment_state", "action",
                "next.reward", "next.total_reward", "next.factor_rewards", "next.done",
                "language_goal", "observation.images.front", "observation.images.left",
                "observation.images.right"):
        assert key in feats, key
    assert feats["action"]["shape"] == [ACTION_WIDTH] and feats["action"]["names"] == ACTION_NAMES
    assert set(ds["tasks"]) == {0, 1}
    frames = ds["frames"]
    # Only successful demonstrations: each episode ends done with total reward >= 0.99.
    for e in ds["episodes"]:
        last = e["dataset_to_index"] - 1
        assert frames["next.done"][last] and frames["next.total_reward"][last] >= 0.99
        assert e["factask/success"]
    assert len(frames["language_goal"]) == info["total_frames"]


def test_decoded_frames_match_re_rendered_states(dataset: Path) -> None:
    ds = load_dataset(dataset)
    cams = ravens_cameras(*SIZE)
    for k, e in enumerate(ds["episodes"]):
        states = read_states(dataset / e["factask/states_path"])
        rendered = render_states(states, cams)
        for cam in cams:
            decoded = episode_video(ds, f"observation.images.{cam.name}", k)
            assert decoded.shape == rendered[cam.name].shape
            diff = np.abs(decoded.astype(float) - rendered[cam.name].astype(float))
            mse = float(np.mean(diff ** 2))
            psnr = 10 * np.log10(255.0 ** 2 / max(mse, 1e-9))
            assert psnr > 30.0, (k, cam.name, psnr)


def test_replay_is_bit_identical(dataset: Path) -> None:
    states = read_states(dataset / "states" / "episode_000000.npz")
    assert compare_states(states, resimulate(states)) == []
    # The low-level stream covers every action, in simulated time order.
    assert set(states.control_step.tolist()) == set(range(states.steps))
    assert np.all(np.diff(states.control_time) > 0) and states.control_tip.shape[1] == 8
    result = CliRunner().invoke(app, ["replay", str(dataset), "--episode", "1", "--json"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.output)["identical"] is True


def test_seed_splits_are_disjoint_and_documented() -> None:
    train, val, test = (set(split_seeds(s, 200)) for s in ("train", "val", "test"))
    assert not (train & val) and not (train & test) and not (val & test)
    assert min(test) == TEST_START and all(split_of_seed(s) == "test" for s in test)
    assert max(split_seeds("val", MAX_VAL_EPISODES)) < TEST_START
    with pytest.raises(InvalidValueError, match="val"):
        split_seeds("val", MAX_VAL_EPISODES + 1)


def test_files_roll_over_by_size_and_the_reader_follows(tmp_path: Path) -> None:
    """Tiny size targets: every episode starts new data and video files."""
    config = CollectConfig(tasks=TASKS, episodes=2, image_size=SIZE, shard_size=2,
                           data_mb=1e-4, video_mb=1e-5)
    root = tmp_path / "rolled"
    summary = collect(config, root, workers=1)
    ds = load_dataset(root)
    files = {(e["data/chunk_index"], e["data/file_index"]) for e in ds["episodes"]}
    videos = {e["videos/observation.images.front/file_index"] for e in ds["episodes"]}
    assert len(files) == len(videos) == summary.episodes_kept >= 3
    cams = ravens_cameras(*SIZE)
    last = len(ds["episodes"]) - 1
    states = read_states(root / ds["episodes"][last]["factask/states_path"])
    decoded = episode_video(ds, "observation.images.front", last)
    rendered = render_states(states, cams[:1])["front"]
    assert np.mean(np.abs(decoded.astype(float) - rendered.astype(float))) < 3.0


def test_collect_refuses_a_finished_dataset(dataset: Path) -> None:
    config = CollectConfig(tasks=TASKS, episodes=2, image_size=SIZE, shard_size=1)
    with pytest.raises(CollectError, match="already holds a dataset"):
        collect(config, dataset, workers=1)


@pytest.fixture(scope="module")
def control_dataset(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("ctl") / "demo"
    config = CollectConfig(tasks=("align-box-corner",), episodes=1, image_size=SIZE,
                           fps=default_control_fps(), frames="control")
    assert collect(config, root, workers=1).episodes_kept == 1
    return root


def test_control_frames_carry_the_low_level_command(control_dataset: Path) -> None:
    """One frame per command sample at the command rate: the format-only reader checks
    timestamps, frame and episode indices; the frames agree with the states file."""
    ds = load_dataset(control_dataset)
    info, frames = ds["info"], ds["frames"]
    assert info["fps"] == default_control_fps() == 50
    feats = info["features"]
    assert feats["action"]["names"] == FLOATING_COMMAND_NAMES
    assert feats["action.primitive"]["names"] == ACTION_NAMES and "decision_index" in feats
    states = read_states(control_dataset / ds["episodes"][0]["factask/states_path"])
    n = len(states.control_step)
    assert info["total_frames"] == n > 10 * states.steps
    assert np.array_equal(frames["decision_index"], states.control_step)
    assert np.allclose(frames["action.primitive"], states.actions[states.control_step])
    # The floating cup reaches its command: each frame's command is the next frame's tip.
    assert np.allclose(frames["action"][:-1], frames["observation.state"][1:], atol=1e-6)
    assert np.allclose(frames["observation.state"], states.control_tip, atol=1e-6)
    # Rewards land on each decision's last sample and add up to the episode's total.
    assert frames["next.done"][-1] and not frames["next.done"][:-1].any()
    assert frames["next.total_reward"][-1] >= 0.99
    assert frames["next.reward"].sum() == pytest.approx(
        frames["next.total_reward"][-1] - (frames["next.total_reward"][0]
                                           - frames["next.reward"][0]), abs=1e-5)
    last = np.append(frames["decision_index"][1:] != frames["decision_index"][:-1], True)
    assert not frames["next.reward"][~last].any()


def test_control_frames_video_matches_the_states_and_replays(control_dataset: Path) -> None:
    ds = load_dataset(control_dataset)
    states = read_states(control_dataset / ds["episodes"][0]["factask/states_path"])
    front = ravens_cameras(*SIZE)[:1]
    rendered = render_states(states, front, control=True)["front"]
    decoded = episode_video(ds, "observation.images.front", 0)
    assert decoded.shape == rendered.shape
    mse = float(np.mean((decoded.astype(float) - rendered.astype(float)) ** 2))
    assert 10 * np.log10(255.0 ** 2 / max(mse, 1e-9)) > 30.0
    # Rendering at every sample while recording left the physics as it was.
    assert compare_states(states, resimulate(states)) == []
    # factask replay re-renders every command sample, at the command rate.
    out = control_dataset.parent / "replay.mp4"
    result = CliRunner().invoke(app, ["replay", str(control_dataset), "--video", str(out),
                                      "--size", "64x48", "--json"])
    assert result.exit_code == 0 and json.loads(result.output)["identical"], result.output
    frames, times = decode_video(out)
    assert len(frames) == len(states.control_step)
    assert np.allclose(np.diff(times), 1 / default_control_fps())


def test_control_frames_refuse_another_rate(tmp_path: Path, dataset: Path) -> None:
    config = CollectConfig(tasks=("align-box-corner",), episodes=1, image_size=None, fps=10,
                           frames="control")
    with pytest.raises(CollectError, match="50 per second"):
        collect(config, tmp_path / "x", workers=1)
    with pytest.raises(StatesFileError, match="--frames control"):
        render_states(read_states(dataset / "states" / "episode_000000.npz"),
                      ravens_cameras(*SIZE)[:1], control=True)


def test_an_episode_without_samples_has_no_control_frames() -> None:
    """A reset that failed: no decision, no sample; an arm's command is still 7 wide."""
    cols = control_columns(ControlStream(), DecisionRows(), [], nu=6, env_width=14,
                           n_factors=2)
    assert cols["action"].shape == (0, 7) and cols["environment_state"].shape == (0, 14)
    assert cols["factor_rewards"].shape == (0, 2) and cols["goal"] == []


def test_collect_cli_takes_control_frames(tmp_path: Path) -> None:
    out = tmp_path / "ctl"
    args = ["collect", "align-box-corner", "-n", "1", "--no-video", "--workers", "1",
            "--frames", "control", "-o", str(out), "--json"]
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 0, result.output
    info = json.loads((out / "meta" / "info.json").read_text())
    assert info["fps"] == default_control_fps() and "action.primitive" in info["features"]
    assert info["factask"]["collect"]["frames"] == "control"
    bad = CliRunner().invoke(app, [*args[:-3], "-o", str(tmp_path / "bad"), "--fps", "10"])
    assert bad.exit_code != 0 and "50 per second" in bad.output
    bad = CliRunner().invoke(app, ["collect", "align-box-corner", "--frames", "steps", "-o",
                                   str(tmp_path / "bad2")])
    assert bad.exit_code != 0 and "decision, control" in bad.output
