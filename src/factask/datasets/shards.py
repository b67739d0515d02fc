"""Collection at scale: (task, seed range) shards, a process pool or Ray, resume, merge.

A run plans its shards up front (:func:`plan_shards`) and writes the plan to
``<out>/.shards/plan.json``. Each shard is recorded by one worker and written to
``<out>/.shards/<shard id>.pkl`` *atomically* (a temporary file, then a rename), so a
shard file exists only when complete. A killed run, started again with the same
options, skips the shards already written and records only the rest: nothing is
lost and nothing repeated. When every shard is there they are merged, in plan order,
into one LeRobot dataset (:mod:`factask.datasets.lerobot`) with a states file per
episode; the shard folder is then removed.
"""

from __future__ import annotations

import json
import os
import pickle
import shutil
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from factask.datasets.actions import ACTION_ENCODING
from factask.datasets.control_frames import (
    check_frame_mode,
    command_names,
    default_control_fps,
)
from factask.datasets.layout import DATA_FILES_SIZE_IN_MB, DEFAULT_FPS, VIDEO_FILES_SIZE_IN_MB
from factask.datasets.parallel import run_jobs
from factask.datasets.recording import EpisodeRecord
from factask.datasets.splits import split_seeds
from factask.datasets.states import write_states
from factask.vocabulary.errors import FactaskError

#: Folder of shard files inside the output folder.
SHARD_DIR = ".shards"
#: Default episodes (seeds) per shard.
DEFAULT_SHARD_SIZE = 10


class CollectError(FactaskError, ValueError):
    """A collection that cannot run as asked (other settings in the folder, no Ray)."""


@dataclass(frozen=True)
class CollectConfig:
    """What a collection records (the same options must be given to resume it).

    Attributes:
        tasks: Library names, ids or graph files, in dataset order.
        episodes: Seeds run per task (the split's first ``episodes``).
        split: "train", "val" or "test" (:mod:`factask.datasets.splits`).
        robot: A name of the robot registry.
        image_size: (width, height) of the Ravens cameras; None records no video.
        fps: Frames per second of timestamps and videos.
        keep_failed: Keep episodes that did not succeed.
        shard_size: Seeds per shard.
        data_mb: Size target of one data parquet file (LeRobot's default 100 MB).
        video_mb: Size target of one MP4 file (LeRobot's default 200 MB).
        frames: "decision" (a frame per pick-and-place) or "control" (a frame per
            low-level command sample; ``fps`` must then be the command rate,
            :func:`~factask.datasets.control_frames.control_fps`).
    """

    tasks: tuple[str, ...]
    episodes: int
    split: str = "train"
    robot: str = "floating"
    image_size: tuple[int, int] | None = (160, 120)
    fps: int = DEFAULT_FPS
    keep_failed: bool = False
    shard_size: int = DEFAULT_SHARD_SIZE
    data_mb: float = DATA_FILES_SIZE_IN_MB
    video_mb: float = VIDEO_FILES_SIZE_IN_MB
    frames: str = "decision"


@dataclass(frozen=True)
class Shard:
    """One unit of work: a task and a run of its split's episodes."""

    task: str
    task_position: int
    first: int
    seeds: tuple[int, ...]

    @property
    def id(self) -> str:
        """A file-safe, sortable name."""
        slug = "".join(ch if ch.isalnum() or ch in "-_" else "_" for ch in self.task)[-60:]
        return f"{self.task_position:04d}-{slug}-{self.first:07d}"


@dataclass
class CollectSummary:
    """What a collection did."""

    root: str
    shards_total: int
    shards_run: int
    shards_resumed: int
    episodes_run: int
    episodes_kept: int
    frames: int
    seconds: float
    kept_seeds: list[int] = field(default_factory=list)

    @property
    def episodes_per_minute(self) -> float:
        """Episodes recorded per minute of this call (resumed shards not counted)."""
        return 60.0 * self.episodes_run / self.seconds if self.seconds > 0 else 0.0

    def to_dict(self) -> dict[str, Any]:
        return asdict(self) | {"episodes_per_minute": self.episodes_per_minute}


def plan_shards(config: CollectConfig) -> list[Shard]:
    """The shards of a collection, in dataset order."""
    shards = []
    for pos, task in enumerate(config.tasks):
        seeds = split_seeds(config.split, config.episodes)
        for k in range(0, len(seeds), config.shard_size):
            shards.append(Shard(task, pos, k, tuple(seeds[k:k + config.shard_size])))
    return shards


def run_shard(shard: Shard, config: CollectConfig, shard_dir: str) -> str:
    """Record one shard and write it atomically (the worker's entry point).

    Returns:
        The shard file's path.
    """
    from factask.datasets.recording import record_episodes
    from factask.registration import resolve_task
    from factask.sim.env import FactaskEnv
    from factask.sim.render.cameras import CameraRig, ravens_cameras

    env = FactaskEnv(resolve_task(shard.task), robot=config.robot)
    rig = None
    if config.image_size is not None:
        rig = CameraRig(env.model, ravens_cameras(*config.image_size), env.scene.geom_object)
    try:
        records = record_episodes(env, shard.seeds, rig, frames=config.frames, fps=config.fps)
    finally:
        if rig is not None:
            rig.close()
        env.close()
    path = Path(shard_dir) / f"{shard.id}.pkl"
    tmp = path.with_name(f"{path.name}.{os.getpid()}.tmp")
    with open(tmp, "wb") as fh:
        pickle.dump(records, fh, protocol=pickle.HIGHEST_PROTOCOL)
    os.replace(tmp, path)  # the shard exists only once complete
    return str(path)


def _check_plan(shard_dir: Path, config: CollectConfig) -> None:
    plan = shard_dir / "plan.json"
    # The action layout too: shards of an older factask hold actions of another width.
    mine = json.dumps(asdict(config) | {"action_encoding": ACTION_ENCODING}, sort_keys=True)
    if plan.exists():
        if plan.read_text() != mine:
            raise CollectError(f"{shard_dir.parent} holds an unfinished collection with other "
                               "options or of another factask version (fix: repeat its "
                               "options to resume, or give a new output folder)")
        return
    shard_dir.mkdir(parents=True, exist_ok=True)
    plan.write_text(mine)


def _widths(config: CollectConfig) -> tuple[int, int]:
    from factask.registration import resolve_task

    graphs = [resolve_task(t) for t in config.tasks]
    objects = max(sum(v.count for v in g.variables) for g in graphs)
    factors = max(len(g.factors) for g in graphs)
    return 7 * objects, factors


def collect(config: CollectConfig, root: Path, workers: int | None = None,
            ray_address: str | None = None,
            on_shard: Callable[[Shard], None] | None = None) -> CollectSummary:
    """Record every shard not yet written, then merge them into a LeRobot dataset.

    Args:
        config: What to record.
        root: Output folder (resumes an unfinished run with the same ``config``).
        workers: Worker processes (default: the machine's cores); 1 runs in-process.
        ray_address: Run the shards on Ray instead ("auto", "local" or an address).
        on_shard: Called in this process as each shard completes.

    Returns:
        The summary.

    Raises:
        CollectError: the folder holds a finished dataset or another run's shards, or
            control frames at another fps than the command rate.
        FrameModeError: an unknown frame mode.
        ParallelError: ``ray_address`` without Ray installed.
    """
    root = Path(root)
    if (root / "meta" / "info.json").exists():
        raise CollectError(f"{root} already holds a dataset (fix: give a new output folder)")
    check_frame_mode(config.frames)
    if config.frames == "control" and config.fps != default_control_fps():
        raise CollectError(f"control frames come at {default_control_fps()} per second, not "
                           f"{config.fps} (fix: fps={default_control_fps()}, or leave --fps out)")
    shard_dir = root / SHARD_DIR
    _check_plan(shard_dir, config)
    shards = plan_shards(config)
    todo = [s for s in shards if not (shard_dir / f"{s.id}.pkl").exists()]
    for stale in shard_dir.glob("*.tmp"):  # a killed worker's partial file
        stale.unlink()
    start = time.perf_counter()

    def done(i: int, _path: str) -> None:
        if on_shard is not None:
            on_shard(todo[i])

    run_jobs(run_shard, [(s, config, str(shard_dir)) for s in todo],
             workers=workers or os.cpu_count() or 1, ray_address=ray_address, on_done=done)
    seconds = time.perf_counter() - start
    summary = merge_shards(config, root, shards)
    summary.shards_run, summary.shards_resumed = len(todo), len(shards) - len(todo)
    summary.episodes_run = sum(len(s.seeds) for s in todo)
    summary.seconds = seconds
    return summary


def merge_shards(config: CollectConfig, root: Path, shards: Sequence[Shard]) -> CollectSummary:
    """Merge written shards, in plan order, into the dataset at ``root``."""
    from factask.datasets.lerobot import LeRobotWriter  # pyarrow: not in the workers

    shard_dir = root / SHARD_DIR
    env_width, factor_width = _widths(config)
    cameras: dict[str, tuple[int, int]] = {}
    if config.image_size is not None:
        w, h = config.image_size
        cameras = {name: (h, w) for name in ("front", "left", "right")}
    control = config.frames == "control"
    writer = LeRobotWriter(root, cameras, env_width, factor_width, fps=config.fps,
                           robot_type=config.robot, data_mb=config.data_mb,
                           video_mb=config.video_mb, control=control,
                           action_names=command_names(config.robot) if control else None)
    kept_seeds: list[int] = []
    try:
        for shard in shards:
            with open(shard_dir / f"{shard.id}.pkl", "rb") as fh:
                records: list[EpisodeRecord] = pickle.load(fh)
            for rec in records:
                if not (rec.success or config.keep_failed):
                    continue
                rel = f"states/episode_{len(writer.episodes):06d}.npz"
                write_states(root / rel, rec.states)
                writer.add_episode(rec, states_path=rel)
                kept_seeds.append(rec.seed)
    except BaseException:
        writer.abort()
        raise
    from factask.sim.render.cameras import ravens_cameras

    extra: dict[str, Any] = {"collect": asdict(config), "states_path":
                             "states/episode_{episode_index:06d}.npz"}
    if config.image_size is not None:
        extra["cameras"] = {c.name: {"position": list(c.position), "rotation": c.rotation,
                                     "fx": c.fx, "fy": c.fy, "cx": c.cx, "cy": c.cy,
                                     "width": c.width, "height": c.height}
                            for c in ravens_cameras(*config.image_size)}
    n = len(writer.episodes)
    writer.finalize(splits={config.split: f"0:{n}"}, extra=extra)
    shutil.rmtree(shard_dir)
    return CollectSummary(str(root), len(shards), 0, 0, 0, n, writer.frames, 0.0, kept_seeds)
