"""A LeRobot v3.0 reader written only against the format: pyarrow, PyAV, numpy, json.

It imports nothing of factask (tests/test_lerobot_dataset.py checks that), so a
dataset it accepts is one any v3.0 loader can read.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import av
import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

DEFAULT_KEYS = ("timestamp", "frame_index", "episode_index", "index", "task_index")


class FormatError(AssertionError):
    """The folder is not a valid LeRobot v3.0 dataset."""


def _check(cond: bool, message: str) -> None:
    if not cond:
        raise FormatError(message)


def _column(table: Any, key: str, shape: list[int]) -> np.ndarray:
    col = table.column(key).combine_chunks()
    if shape == [1]:
        return col.to_numpy(zero_copy_only=False)
    _check(col.type.list_size == shape[0], f"{key}: list size {col.type.list_size} != {shape}")
    return col.flatten().to_numpy(zero_copy_only=False).reshape(len(col), *shape)


def decode_video(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """All frames (n, h, w, 3) uint8 of an MP4 and their presentation times (s)."""
    frames, times = [], []
    with av.open(str(path)) as container:
        stream = container.streams.video[0]
        for frame in container.decode(stream):
            frames.append(frame.to_ndarray(format="rgb24"))
            times.append(float(frame.pts * stream.time_base))
    return np.stack(frames), np.asarray(times)


def load_dataset(root: Path) -> dict[str, Any]:
    """Read and check a LeRobot v3.0 dataset.

    Returns:
        {"info", "tasks" (index -> text), "frames" (key -> array), "episodes" (list of
        dicts), "videos" (key -> (frames, times))}.

    Raises:
        FormatError: anything that breaks the format.
    """
    info = json.loads((root / "meta" / "info.json").read_text())
    _check(info["codebase_version"] == "v3.0", "codebase_version must be v3.0")
    fps, feats = info["fps"], info["features"]
    _check(isinstance(fps, int) and fps > 0, "fps must be a positive int")
    for key in DEFAULT_KEYS:
        _check(key in feats, f"feature {key} missing")
    for key, f in feats.items():
        _check({"dtype", "shape", "names"} <= set(f), f"feature {key} lacks dtype/shape/names")
    stats = json.loads((root / "meta" / "stats.json").read_text())
    tasks_table = pq.read_table(root / "meta" / "tasks.parquet")
    tasks = dict(zip(tasks_table.column("task_index").to_pylist(),
                     tasks_table.column("task").to_pylist(), strict=True))
    # Data files in (chunk, file) order hold the frames in global index order.
    data_files = sorted((root / "data").glob("chunk-*/file-*.parquet"))
    _check(bool(data_files), "no data files")
    per_file = {(int(f.parent.name[6:]), int(f.stem[5:])): pq.read_table(f) for f in data_files}
    table = pa.concat_tables([per_file[k] for k in sorted(per_file)])
    plain = {k: f for k, f in feats.items() if f["dtype"] != "video"}
    _check(set(plain) == set(table.column_names),
           f"data columns {sorted(table.column_names)} != features {sorted(plain)}")
    frames = {k: _column(table, k, f["shape"]) for k, f in plain.items()}
    for k, f in plain.items():
        if f["dtype"] in ("float32", "int64", "bool", "float64"):
            _check(k in stats, f"stats.json lacks {k}")
    n = len(table)
    _check(n == info["total_frames"], f"{n} frames, info says {info['total_frames']}")
    _check(np.array_equal(frames["index"], np.arange(n)), "index must be 0 .. N-1")
    eps_table = pq.read_table(root / "meta" / "episodes" / "chunk-000" / "file-000.parquet")
    episodes = eps_table.to_pylist()
    _check(len(episodes) == info["total_episodes"], "total_episodes disagrees")
    video_keys = [k for k, f in feats.items() if f["dtype"] == "video"]
    videos: dict[tuple[str, int, int], tuple[np.ndarray, np.ndarray]] = {}
    for key in video_keys:
        for path in sorted((root / "videos" / key).glob("chunk-*/file-*.mp4")):
            videos[(key, int(path.parent.name[6:]), int(path.stem[5:]))] = decode_video(path)
    for e in episodes:
        i, length = e["episode_index"], e["length"]
        lo, hi = e["dataset_from_index"], e["dataset_to_index"]
        _check(hi - lo == length, f"episode {i}: range {lo}:{hi} vs length {length}")
        _check(np.all(frames["episode_index"][lo:hi] == i), f"episode {i}: episode_index")
        _check(np.array_equal(frames["frame_index"][lo:hi], np.arange(length)),
               f"episode {i}: frame_index must be 0 .. length-1")
        _check(np.allclose(frames["timestamp"][lo:hi], np.arange(length) / fps),
               f"episode {i}: timestamps must be frame_index / fps")
        _check(tasks[int(frames["task_index"][lo])] in e["tasks"], f"episode {i}: task")
        own = per_file[(e["data/chunk_index"], e["data/file_index"])]
        _check(i in set(own.column("episode_index").to_pylist()),
               f"episode {i}: not in its data file")
        for key in video_keys:
            vframes = episode_video({"episodes": episodes, "videos": videos}, key, i)
            _check(len(vframes) == length, f"episode {i}: {key} has {len(vframes)} frames")
            _check(vframes.shape[1:] == tuple(feats[key]["shape"]), f"{key}: frame shape")
    for key in video_keys:
        total = sum(len(v[0]) for (k, _, _), v in videos.items() if k == key)
        _check(total == n, f"{key}: {total} video frames for {n} frames")
    return {"info": info, "tasks": tasks, "frames": frames, "episodes": episodes,
            "videos": videos}


def episode_video(ds: dict[str, Any], key: str, episode: int) -> np.ndarray:
    """The decoded frames of one episode of one video key (from its own file)."""
    e = ds["episodes"][episode]
    vframes, vtimes = ds["videos"][(key, e[f"videos/{key}/chunk_index"],
                                    e[f"videos/{key}/file_index"])]
    t0, t1 = e[f"videos/{key}/from_timestamp"], e[f"videos/{key}/to_timestamp"]
    return vframes[(vtimes >= t0 - 1e-6) & (vtimes < t1 - 1e-6)]
