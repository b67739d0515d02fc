"""LeRobot v3.0's layout constants: path templates, file-size targets, default fps.

Apart from the writer (:mod:`factask.datasets.lerobot`) so that what only needs the
numbers (a collection's options, a worker recording a shard) does not import pyarrow.
"""

from __future__ import annotations

CODEBASE_VERSION = "v3.0"
DATA_PATH = "data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet"
VIDEO_PATH = "videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4"
EPISODES_PATH = "meta/episodes/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet"
TASKS_PATH = "meta/tasks.parquet"
#: LeRobot's defaults: files per chunk folder, size targets of data and video files.
CHUNKS_SIZE = 1000
DATA_FILES_SIZE_IN_MB = 100
VIDEO_FILES_SIZE_IN_MB = 200
#: Default frames per second: one frame per pick-and-place decision, shown at 1 Hz.
DEFAULT_FPS = 1
