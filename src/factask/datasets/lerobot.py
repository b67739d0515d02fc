"""A LeRobot v3.0 dataset writer on pyarrow and PyAV (no ``lerobot``, no torch).

Layout (LeRobot's path templates; a file rolls over to the next once it passes its size
target, :mod:`factask.datasets.lerobot_files`)::

    meta/info.json                       codebase_version "v3.0", fps, features, totals
    meta/stats.json                      min / max / mean / std / count per feature
    meta/tasks.parquet                   task (the language instruction) -> task_index
    meta/episodes/chunk-000/file-000.parquet   one row per episode (with its files)
    data/chunk-CCC/file-FFF.parquet      one row per frame, many episodes per file
    videos/observation.images.<camera>/chunk-CCC/file-FFF.mp4   many episodes per file

Per frame: ``observation.state`` (suction tip pose, suction), ``observation.environment_state``
(object poses, zero-padded to the largest task), ``action`` (the decision encoded:
:mod:`factask.datasets.actions`),
``next.reward`` (the reward change), ``next.total_reward``, ``next.factor_rewards``
(per-factor progress, zero-padded), ``next.done``, ``next.success``, ``language_goal``
(the current factor's goal), and LeRobot's ``timestamp``, ``frame_index``,
``episode_index``, ``index``, ``task_index``. Videos are H.264 (yuv420p); frame k of a
file has presentation time k / fps, so an episode spans [from_timestamp, to_timestamp)
of its file.

With control frames (:mod:`factask.datasets.control_frames`) a frame is one sample of
the low-level command stream: ``action`` is the low-level command, and two more
features carry the decision each frame belongs to: ``action.primitive`` (encoded as
above) and ``decision_index``.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from factask.datasets.actions import ACTION_ENCODING, ACTION_NAMES
from factask.datasets.layout import (
    CHUNKS_SIZE,
    CODEBASE_VERSION,
    DATA_FILES_SIZE_IN_MB,
    DATA_PATH,
    DEFAULT_FPS,
    EPISODES_PATH,
    TASKS_PATH,
    VIDEO_FILES_SIZE_IN_MB,
    VIDEO_PATH,
)
from factask.datasets.lerobot_files import RollingParquet, RollingVideo, RunningStats
from factask.datasets.recording import STATE_NAMES, EpisodeRecord
from factask.vocabulary.errors import FactaskError
from factask.vocabulary.tolerances import SUCCESS_REWARD

#: Images per step of the running image statistics.
STATS_FRAMES = 16


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
        data_mb: Size target of a data file (MB).
        video_mb: Size target of a video file (MB).
        action_names: Names of ``action`` (default: the decision encoded,
            :data:`~factask.datasets.actions.ACTION_NAMES`); control frames name the
            low-level command here.
        control: Frames are control samples: adds ``action.primitive`` and
            ``decision_index``.

    Raises:
        DatasetWriteError: a dataset is already there, an odd image size, bad fps.
    """

    def __init__(self, root: Path, cameras: dict[str, tuple[int, int]], env_width: int,
                 factor_width: int, fps: int = DEFAULT_FPS, robot_type: str | None = None,
                 data_mb: float = DATA_FILES_SIZE_IN_MB,
                 video_mb: float = VIDEO_FILES_SIZE_IN_MB,
                 action_names: list[str] | None = None, control: bool = False) -> None:
        self.root = Path(root)
        self.action_names = list(action_names or ACTION_NAMES)
        self.control = control
        if (self.root / "meta" / "info.json").exists():
            raise DatasetWriteError(f"{self.root} already holds a dataset (fix: give a new "
                                    "output folder)")
        for name, (h, w) in cameras.items():
            if h % 2 or w % 2:
                raise DatasetWriteError(f"camera {name!r}: {w}x{h} must be even in both "
                                        "sides for yuv420p video (fix: e.g. --size 160x120)")
        if fps <= 0:
            raise DatasetWriteError(f"fps must be a positive integer, got {fps}")
        if not (data_mb > 0 and video_mb > 0):
            raise DatasetWriteError(f"file size targets must be positive, got data {data_mb} "
                                    f"MB and video {video_mb} MB")
        self.cameras, self.fps, self.robot_type = dict(cameras), int(fps), robot_type
        self.env_width, self.factor_width = env_width, factor_width
        self.data_mb, self.video_mb = data_mb, video_mb
        self.episodes: list[dict[str, Any]] = []
        self.tasks: dict[str, int] = {}
        self.frames = 0
        feats = self.features()
        self._plain = {k: f for k, f in feats.items() if f["dtype"] != "video"}
        self._stats = {k: RunningStats() for k, f in feats.items() if f["dtype"] != "string"}
        self._data = RollingParquet(self.root, DATA_PATH, self._schema(), data_mb, CHUNKS_SIZE)
        self._videos = {cam: RollingVideo(self.root, VIDEO_PATH, image_key(cam), size,
                                          self.fps, video_mb, CHUNKS_SIZE)
                        for cam, size in self.cameras.items()}

    def _schema(self) -> pa.Schema:
        fields = []
        for key, f in self._plain.items():
            base = pa.string() if f["dtype"] == "string" else pa.from_numpy_dtype(
                np.dtype(f["dtype"]))
            fields.append(pa.field(key, base if f["shape"] == [1] or f["dtype"] == "string"
                                   else pa.list_(base, f["shape"][0])))
        return pa.schema(fields)

    def _frame_columns(self, ep: EpisodeRecord, index: int, task_index: int
                       ) -> dict[str, np.ndarray | list[str]]:
        n, start = ep.length, self.frames
        env = np.zeros((n, self.env_width), np.float32)
        env[:, :ep.environment_state.shape[1]] = ep.environment_state
        fac = np.zeros((n, self.factor_width), np.float32)
        fac[:, :ep.factor_rewards.shape[1]] = ep.factor_rewards
        extra: dict[str, np.ndarray] = {}
        if self.control:
            if ep.primitive is None or ep.decision is None:
                raise DatasetWriteError(f"episode of {ep.task!r} (seed {ep.seed}) was not "
                                        "recorded with control frames")
            if ep.primitive.shape[1:] != (len(ACTION_NAMES),):
                raise DatasetWriteError(f"episode of {ep.task!r}: action.primitive width "
                                        f"{ep.primitive.shape[1:]} for {len(ACTION_NAMES)} "
                                        "names (recorded by an older factask?)")
            extra = {"action.primitive": ep.primitive.astype(np.float32),
                     "decision_index": ep.decision.astype(np.int64)}
        return extra | {
            "observation.state": ep.state.astype(np.float32),
            "observation.environment_state": env,
            "action": ep.action.astype(np.float32),
            "next.reward": ep.reward.astype(np.float32),
            "next.total_reward": ep.total_reward.astype(np.float32),
            "next.factor_rewards": fac,
            "next.done": ep.done.astype(bool),
            "next.success": ep.total_reward >= SUCCESS_REWARD,
            "language_goal": list(ep.goal),
            "timestamp": np.arange(n, dtype=np.float32) / self.fps,
            "frame_index": np.arange(n, dtype=np.int64),
            "episode_index": np.full(n, index, np.int64),
            "index": np.arange(start, start + n, dtype=np.int64),
            "task_index": np.full(n, task_index, np.int64),
        }

    def _table(self, columns: dict[str, Any]) -> pa.Table:
        arrays = []
        for key, f in self._plain.items():
            values = columns[key]
            if f["dtype"] == "string":
                arrays.append(pa.array(values, pa.string()))
            elif f["shape"] == [1]:
                # (n,) or (n, 1): a task of one factor has factor rewards one wide.
                arrays.append(pa.array(np.asarray(values, dtype=f["dtype"]).reshape(-1)))
            else:
                flat = np.asarray(values, dtype=f["dtype"]).reshape(-1)
                arrays.append(pa.FixedSizeListArray.from_arrays(pa.array(flat), f["shape"][0]))
        return pa.Table.from_arrays(arrays, schema=self._data.schema)

    def add_episode(self, ep: EpisodeRecord, states_path: str | None = None) -> int:
        """Append one episode; returns its episode index.

        Raises:
            DatasetWriteError: its cameras, widths or image counts do not fit.
        """
        if set(ep.images) != set(self.cameras):
            raise DatasetWriteError(f"episode cameras {sorted(ep.images)} differ from the "
                                    f"dataset's {sorted(self.cameras)}")
        if ep.environment_state.shape[1] > self.env_width or \
                ep.factor_rewards.shape[1] > self.factor_width:
            raise DatasetWriteError(f"task {ep.task!r} has more objects or factors than "
                                    "the dataset was sized for")
        n = ep.length
        if ep.action.shape[1:] != (len(self.action_names),):
            raise DatasetWriteError(f"episode of {ep.task!r}: action width "
                                    f"{ep.action.shape[1:]} for {len(self.action_names)} names")
        for cam, frames in ep.images.items():
            if len(frames) != n:
                raise DatasetWriteError(f"camera {cam!r}: {len(frames)} images for {n} frames")
        index = len(self.episodes)
        task_index = self.tasks.setdefault(ep.instruction, len(self.tasks))
        columns = self._frame_columns(ep, index, task_index)
        for key, stats in self._stats.items():
            if key in columns:
                stats.add(np.asarray(columns[key]))
        chunk, file = self._data.write(self._table(columns))
        row: dict[str, Any] = {
            "episode_index": index, "tasks": [ep.instruction], "length": n,
            "data/chunk_index": chunk, "data/file_index": file,
            "dataset_from_index": self.frames, "dataset_to_index": self.frames + n,
        }
        for cam, frames in ep.images.items():
            key = image_key(cam)
            v_chunk, v_file, t0, t1 = self._videos[cam].write(frames)
            # A few frames at a time: a control-frame episode has hundreds of images,
            # whose pixels as float64 at once would take hundreds of MB.
            for k in range(0, n, STATS_FRAMES):
                self._stats[key].add(frames[k:k + STATS_FRAMES].reshape(-1, 3) / 255.0)
            row.update({f"videos/{key}/chunk_index": v_chunk, f"videos/{key}/file_index": v_file,
                        f"videos/{key}/from_timestamp": t0, f"videos/{key}/to_timestamp": t1})
        row.update({"meta/episodes/chunk_index": 0, "meta/episodes/file_index": 0,
                    "factask/task": ep.task, "factask/seed": ep.seed,
                    "factask/success": ep.success, "factask/final_reward": ep.final_reward,
                    "factask/states_path": states_path or ""})
        self.episodes.append(row)
        self.frames += n
        return index

    # ------------------------------------------------------------- metadata
    def features(self) -> dict[str, dict[str, Any]]:
        """The ``features`` of info.json."""
        feats: dict[str, dict[str, Any]] = {
            "observation.state": _vec("float32", len(STATE_NAMES), STATE_NAMES),
            "observation.environment_state": _vec("float32", self.env_width),
            "action": _vec("float32", len(self.action_names), self.action_names),
            "next.reward": _vec("float32", 1),
            "next.total_reward": _vec("float32", 1),
            "next.factor_rewards": _vec("float32", self.factor_width),
            "next.done": _vec("bool", 1),
            "next.success": _vec("bool", 1),
            "language_goal": _vec("string", 1),
        }
        if self.control:
            feats["action.primitive"] = _vec("float32", len(ACTION_NAMES), ACTION_NAMES)
            feats["decision_index"] = _vec("int64", 1)
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

    def _close_files(self) -> None:
        self._data.close()
        for video in self._videos.values():
            video.close()

    def finalize(self, splits: dict[str, str] | None = None,
                 extra: dict[str, Any] | None = None) -> dict[str, Any]:
        """Close the data and video files; write episodes, tasks, stats and info.

        Args:
            splits: LeRobot's ``splits`` ("train": "0:N", episode ranges).
            extra: More keys for info.json's ``factask`` (factask's own: options,
                cameras; ``action_encoding`` is always there).

        Returns:
            The info.json content.
        """
        self._close_files()
        ep_path = self.root / EPISODES_PATH.format(chunk_index=0, file_index=0)
        ep_path.parent.mkdir(parents=True, exist_ok=True)
        pq.write_table(pa.Table.from_pylist(self.episodes) if self.episodes else
                       pa.table({"episode_index": pa.array([], pa.int64())}), ep_path)
        self._write_tasks()
        feats = self.features()
        stats = {k: d for k, s in self._stats.items()
                 if (d := s.as_dict(image=feats[k]["dtype"] == "video")) is not None}
        (self.root / "meta" / "stats.json").write_text(json.dumps(stats, indent=2))
        info = {
            "codebase_version": CODEBASE_VERSION, "robot_type": self.robot_type,
            "total_episodes": len(self.episodes), "total_frames": self.frames,
            "total_tasks": len(self.tasks), "chunks_size": CHUNKS_SIZE,
            "data_files_size_in_mb": self.data_mb, "video_files_size_in_mb": self.video_mb,
            "fps": self.fps, "splits": splits or {"train": f"0:{len(self.episodes)}"},
            "data_path": DATA_PATH, "video_path": VIDEO_PATH if self.cameras else None,
            "features": feats,
        }
        # The action layout's version (factask.datasets.actions): 2 is every primitive.
        info["factask"] = {"action_encoding": ACTION_ENCODING} | (extra or {})
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
        """Close open files without writing metadata (no info.json: not a dataset)."""
        self._close_files()
