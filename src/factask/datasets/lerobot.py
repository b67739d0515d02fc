"""A LeRobot v3.0 dataset writer on pyarrow and PyAV (no ``lerobot``, no torch).

Layout (LeRobot's path templates, one chunk and one file per kind)::

    meta/info.json                       codebase_version "v3.0", fps, features, totals
    meta/stats.json                      min / max / mean / std / count per feature
    meta/tasks.parquet                   task (the language instruction) -> task_index
    meta/episodes/chunk-000/file-000.parquet   one row per episode
    data/chunk-000/file-000.parquet      one row per frame, all episodes
    videos/observation.images.<camera>/chunk-000/file-000.mp4   all episodes, in order

Per frame: ``observation.state`` (suction tip pose, suction), ``observation.environment_state``
(object poses, zero-padded to the largest task), ``action`` (pick and place, x y z yaw),
``next.reward`` (the reward change), ``next.total_reward``, ``next.factor_rewards``
(per-factor progress, zero-padded), ``next.done``, ``next.success``, ``language_goal``
(the current factor's goal), and LeRobot's ``timestamp``, ``frame_index``,
``episode_index``, ``index``, ``task_index``. Videos are H.264 (yuv420p); frame k of the
file has presentation time k / fps, so an episode spans [from_timestamp, to_timestamp).
"""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from factask.datasets.recording import ACTION_NAMES, STATE_NAMES, EpisodeRecord
from factask.model.errors import FactaskError
from factask.model.tolerances import SUCCESS_REWARD

CODEBASE_VERSION = "v3.0"
DATA_PATH = "data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet"
VIDEO_PATH = "videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4"
EPISODES_PATH = "meta/episodes/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet"
TASKS_PATH = "meta/tasks.parquet"
#: LeRobot's defaults, recorded in info.json (this writer keeps one file per kind).
CHUNKS_SIZE = 1000
DATA_FILES_SIZE_IN_MB = 100
VIDEO_FILES_SIZE_IN_MB = 200
#: Default frames per second: one frame per pick-and-place decision, shown at 1 Hz.
DEFAULT_FPS = 1
#: H.264 quality (lower is better; 0 is lossless luma, still 4:2:0 chroma).
VIDEO_CRF = 15


class DatasetWriteError(FactaskError, ValueError):
    """A dataset that cannot be written as asked (bad size, mismatched episode)."""


def image_key(camera: str) -> str:
    """The feature key of a camera's video: ``observation.images.<camera>``."""
    return f"observation.images.{camera}"


def _vec(dtype: str, n: int, names: list[str] | None = None) -> dict[str, Any]:
    return {"dtype": dtype, "shape": [n], "names": names}


class LeRobotWriter:
    """Writes episodes into a LeRobot v3.0 folder; :meth:`finalize` writes the metadata.

    Args:
        root: The dataset folder (created; must not hold a dataset yet).
        cameras: Camera name -> (height, width) of its images (even sizes: yuv420p).
        env_width: Width of ``observation.environment_state`` (7 x most objects).
        factor_width: Width of ``next.factor_rewards`` (most factors).
        fps: Frames per second of timestamps and videos.
        robot_type: Recorded in info.json.

    Raises:
        DatasetWriteError: a dataset is already there, or an odd image size.
    """

    def __init__(self, root: Path, cameras: dict[str, tuple[int, int]], env_width: int,
                 factor_width: int, fps: int = DEFAULT_FPS, robot_type: str | None = None
                 ) -> None:
        self.root = Path(root)
        if (self.root / "meta" / "info.json").exists():
            raise DatasetWriteError(f"{self.root} already holds a dataset (fix: give a new "
                                    "output folder)")
        for name, (h, w) in cameras.items():
            if h % 2 or w % 2:
                raise DatasetWriteError(f"camera {name!r}: {w}x{h} must be even in both "
                                        "sides for yuv420p video (fix: e.g. --size 160x120)")
        if fps <= 0:
            raise DatasetWriteError(f"fps must be a positive integer, got {fps}")
        self.cameras, self.fps, self.robot_type = dict(cameras), int(fps), robot_type
        self.env_width, self.factor_width = env_width, factor_width
        self.columns: dict[str, list[Any]] = {k: [] for k in (
            "observation.state", "observation.environment_state", "action", "next.reward",
            "next.total_reward", "next.factor_rewards", "next.done", "next.success",
            "language_goal", "timestamp", "frame_index", "episode_index", "index",
            "task_index")}
        self.episodes: list[dict[str, Any]] = []
        self.tasks: dict[str, int] = {}
        self.frames = 0
        self._video_frames = 0
        self._image_sums = {c: np.zeros((3, 3)) for c in cameras}  # sum, sum sq, min/max
        self._image_min = {c: np.full(3, np.inf) for c in cameras}
        self._image_max = {c: np.full(3, -np.inf) for c in cameras}
        self._containers: dict[str, Any] = {}
        self._streams: dict[str, Any] = {}
        self._open_videos()

    def _open_videos(self) -> None:
        import av

        for cam, (h, w) in self.cameras.items():
            path = self.root / VIDEO_PATH.format(video_key=image_key(cam), chunk_index=0,
                                                 file_index=0)
            path.parent.mkdir(parents=True, exist_ok=True)
            container = av.open(str(path), mode="w")
            stream = container.add_stream("libx264", rate=self.fps)
            stream.width, stream.height, stream.pix_fmt = w, h, "yuv420p"
            stream.time_base = Fraction(1, self.fps)
            # Every frame a keyframe: random access by timestamp stays exact and cheap.
            stream.options = {"crf": str(VIDEO_CRF), "g": "1", "bf": "0"}
            self._containers[cam], self._streams[cam] = container, stream

    def add_episode(self, ep: EpisodeRecord, states_path: str | None = None) -> int:
        """Append one episode; returns its episode index.

        Raises:
            DatasetWriteError: its cameras or widths do not fit this dataset.
        """
        import av

        if set(ep.images) != set(self.cameras):
            raise DatasetWriteError(f"episode cameras {sorted(ep.images)} differ from the "
                                    f"dataset's {sorted(self.cameras)}")
        if ep.environment_state.shape[1] > self.env_width or \
                ep.factor_rewards.shape[1] > self.factor_width:
            raise DatasetWriteError(f"task {ep.task!r} has more objects or factors than "
                                    "the dataset was sized for")
        index = len(self.episodes)
        task_index = self.tasks.setdefault(ep.instruction, len(self.tasks))
        n, start = ep.length, self.frames
        env = np.zeros((n, self.env_width), np.float32)
        env[:, :ep.environment_state.shape[1]] = ep.environment_state
        fac = np.zeros((n, self.factor_width), np.float32)
        fac[:, :ep.factor_rewards.shape[1]] = ep.factor_rewards
        c = self.columns
        c["observation.state"].extend(ep.state.astype(np.float32))
        c["observation.environment_state"].extend(env)
        c["action"].extend(ep.action.astype(np.float32))
        c["next.reward"].extend(ep.reward.astype(np.float32))
        c["next.total_reward"].extend(ep.total_reward.astype(np.float32))
        c["next.factor_rewards"].extend(fac)
        c["next.done"].extend(ep.done.astype(bool))
        c["next.success"].extend(ep.total_reward >= SUCCESS_REWARD)
        c["language_goal"].extend(ep.goal)
        c["timestamp"].extend(np.arange(n, dtype=np.float32) / self.fps)
        c["frame_index"].extend(range(n))
        c["episode_index"].extend([index] * n)
        c["index"].extend(range(start, start + n))
        c["task_index"].extend([task_index] * n)
        row: dict[str, Any] = {
            "episode_index": index, "tasks": [ep.instruction], "length": n,
            "data/chunk_index": 0, "data/file_index": 0,
            "dataset_from_index": start, "dataset_to_index": start + n,
        }
        for cam, frames in ep.images.items():
            if len(frames) != n:
                raise DatasetWriteError(f"camera {cam!r}: {len(frames)} images for {n} frames")
            stream, container = self._streams[cam], self._containers[cam]
            for k, img in enumerate(frames):
                frame = av.VideoFrame.from_ndarray(np.ascontiguousarray(img), format="rgb24")
                frame.pts = self._video_frames + k
                frame.time_base = Fraction(1, self.fps)
                for packet in stream.encode(frame):
                    container.mux(packet)
            if n:
                pix = frames.reshape(-1, 3).astype(np.float64) / 255.0
                self._image_sums[cam][0] += pix.sum(0)
                self._image_sums[cam][1] += (pix ** 2).sum(0)
                self._image_sums[cam][2] += len(pix)
                self._image_min[cam] = np.minimum(self._image_min[cam], pix.min(0))
                self._image_max[cam] = np.maximum(self._image_max[cam], pix.max(0))
            key = image_key(cam)
            row[f"videos/{key}/chunk_index"] = 0
            row[f"videos/{key}/file_index"] = 0
            row[f"videos/{key}/from_timestamp"] = self._video_frames / self.fps
            row[f"videos/{key}/to_timestamp"] = (self._video_frames + n) / self.fps
        row.update({"meta/episodes/chunk_index": 0, "meta/episodes/file_index": 0,
                    "factask/task": ep.task, "factask/seed": ep.seed,
                    "factask/success": ep.success, "factask/final_reward": ep.final_reward,
                    "factask/states_path": states_path or ""})
        self.episodes.append(row)
        self.frames += n
        self._video_frames += n
        return index

    # ------------------------------------------------------------- metadata
    def features(self) -> dict[str, dict[str, Any]]:
        """The ``features`` of info.json."""
        feats: dict[str, dict[str, Any]] = {
            "observation.state": _vec("float32", len(STATE_NAMES), STATE_NAMES),
            "observation.environment_state": _vec("float32", self.env_width),
            "action": _vec("float32", len(ACTION_NAMES), ACTION_NAMES),
            "next.reward": _vec("float32", 1),
            "next.total_reward": _vec("float32", 1),
            "next.factor_rewards": _vec("float32", self.factor_width),
            "next.done": _vec("bool", 1),
            "next.success": _vec("bool", 1),
            "language_goal": _vec("string", 1),
        }
        for cam, (h, w) in self.cameras.items():
            feats[image_key(cam)] = {
                "dtype": "video", "shape": [h, w, 3], "names": ["height", "width", "channels"],
                "info": {"video.height": h, "video.width": w, "video.codec": "h264",
                         "video.pix_fmt": "yuv420p", "video.is_depth_map": False,
                         "video.fps": self.fps, "video.channels": 3, "has_audio": False}}
        for key, dtype in (("timestamp", "float32"), ("frame_index", "int64"),
                           ("episode_index", "int64"), ("index", "int64"),
                           ("task_index", "int64")):
            feats[key] = _vec(dtype, 1)
        return feats

    def _data_table(self) -> pa.Table:
        arrays, feats = {}, self.features()
        for key, values in self.columns.items():
            f = feats[key]
            if f["dtype"] == "string":
                arrays[key] = pa.array(values, pa.string())
            elif f["shape"] == [1]:
                arrays[key] = pa.array(np.asarray(values, dtype=f["dtype"]))
            else:
                flat = np.asarray(values, dtype=f["dtype"]).reshape(-1)
                arrays[key] = pa.FixedSizeListArray.from_arrays(pa.array(flat), f["shape"][0])
        return pa.table(arrays)

    def _stats(self, table: pa.Table) -> dict[str, Any]:
        stats: dict[str, Any] = {}
        for key, f in self.features().items():
            if f["dtype"] in ("string", "video") or key not in table.column_names:
                continue
            col = table.column(key).combine_chunks()
            values = (col.flatten() if f["shape"] != [1] else col).to_numpy(
                zero_copy_only=False).astype(np.float64).reshape(len(col), -1)
            if not len(values):
                continue
            stats[key] = {"min": values.min(0).tolist(), "max": values.max(0).tolist(),
                          "mean": values.mean(0).tolist(), "std": values.std(0).tolist(),
                          "count": [len(values)]}
        for cam in self.cameras:
            s, count = self._image_sums[cam], self._image_sums[cam][2][0]
            if not count:
                continue
            mean = s[0] / count
            std = np.sqrt(np.maximum(s[1] / count - mean ** 2, 0.0))
            # LeRobot keeps image stats per channel as (3, 1, 1), values in [0, 1].
            stats[image_key(cam)] = {
                k: [[[float(v)]] for v in arr] for k, arr in (
                    ("min", self._image_min[cam]), ("max", self._image_max[cam]),
                    ("mean", mean), ("std", std))} | {"count": [int(count)]}
        return stats

    def finalize(self, splits: dict[str, str] | None = None,
                 extra: dict[str, Any] | None = None) -> dict[str, Any]:
        """Close the videos and write data, episodes, tasks, stats and info.

        Args:
            splits: LeRobot's ``splits`` ("train": "0:N", episode ranges).
            extra: More keys for info.json (factask's own: seeds, cameras).

        Returns:
            The info.json content.
        """
        for cam, container in self._containers.items():
            for packet in self._streams[cam].encode():
                container.mux(packet)
            container.close()
        self._containers.clear()
        table = self._data_table()
        data_path = self.root / DATA_PATH.format(chunk_index=0, file_index=0)
        data_path.parent.mkdir(parents=True, exist_ok=True)
        pq.write_table(table, data_path)
        ep_path = self.root / EPISODES_PATH.format(chunk_index=0, file_index=0)
        ep_path.parent.mkdir(parents=True, exist_ok=True)
        pq.write_table(pa.Table.from_pylist(self.episodes) if self.episodes else
                       pa.table({"episode_index": pa.array([], pa.int64())}), ep_path)
        self._write_tasks()
        stats = self._stats(table)
        (self.root / "meta" / "stats.json").write_text(json.dumps(stats, indent=2))
        info = {
            "codebase_version": CODEBASE_VERSION, "robot_type": self.robot_type,
            "total_episodes": len(self.episodes), "total_frames": self.frames,
            "total_tasks": len(self.tasks), "chunks_size": CHUNKS_SIZE,
            "data_files_size_in_mb": DATA_FILES_SIZE_IN_MB,
            "video_files_size_in_mb": VIDEO_FILES_SIZE_IN_MB, "fps": self.fps,
            "splits": splits or {"train": f"0:{len(self.episodes)}"},
            "data_path": DATA_PATH, "video_path": VIDEO_PATH if self.cameras else None,
            "features": self.features(),
        }
        if extra:
            info["factask"] = extra
        (self.root / "meta" / "info.json").write_text(json.dumps(info, indent=4))
        return info

    def _write_tasks(self) -> None:
        tasks = sorted(self.tasks.items(), key=lambda kv: kv[1])
        table = pa.table({"task_index": pa.array([i for _, i in tasks], pa.int64()),
                          "task": pa.array([t for t, _ in tasks], pa.string())})
        # pandas metadata: LeRobot reads this file with pandas, the task text as the index.
        pandas_meta = {"index_columns": ["task"], "column_indexes": [], "columns": [
            {"name": "task_index", "field_name": "task_index", "pandas_type": "int64",
             "numpy_type": "int64", "metadata": None},
            {"name": "task", "field_name": "task", "pandas_type": "unicode",
             "numpy_type": "object", "metadata": None}],
            "creator": {"library": "factask"}, "pandas_version": "2.2.0"}
        table = table.replace_schema_metadata({"pandas": json.dumps(pandas_meta)})
        pq.write_table(table, self.root / TASKS_PATH)

    def abort(self) -> None:
        """Close open video files without writing metadata."""
        for container in self._containers.values():
            container.close()
        self._containers.clear()
