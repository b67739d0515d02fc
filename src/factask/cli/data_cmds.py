"""Dataset commands: ``collect`` (LeRobot v3.0 demonstrations) and ``replay``."""

from __future__ import annotations

import json
import os
from pathlib import Path

import typer
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from factask.cli.app import MAX_EPISODES, ROBOT_HELP, app, check_robot, make_console
from factask.vocabulary.errors import FactaskError

console = make_console()
err_console = make_console(stderr=True)

SIZE_HELP = "Camera image size WIDTHxHEIGHT (even numbers; Ravens' is 640x480)."


def _fail(message: str) -> typer.Exit:
    err_console.print(message, style="red", markup=False)
    return typer.Exit(2)


def parse_size(text: str) -> tuple[int, int]:
    """``WIDTHxHEIGHT`` -> (width, height); exit 2 when malformed."""
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise _fail(f"--size {text!r}: give WIDTHxHEIGHT, e.g. 160x120") from None
    if w <= 0 or h <= 0 or w % 2 or h % 2:
        raise _fail(f"--size {text!r}: both sides positive and even (H.264 4:2:0)")
    return w, h


@app.command()
def collect(
    tasks: list[str] = typer.Argument(None, help="Library task names, ids or graph files "
                                      "(or --suite)."),
    suite: str | None = typer.Option(None, "--suite", help="'all': every library task."),
    episodes: int = typer.Option(10, "--episodes", "-n", min=1, max=MAX_EPISODES,
                                 help="Seeds run per task (only successes are kept)."),
    split: str = typer.Option("train", "--split", help="train (seeds 0, 2, 4, ...), val (1, "
                              "3, ..., 9999) or test (10001, 10003, ...): disjoint."),
    robot: str = typer.Option("floating", "--robot", "-r", help=ROBOT_HELP),
    out: Path = typer.Option(..., "--out", "-o", help="Dataset folder (a killed run "
                             "resumes when started again with the same options)."),
    size: str = typer.Option("160x120", "--size", help=SIZE_HELP),
    no_video: bool = typer.Option(False, "--no-video", help="Record no camera video."),
    fps: int | None = typer.Option(None, "--fps", min=1, max=60, help="Frames per second "
                                   "of timestamps and videos (default: 1 for decision "
                                   "frames, the command rate (50) for control frames)."),
    frames: str = typer.Option("decision", "--frames", help="'decision': a frame per "
                               "action primitive, action = its 12 numbers (two poses x y z "
                               "yaw, lift, hinge x y, primitive code); 'control': a frame "
                               "per low-level command sample (50 Hz), action = the "
                               "command, with the decision's 12 numbers beside it."),
    keep_failed: bool = typer.Option(False, "--keep-failed", help="Keep failed episodes."),
    workers: int = typer.Option(0, "--workers", "-w", min=0, max=256,
                                help="Worker processes (0: the machine's cores)."),
    shard_size: int = typer.Option(10, "--shard-size", min=1, max=10_000,
                                   help="Seeds per shard (the unit of resumption)."),
    ray: str | None = typer.Option(None, "--ray", help="Run the shards on Ray: 'auto', "
                                   "'local' or a cluster address (pip install 'factask[ray]')."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON summary, nothing else."),
) -> None:
    """Record oracle demonstrations as a LeRobot v3.0 dataset, with a states file per episode."""
    from factask.datasets.control_frames import FRAME_MODES, default_control_fps
    from factask.datasets.layout import DEFAULT_FPS
    from factask.datasets.shards import CollectConfig, plan_shards
    from factask.datasets.shards import collect as run_collect
    from factask.datasets.splits import SPLITS
    from factask.library import task_names

    check_robot(robot)
    if split not in SPLITS:
        raise _fail(f"--split {split!r}: use one of {', '.join(SPLITS)}")
    names = list(tasks or [])
    if suite is not None:
        if suite != "all":
            raise _fail(f"--suite {suite!r}: the only suite is 'all'")
        names += task_names()
    if not names:
        raise _fail("give task names or --suite all")
    image_size = None if no_video else parse_size(size)
    if frames not in FRAME_MODES:
        raise _fail(f"--frames {frames!r}: use one of {', '.join(FRAME_MODES)}")
    if fps is None:
        fps = default_control_fps() if frames == "control" else DEFAULT_FPS
    config = CollectConfig(tasks=tuple(names), episodes=episodes, split=split, robot=robot,
                           image_size=image_size, fps=fps, keep_failed=keep_failed,
                           shard_size=shard_size, frames=frames)
    total = len(plan_shards(config))
    progress = Progress(TextColumn("[bold]shards"), BarColumn(), MofNCompleteColumn(),
                        TimeElapsedColumn(), console=err_console, disable=as_json,
                        transient=True)
    try:
        with progress:
            bar = progress.add_task("collect", total=total)
            summary = run_collect(config, out, workers=workers or os.cpu_count() or 1,
                                  ray_address=ray,
                                  on_shard=lambda _s: progress.advance(bar))
    except FactaskError as exc:
        raise _fail(str(exc)) from None
    result = summary.to_dict()
    if as_json:
        typer.echo(json.dumps(result))
        return
    console.print(f"{out}: {summary.episodes_kept} episodes, {summary.frames} frames "
                  f"({summary.shards_run} shards run, {summary.shards_resumed} resumed) in "
                  f"{summary.seconds:.1f} s, {summary.episodes_per_minute:.0f} episodes/min",
                  markup=False)


@app.command()
def replay(
    dataset: Path = typer.Argument(..., help="A dataset folder written by factask collect."),
    episode: int = typer.Option(0, "--episode", "-e", min=0, help="Episode index."),
    video: Path | None = typer.Option(None, "--video", help="Re-render the episode's frames "
                                      "into this .mp4 (front, left, right side by side; "
                                      "every command sample of a --frames control dataset)."),
    size: str = typer.Option("320x240", "--size", help=SIZE_HELP),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object, nothing else."),
) -> None:
    """Re-simulate an episode from its states file and check the states are bit-identical.

    Exit codes: 0 identical; 1 the states differ; 2 bad input.
    """
    import numpy as np

    from factask.datasets.replay import compare_states, render_states, resimulate
    from factask.datasets.states import read_states

    path = dataset / "states" / f"episode_{episode:06d}.npz"
    try:
        states = read_states(path)
        differences = compare_states(states, resimulate(states))
    except FactaskError as exc:
        raise _fail(str(exc)) from None
    written = None
    if video is not None:
        from factask.datasets.control_frames import default_control_fps
        from factask.sim.render.cameras import ravens_cameras
        from factask.sim.render.offscreen import VideoRecorder

        # A control-frame episode holds a state per command sample: its video at that rate.
        control = len(states.control_qpos) > 0
        frames = render_states(states, ravens_cameras(*parse_size(size)),
                               steps=None if control else range(states.steps + 1),
                               control=control)
        with VideoRecorder(video, fps=default_control_fps() if control else 2) as rec:
            for row in zip(*frames.values(), strict=True):
                rec.append(np.concatenate(row, axis=1))
        written = str(video)
    result = {"episode": episode, "seed": states.seed, "steps": states.steps,
              "identical": not differences, "differences": differences, "video": written}
    if as_json:
        typer.echo(json.dumps(result))
    else:
        verdict = "bit-identical" if not differences else "DIFFERENT: " + "; ".join(differences)
        console.print(f"episode {episode} (seed {states.seed}, {states.steps} actions): "
                      f"{verdict}" + (f"; video {written}" if written else ""), markup=False)
    raise typer.Exit(0 if not differences else 1)
