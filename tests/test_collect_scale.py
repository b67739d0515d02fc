"""Collection at scale: a process pool gives the same dataset as one process, a killed
run resumes without loss or repetition, and Ray (optional) gives the same dataset."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
import pytest
from lerobot_v3_reader import decode_video, load_dataset

import factask.sim  # noqa: F401  (headless GL backend before MuJoCo's GL loads)
from factask.datasets.shards import SHARD_DIR, CollectConfig, CollectError, collect

SIZE = (32, 24)
CONFIG = CollectConfig(tasks=("align-box-corner", "place-red-in-green"), episodes=2,
                       image_size=SIZE, shard_size=1)


def content(root: Path) -> dict[str, object]:
    """Everything a dataset holds, comparable with ==."""
    data = pq.read_table(root / "data" / "chunk-000" / "file-000.parquet").to_pylist()
    episodes = pq.read_table(root / "meta" / "episodes" / "chunk-000" / "file-000.parquet")
    states = {}
    for path in sorted((root / "states").glob("*.npz")):
        with np.load(path) as z:
            states[path.name] = {k: z[k].tobytes() for k in z.files}
    videos = {}
    for path in sorted((root / "videos").rglob("*.mp4")):
        videos[path.parent.parent.name] = decode_video(path)[0].tobytes()
    return {"data": data, "episodes": episodes.to_pylist(), "states": states,
            "videos": videos}


@pytest.fixture(scope="module")
def serial(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("serial") / "ds"
    summary = collect(CONFIG, root, workers=1)
    assert summary.shards_total == 4 and summary.episodes_run == 4
    return root


def test_two_workers_write_the_same_dataset_as_one(serial: Path, tmp_path: Path) -> None:
    root = tmp_path / "pool"
    summary = collect(CONFIG, root, workers=2)
    assert summary.shards_run == 4
    assert content(root) == content(serial)
    load_dataset(root)
    assert not (root / SHARD_DIR).exists()


def test_other_options_cannot_resume_a_run(tmp_path: Path) -> None:
    root = tmp_path / "ds"
    (root / SHARD_DIR).mkdir(parents=True)
    (root / SHARD_DIR / "plan.json").write_text("{}")
    with pytest.raises(CollectError, match="other options"):
        collect(CONFIG, root, workers=1)


def test_a_killed_collect_resumes_without_loss_or_repetition(serial: Path,
                                                              tmp_path: Path) -> None:
    root = tmp_path / "killed"
    args = [sys.executable, "-m", "factask", "collect", *CONFIG.tasks, "-n", "2",
            "--size", f"{SIZE[0]}x{SIZE[1]}", "--shard-size", "1", "--workers", "1",
            "--out", str(root), "--json"]
    env = dict(os.environ, MUJOCO_GL=os.environ.get("MUJOCO_GL", "egl"))
    proc = subprocess.Popen(args, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    shard_dir = root / SHARD_DIR
    while time.monotonic() < deadline and not list(shard_dir.glob("*.pkl")):
        time.sleep(0.02)
    proc.send_signal(signal.SIGKILL)  # our own child, by its id
    proc.wait()
    written = len(list(shard_dir.glob("*.pkl")))
    assert 1 <= written < 4, f"the kill came too late or too early ({written} shards)"
    assert not (root / "meta" / "info.json").exists()
    summary = collect(CONFIG, root, workers=1)
    assert summary.shards_resumed == written and summary.shards_run == 4 - written
    assert summary.kept_seeds == [0, 2, 0, 2]  # every seed once, in order
    assert content(root) == content(serial)


@pytest.mark.slow
def test_ray_gives_the_same_dataset(serial: Path, tmp_path: Path) -> None:
    ray = pytest.importorskip("ray", reason="Ray is optional: pip install 'factask[ray]'")
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        root = tmp_path / "ray"
        summary = collect(CONFIG, root, ray_address="auto")
        assert summary.shards_run == 4
        assert content(root) == content(serial)
    finally:
        ray.shutdown()
