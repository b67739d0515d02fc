"""Every action primitive records, writes a LeRobot dataset, reads back and replays
bit for bit (:mod:`factask.datasets.actions`)."""

from __future__ import annotations

import json
from dataclasses import asdict
from pathlib import Path

import numpy as np
import pytest
from lerobot_v3_reader import load_dataset
from typer.testing import CliRunner

import factask
from factask.cli import app
from factask.datasets.actions import (
    ACTION_ENCODING,
    ACTION_NAMES,
    ACTION_WIDTH,
    KINDS_BY_CODE,
    ActionEncodingError,
    decode_action,
    encode_action,
    primitive_name,
)
from factask.datasets.recording import record_episode
from factask.datasets.replay import compare_states, resimulate
from factask.datasets.shards import SHARD_DIR, CollectConfig, CollectError, collect
from factask.datasets.states import StatesFileError, read_states, write_states
from factask.sim.env import ACTION_KINDS, ActionError, FactaskEnv, action_kind

#: One library task per primitive other than the plain pick-and-place.
TASKS = {"push": "sweep-and-sort-blocks", "low_carry": "align-rope", "slide": "open-drawer",
         "swing": "open-microwave", "press": "turn-on-stove"}


@pytest.fixture(scope="module")
def dataset(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """One oracle episode (seed 0) of each task, floating robot, no video."""
    root = tmp_path_factory.mktemp("prim") / "demo"
    config = CollectConfig(tasks=tuple(TASKS.values()), episodes=1, image_size=None,
                           shard_size=1)
    summary = collect(config, root, workers=1)
    assert summary.episodes_kept == len(TASKS)  # every oracle episode succeeded
    return root


def _example(kind_name: str) -> dict[str, np.ndarray]:
    kind = next(k for k in ACTION_KINDS if k.name == kind_name)
    out = {key: np.array([0.5 + i / 10, -0.1, 0.02 * (i + 1), 0.3]) for i, key in
           enumerate(kind.poses)}
    for key, width in kind.extras:
        out[key] = np.arange(1, width + 1) / 50.0
    return out


@pytest.mark.parametrize("name", [k.name for k in ACTION_KINDS])
def test_encoding_round_trips_every_primitive(name: str) -> None:
    action = _example(name)
    vec = encode_action(action)
    assert vec.shape == (ACTION_WIDTH,) and vec.dtype == np.float64
    back = decode_action(vec)
    assert set(back) == set(action) and action_kind(back).name == name
    for key, value in action.items():
        assert np.array_equal(back[key], value), key
    assert primitive_name(vec) == name and KINDS_BY_CODE[int(vec[-1])].name == name


def test_the_columns_are_the_pick_and_place_then_the_extras() -> None:
    assert ACTION_NAMES[:8] == ["pick_x", "pick_y", "pick_z", "pick_yaw",
                                "place_x", "place_y", "place_z", "place_yaw"]
    assert ACTION_NAMES[8:] == ["lift", "hinge_x", "hinge_y", "primitive"]
    assert len({k.code for k in ACTION_KINDS}) == len(ACTION_KINDS)
    # A pick-and-place of encoding 1 (8 numbers) still decodes.
    old = np.arange(8, dtype=float)
    assert action_kind(decode_action(old)).name == "pick_place"


def test_unknown_action_shapes_are_typed_errors_naming_the_keys() -> None:
    with pytest.raises(ActionEncodingError, match=r"\['grab', 'put'\]") as exc:
        encode_action({"grab": [0, 0, 0, 0], "put": [0, 0, 0, 0]})
    assert "'swing_to'" in str(exc.value) and "'press_to'" in str(exc.value)
    with pytest.raises(ActionError, match="'pick', 'place'"):
        action_kind([1, 2, 3])
    with pytest.raises(ActionEncodingError, match="4 numbers"):
        encode_action({"pick": [0, 0, 0], "place": [0, 0, 0, 0]})
    with pytest.raises(ActionEncodingError, match="unknown primitive code"):
        decode_action(np.r_[np.zeros(ACTION_WIDTH - 1), 9.0])
    with pytest.raises(ActionEncodingError, match="12 numbers"):
        decode_action(np.zeros(5))


def test_recording_an_unknown_action_is_a_typed_error() -> None:
    env = FactaskEnv(factask.get_task("turn-on-stove"))
    try:
        with pytest.raises(ActionEncodingError, match="'grab'"):
            record_episode(env, 0, policy=lambda e, s: lambda: {"grab": [0.5, 0, 0, 0]})
    finally:
        env.close()


def test_every_primitive_reads_back_from_the_dataset(dataset: Path) -> None:
    ds = load_dataset(dataset)
    feats, frames = ds["info"]["features"], ds["frames"]
    assert feats["action"]["names"] == ACTION_NAMES
    assert feats["action"]["shape"] == [ACTION_WIDTH]
    assert ds["info"]["factask"]["action_encoding"] == ACTION_ENCODING
    seen = []
    for e in ds["episodes"]:
        lo, hi = e["dataset_from_index"], e["dataset_to_index"]
        assert e["factask/success"] and frames["next.success"][hi - 1]
        states = read_states(dataset / e["factask/states_path"])
        assert states.actions.shape == (hi - lo, ACTION_WIDTH)
        # The frames' actions are the states file's (float32 of the float64).
        assert np.array_equal(frames["action"][lo:hi], states.actions.astype(np.float32))
        kinds = {primitive_name(a) for a in states.actions}
        assert len(kinds) == 1
        seen.append(kinds.pop())
    assert seen == list(TASKS)
    # The extras are there: a rope's lift, a door's hinge.
    lift = ACTION_NAMES.index("lift")
    hinge = [ACTION_NAMES.index("hinge_x"), ACTION_NAMES.index("hinge_y")]
    by_kind = dict(zip(seen, ds["episodes"], strict=True))
    rope = frames["action"][by_kind["low_carry"]["dataset_from_index"]]
    door = frames["action"][by_kind["swing"]["dataset_from_index"]]
    assert 0 < rope[lift] < 0.1 and np.all(rope[hinge] == 0)
    assert np.any(door[hinge] != 0) and door[lift] == 0


@pytest.mark.parametrize("index", range(len(TASKS)), ids=list(TASKS))
def test_every_primitive_replays_bit_identically(dataset: Path, index: int) -> None:
    states = read_states(dataset / "states" / f"episode_{index:06d}.npz")
    assert compare_states(states, resimulate(states)) == []


def test_the_replay_command_takes_every_primitive(dataset: Path) -> None:
    result = CliRunner().invoke(app, ["replay", str(dataset), "--episode", "4", "--json"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.output)["identical"] is True


@pytest.mark.parametrize("kind", list(TASKS))
def test_control_frames_carry_the_decision_of_any_primitive(kind: str) -> None:
    env = FactaskEnv(factask.get_task(TASKS[kind]))
    try:
        rec = record_episode(env, 0, frames="control")
    finally:
        env.close()
    assert rec.success and rec.primitive is not None and rec.decision is not None
    assert rec.primitive.shape == (rec.length, ACTION_WIDTH)
    assert np.array_equal(rec.primitive, rec.states.actions[rec.decision].astype(np.float32))
    assert {primitive_name(a) for a in rec.primitive} == {kind}
    assert compare_states(rec.states, resimulate(rec.states)) == []


def test_a_states_file_of_layout_1_reads_as_pick_and_places(tmp_path: Path) -> None:
    env = FactaskEnv(factask.get_task("turn-on-stove"))
    try:
        rec = record_episode(env, 0)
    finally:
        env.close()
    path = tmp_path / "ep.npz"
    write_states(path, rec.states)
    with np.load(path) as z:
        old = {k: z[k] for k in z.files}
    old["version"], old["actions"] = np.int64(1), np.arange(16.0).reshape(2, 8)
    np.savez(path, **old)
    states = read_states(path)
    assert states.actions.shape == (2, ACTION_WIDTH)
    assert {primitive_name(a) for a in states.actions} == {"pick_place"}
    old["version"] = np.int64(7)
    np.savez(path, **old)
    with pytest.raises(StatesFileError, match="layout 7"):
        read_states(path)


def test_shards_of_the_older_action_layout_are_not_resumed(tmp_path: Path) -> None:
    """A run started by a factask of encoding 1 (its plan.json has no action_encoding)."""
    config = CollectConfig(tasks=("turn-on-stove",), episodes=1, image_size=None)
    shard_dir = tmp_path / "ds" / SHARD_DIR
    shard_dir.mkdir(parents=True)
    (shard_dir / "plan.json").write_text(json.dumps(asdict(config), sort_keys=True))
    with pytest.raises(CollectError, match="another factask version"):
        collect(config, tmp_path / "ds", workers=1)
