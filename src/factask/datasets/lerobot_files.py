"""The files of a LeRobot v3.0 dataset that grow: rolling parquet and MP4 files, stats.

LeRobot v3.0 packs many episodes into one file and starts the next file once a file
passes its size target (``data_files_size_in_mb``, ``video_files_size_in_mb``); files
are numbered ``chunk-CCC/file-FFF`` with at most ``chunks_size`` files per chunk. An
episode never straddles two files. Statistics are accumulated as episodes arrive, so
nothing is held in memory beyond one episode.
"""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

#: H.264 quality (lower is better).
VIDEO_CRF = 15
MEGABYTE = 1024 * 1024


def file_position(counter: int, chunks_size: int) -> tuple[int, int]:
    """(chunk_index, file_index) of the ``counter``-th file."""
    return counter // chunks_size, counter % chunks_size


class RollingParquet:
    """Episode tables appended to ``data/chunk-CCC/file-FFF.parquet``, rolling by size.

    Args:
        root: The dataset folder.
        template: The path template (``info["data_path"]``).
        schema: The table schema.
        max_mb: Start a new file once the current one holds more than this.
        chunks_size: Files per chunk folder.
    """

    def __init__(self, root: Path, template: str, schema: pa.Schema, max_mb: float,
                 chunks_size: int) -> None:
        self.root, self.template, self.schema = root, template, schema
        self.max_bytes, self.chunks_size = max_mb * MEGABYTE, chunks_size
        self.counter, self.bytes = 0, 0
        self._writer: pq.ParquetWriter | None = None

    def write(self, table: pa.Table) -> tuple[int, int]:
        """Append one episode's rows; returns the (chunk, file) they went to."""
        if self._writer is not None and self.bytes >= self.max_bytes:
            self._writer.close()
            self._writer, self.counter, self.bytes = None, self.counter + 1, 0
        chunk, file = file_position(self.counter, self.chunks_size)
        if self._writer is None:
            path = self.root / self.template.format(chunk_index=chunk, file_index=file)
            path.parent.mkdir(parents=True, exist_ok=True)
            self._writer = pq.ParquetWriter(path, self.schema)
        self._writer.write_table(table)
        self.bytes += table.nbytes
        return chunk, file

    def close(self) -> None:
        """Close the current file (an empty dataset still gets one, empty)."""
        if self._writer is None:
            path = self.root / self.template.format(chunk_index=0, file_index=0)
            path.parent.mkdir(parents=True, exist_ok=True)
            self._writer = pq.ParquetWriter(path, self.schema)
        self._writer.close()


class RollingVideo:
    """One camera's frames in H.264 MP4 files, rolling by size.

    Frame k of a file has presentation time k / fps. Every frame is a keyframe (GOP 1,
    no B-frames): seeking to an episode's first timestamp is exact and cheap.
    """

    def __init__(self, root: Path, template: str, key: str, size: tuple[int, int], fps: int,
                 max_mb: float, chunks_size: int) -> None:
        self.root, self.template, self.key = root, template, key
        self.height, self.width = size
        self.fps, self.max_bytes, self.chunks_size = fps, max_mb * MEGABYTE, chunks_size
        self.counter, self.bytes, self.frames = 0, 0, 0
        self._container: Any = None
        self._stream: Any = None

    def _open(self) -> None:
        import av

        chunk, file = file_position(self.counter, self.chunks_size)
        path = self.root / self.template.format(video_key=self.key, chunk_index=chunk,
                                                file_index=file)
        path.parent.mkdir(parents=True, exist_ok=True)
        self._container = av.open(str(path), mode="w")
        stream = self._container.add_stream("libx264", rate=self.fps)
        stream.width, stream.height, stream.pix_fmt = self.width, self.height, "yuv420p"
        stream.time_base = Fraction(1, self.fps)
        # zerolatency: each frame's packet comes out at once, so the size count is current
        # when the next episode decides whether to start a new file.
        stream.options = {"crf": str(VIDEO_CRF), "g": "1", "bf": "0", "tune": "zerolatency"}
        self._stream = stream

    def _mux(self, packets: Any) -> None:
        for packet in packets:
            self.bytes += packet.size
            self._container.mux(packet)

    def write(self, frames: np.ndarray) -> tuple[int, int, float, float]:
        """Append one episode's frames (n, h, w, 3) uint8.

        Returns:
            (chunk, file, from_timestamp, to_timestamp) of the episode in its file.
        """
        import av

        if self._container is not None and self.bytes >= self.max_bytes:
            self.close()
            self.counter, self.bytes, self.frames = self.counter + 1, 0, 0
        if self._container is None:
            self._open()
        start = self.frames
        for img in frames:
            frame = av.VideoFrame.from_ndarray(np.ascontiguousarray(img), format="rgb24")
            frame.pts, frame.time_base = self.frames, Fraction(1, self.fps)
            self._mux(self._stream.encode(frame))
            self.frames += 1
        chunk, file = file_position(self.counter, self.chunks_size)
        return chunk, file, start / self.fps, self.frames / self.fps

    def close(self) -> None:
        """Flush the encoder and close the current file."""
        if self._container is not None:
            self._mux(self._stream.encode())
            self._container.close()
            self._container = self._stream = None


class RunningStats:
    """min / max / mean / std / count of a feature, accumulated over episodes."""

    def __init__(self) -> None:
        self.count = 0
        self.low: np.ndarray | None = None
        self.high: np.ndarray | None = None
        self.total: np.ndarray | None = None
        self.squares: np.ndarray | None = None

    def add(self, values: np.ndarray) -> None:
        """Add rows (n, d) of values."""
        if not len(values):
            return
        v = np.asarray(values, dtype=np.float64).reshape(len(values), -1)
        if self.low is None:
            self.low, self.high = v.min(0), v.max(0)
            self.total, self.squares = v.sum(0), (v ** 2).sum(0)
        else:
            self.low, self.high = np.minimum(self.low, v.min(0)), np.maximum(self.high, v.max(0))
            self.total, self.squares = self.total + v.sum(0), self.squares + (v ** 2).sum(0)
        self.count += len(v)

    def as_dict(self, image: bool = False) -> dict[str, Any] | None:
        """LeRobot's stats entry (images: per channel as (3, 1, 1) lists), or None if empty."""
        if self.low is None:
            return None
        mean = self.total / self.count
        std = np.sqrt(np.maximum(self.squares / self.count - mean ** 2, 0.0))
        parts = {"min": self.low, "max": self.high, "mean": mean, "std": std}
        if image:
            out: dict[str, Any] = {k: [[[float(x)]] for x in v] for k, v in parts.items()}
        else:
            out = {k: v.tolist() for k, v in parts.items()}
        out["count"] = [self.count]
        return out
