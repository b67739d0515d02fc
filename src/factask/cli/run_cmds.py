"""Commands that run the oracle: ``run``, ``eval-library`` and ``demo``."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import typer
from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table

from factask.cli.app import (
    CAMERA_HELP,
    JSON_HELP,
    MAX_EPISODES,
    MAX_SEED,
    ROBOT_HELP,
    TIME_LIMIT_HELP,
    app,
    check_camera,
    check_readable_file,
    check_robot,
    check_video,
    fail,
    make_console,
    parse_size,
)
from factask.graph import FactaskError, GraphValidationError, TaskGraph, parse_graph

console = make_console()
err_console = make_console(stderr=True)

def _progress(quiet: bool) -> Progress:
    return Progress(
        TextColumn("[bold]{task.description}"), BarColumn(), MofNCompleteColumn(),
        TimeElapsedColumn(), console=err_console, disable=quiet, transient=True,
    )


def load_task(spec: str, seed: int = 0) -> TaskGraph:
    """A task from a library name, a graph JSON file, or a CLIPort task file
    (see :func:`load_task_source`)."""
    return load_task_source(spec, seed)[0]


def load_task_source(spec: str, seed: int = 0,
                     time_limit: float | None = None) -> tuple[TaskGraph, Any]:
    """A task and, for a CLIPort task file, its import result (None otherwise).

    Args:
        spec: ``NAME`` (library), ``FILE.json``, ``FILE.py[:ClassName]`` or a LIBERO
            ``FILE.bddl``.
        seed: Seed for CLIPort task files (their ``reset`` samples poses).
        time_limit: Seconds a CLIPort task file's own code may run (``--time-limit``;
            None: the loader's default).

    Raises:
        typer.Exit: with code 2 and a message when the task cannot be loaded.
    """
    path_part, _, class_name = spec.partition(":") if ".py" in spec else (spec, "", "")
    if path_part.endswith((".py", ".json", ".bddl")):  # a file, not a library name
        check_readable_file(path_part)
    if path_part.endswith(".bddl"):
        from factask.cli.compat_cmds import load_libero_task

        return load_libero_task(path_part), None
    if path_part.endswith(".py"):
        from factask.compat.cliport import import_cliport

        try:
            limit = {} if time_limit is None else {"time_limit": time_limit}
            result = import_cliport(path_part, class_name or None, seed=seed, **limit)
        except FactaskError as exc:
            err_console.print(f"cannot import {spec}: {exc}", style="red", markup=False)
            raise typer.Exit(2) from None
        for warning in result.warnings:
            err_console.print(f"warning: {warning}", style="yellow", markup=False)
        return result.graph, result
    if spec.endswith(".json") or Path(spec).is_file():
        try:
            return parse_graph(Path(spec).read_text()), None
        except (OSError, UnicodeDecodeError) as exc:
            why = exc.strerror if isinstance(exc, OSError) else "not UTF-8 text"
            err_console.print(f"cannot read {spec}: {why or exc}", style="red", markup=False)
            raise typer.Exit(2) from None
        except GraphValidationError as exc:
            err_console.print(f"{spec}: invalid task graph\n{exc}", style="red", markup=False)
            raise typer.Exit(2) from None
    from factask.library import get_task
    from factask.library.tasks import UnknownTaskError

    try:
        return get_task(spec), None
    except UnknownTaskError as exc:
        err_console.print(str(exc), style="red", markup=False)
        raise typer.Exit(2) from None


def _episode_table(result: Any, ravens: list[Any] | None = None) -> Table:
    table = Table(title=f"{result.task}: success {result.success_rate:.0%} "
                  f"({'completed' if result.completed else 'not completed'})")
    cols = ["seed", "reward", "success", "actions", "failure"]
    if ravens:
        cols[3:3] = ["Ravens reward", "Ravens success"]
    for col in cols:
        table.add_column(col)
    for k, e in enumerate(result.episodes):
        row = [str(e.seed), f"{e.reward:.3f}", "yes" if e.success else "no", str(e.steps),
               escape(e.failure or "")]
        if ravens:
            row[3:3] = [f"{ravens[k].reward:.3f}", "yes" if ravens[k].success else "no"]
        table.add_row(*row)
    return table


def _episode_lines(result: Any, ravens: list[Any]) -> None:
    """The episodes as tab-separated lines with a header, then the summary line."""
    typer.echo("seed\treward\tsuccess\tactions" + ("\tRavens reward\tRavens success"
                                                   if ravens else "") + "\tfailure")
    for k, e in enumerate(result.episodes):
        extra = (f"\t{ravens[k].reward:.3f}\t{'yes' if ravens[k].success else 'no'}"
                 if ravens else "")
        typer.echo(f"{e.seed}\t{e.reward:.3f}\t{'yes' if e.success else 'no'}\t{e.steps}"
                   f"{extra}\t{' '.join((e.failure or '').split())}")
    typer.echo(f"{result.task}: success {result.success_rate:.0%} "
               f"({'completed' if result.completed else 'not completed'})")


def _attach(recording: Any, env: Any) -> None:
    """Attach a recording to ``env``; exit 2 if this machine cannot render."""
    from factask.sim.render.offscreen import RenderError

    try:
        recording.attach(env)
    except RenderError as exc:
        env.close()
        raise fail(f"--video: {exc}") from None


def _frame_size(text: str) -> tuple[int, int]:
    """``--size`` of a picture or video, within the scenes' offscreen buffer."""
    from factask.sim.build.mjcf import OFFSCREEN_SIZE

    return parse_size(text, OFFSCREEN_SIZE)


def _compile(graph: TaskGraph, robot: str, **kwargs: Any) -> Any:
    """The task's environment; exit 2 with the reason if it cannot be compiled."""
    from factask.sim.env import FactaskEnv

    try:
        return FactaskEnv(graph, robot=robot, **kwargs)
    except FactaskError as exc:
        raise fail(f"cannot compile {graph.name}: {exc}") from None


def _recording(video: Path, fps: float, size: tuple[int, int], camera: str,
               caption: bool) -> Any:
    """An :class:`~factask.viz.EpisodeVideo`; exit 2 if its options cannot be met."""
    from factask.sim.render.offscreen import RenderError
    from factask.viz import EpisodeVideo

    try:
        return EpisodeVideo(video, fps=fps, size=size, camera=camera, caption=caption)
    except RenderError as exc:
        raise fail(f"--video {video}: {exc}") from None


@app.command()
def run(
    task: str = typer.Argument(..., help="Library task name, graph FILE.json, LIBERO "
                               "FILE.bddl, or CLIPort FILE.py[:Class] (user code: it is "
                               "executed)."),
    episodes: int = typer.Option(1, "--episodes", "-n", min=1, max=MAX_EPISODES,
                                 help="Oracle episodes."),
    seed: int = typer.Option(0, "--seed", "-s", min=0, max=MAX_SEED,
                             help="First seed; episode k uses seed + k."),
    robot: str = typer.Option("floating", "--robot", "-r", help=ROBOT_HELP),
    video: Path | None = typer.Option(None, "--video", help="Write a video of the first "
                                      "episode: .mp4 (H.264) or .gif, by suffix."),
    fps: float = typer.Option(20.0, "--fps", min=1, max=50, help="Video frames per second "
                              "(smoother, not faster: one second shows 2.4 s of simulation)."),
    size: str = typer.Option("320x240", "--size", help="Video size WIDTHxHEIGHT."),
    camera: str = typer.Option("front", "--camera", help=CAMERA_HELP),
    caption: bool = typer.Option(False, "--caption", help="Caption the video with the "
                                 "current subtask, its language goal and its progress."),
    as_json: bool = typer.Option(False, "--json", help=JSON_HELP),
    ravens: bool = typer.Option(
        False, "--ravens", help="Also score every episode as Ravens does: goals in queue "
        "order (a task file's own goals; a graph's factors in order, each worth its "
        "weight), XY within pos_eps and yaw within rot_eps modulo symmetry (z ignored), "
        "a finished goal never re-checked, success at reward >= 0.99. Shown beside "
        "factask's own checks."),
    time_limit: float | None = typer.Option(None, "--time-limit", min=0.1, max=86_400,
                                            help=TIME_LIMIT_HELP),
) -> None:
    """Run the scripted oracle on a task and report reward and success per episode.

    An episode succeeds at total reward >= 0.99; the task is completed when at
    least half of its episodes succeed (factask's checks decide, also with --ravens).
    """
    from factask.compat.cliport.scoring import scored_episode
    from factask.sim.episode import TaskResult, run_episode

    check_robot(robot)
    check_video(video)
    frame_size = _frame_size(size)
    graph, source = load_task_source(task, seed, time_limit)
    env = _compile(graph, robot)
    recording = None
    if video is not None:
        check_camera(camera, env.model)
        recording = _recording(video, fps, frame_size, camera, caption)
    results = []
    scores: list[Any] = []
    video_info = None
    try:
        with _progress(as_json) as progress:
            bar = progress.add_task(f"{graph.name} ({robot})", total=episodes)
            for k in range(episodes):

                def show(i: int, planned: Any, info: dict[str, Any], k: int = k) -> None:
                    if as_json:
                        return
                    done = ", ".join(f"{n} {p:.0%}" for n, p in info["factors"].items())
                    progress.console.print(f"  seed {seed + k} action {i}: {planned.purpose}"
                                           f" -> reward {info['total_reward']:.2f} [{done}]",
                                           markup=False, highlight=False)

                if recording is not None and k == 0:
                    _attach(recording, env)  # the first episode only
                try:
                    if ravens:
                        episode, score = scored_episode(source or graph, seed + k, robot=robot,
                                                        env=env, on_action=show)
                        results.append(episode)
                        scores.append(score)
                    else:
                        results.append(run_episode(graph, seed + k, robot=robot, env=env,
                                                   on_action=show))
                finally:
                    if recording is not None and k == 0:
                        video_info = recording.finish()
                progress.advance(bar)
    finally:
        env.close()
    result = TaskResult(graph.name, results)
    if as_json:
        out = result.to_dict()
        if ravens:
            out["ravens"] = [{"seed": e.seed, "reward": sc.reward, "success": sc.success,
                              "goals_done": sc.goals_done,
                              "goals": len(source.goals) if source else len(graph.factors)}
                             for e, sc in zip(results, scores, strict=True)]
        if video_info is not None:
            out["video"] = video_info
        typer.echo(json.dumps(out))
    elif not console.is_terminal:  # piped: plain tab-separated lines, nothing cut
        _episode_lines(result, scores)
        if video is not None:
            typer.echo(f"video: {video}")
    else:
        console.print(_episode_table(result, scores))
        if video is not None:
            typer.echo(f"video: {video}")  # one line, never wrapped
    if not result.completed:
        raise typer.Exit(1)


@app.command("eval-library")
def eval_library(
    episodes: int = typer.Option(10, "--episodes", "-n", min=1, help="Episodes per task."),
    seed: int = typer.Option(0, "--seed", "-s", min=0, max=MAX_SEED, help="First seed."),
    robot: str = typer.Option("floating", "--robot", "-r", help=ROBOT_HELP),
    tasks: list[str] | None = typer.Option(None, "--task", "-t", help="Only these tasks "
                                           "(repeat -t, or give a comma-separated list)."),
    limit: int | None = typer.Option(None, "--limit", min=1, help="Only the first N tasks."),
    as_json: bool = typer.Option(False, "--json", help=JSON_HELP),
) -> None:
    """Run the oracle on every library task; print a table and the summary.

    The summary has tasks_total, tasks_completed and episode_success_rate. When
    stderr is not a terminal, progress is one line per task as it finishes.
    """
    from factask.library import task_names
    from factask.sim.episode import evaluate_task, summarize

    check_robot(robot)
    names = [n.strip() for t in tasks for n in t.split(",") if n.strip()] if tasks else (
        task_names())
    names = names[:limit] if limit else names
    # every name is checked before any episode runs: a typo in the last -t must not
    # cost the run of the others and then drop their table
    graphs = [load_task(name) for name in names]
    results = []
    lines = not as_json and not err_console.is_terminal
    with _progress(as_json or lines) as progress:
        bar = progress.add_task("library", total=len(names) * episodes)
        for k, (name, graph) in enumerate(zip(names, graphs, strict=True), 1):
            progress.update(bar, description=name)
            results.append(evaluate_task(graph, episodes, seed, robot,
                                         on_episode=lambda _r: progress.advance(bar)))
            if lines:
                done = results[-1]
                err_console.print(f"[{k}/{len(names)}] {name}: "
                                  f"{sum(e.success for e in done.episodes)}/{episodes} "
                                  "episodes succeeded", markup=False, highlight=False)
    summary = summarize(results)
    if as_json:
        typer.echo(json.dumps({"robot": robot, "episodes_per_task": episodes, **summary,
                               "tasks": [r.to_dict() for r in results]}))
    elif not console.is_terminal:  # piped: plain tab-separated lines, nothing cut
        typer.echo("task\tsuccess\tcompleted\tmean actions\tfailures")
        for r in results:
            fails = sorted({e.failure for e in r.episodes if e.failure})
            typer.echo(f"{r.task}\t{r.success_rate:.0%}\t{'yes' if r.completed else 'NO'}\t"
                       f"{sum(e.steps for e in r.episodes) / len(r.episodes):.1f}\t"
                       + " | ".join(" ".join(f.split()) for f in fails))
        typer.echo(f"tasks completed: {summary['tasks_completed']}/{summary['tasks_total']}, "
                   f"episode success rate: {summary['episode_success_rate']:.1%}")
    else:
        table = Table(title=f"oracle on the task library ({robot}, {episodes} episode(s) each)")
        for col in ("task", "success", "completed", "mean actions", "failures"):
            table.add_column(col)
        for r in results:
            fails = sorted({e.failure for e in r.episodes if e.failure})
            table.add_row(r.task, f"{r.success_rate:.0%}", "yes" if r.completed else "NO",
                          f"{sum(e.steps for e in r.episodes) / len(r.episodes):.1f}",
                          escape("; ".join(fails)[:80]))
        console.print(table)
        console.print(f"tasks completed: {summary['tasks_completed']}/{summary['tasks_total']}, "
                      f"episode success rate: {summary['episode_success_rate']:.1%}")
    if summary["tasks_completed"] < summary["tasks_total"]:
        raise typer.Exit(1)


@app.command()
def demo(
    out: Path = typer.Option(Path("out/demo"), "--out", help="Folder for the demo's files."),
    task: str = typer.Option("stack-block-pyramid", "--task", help="Library task name, graph "
                             "FILE.json, LIBERO FILE.bddl, or CLIPort FILE.py[:Class] (user "
                             "code: it is executed)."),
    robot: str = typer.Option("floating", "--robot", "-r", help=ROBOT_HELP),
    seed: int = typer.Option(0, "--seed", "-s", min=0, max=MAX_SEED),
    as_json: bool = typer.Option(False, "--json", help=JSON_HELP),
) -> None:
    """The main demo: a task's graph, then the oracle solving it, on a captioned video."""
    from factask.sim.episode import run_episode
    from factask.viz import draw_graph

    check_robot(robot)
    graph = load_task(task, seed)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise fail(f"--out {out}: cannot create the folder ({exc.strerror or exc})") from None
    quiet = Console(quiet=True)
    say = quiet if as_json else console  # --json: stdout holds the one object only
    say.rule(f"[bold]{escape(graph.name)}[/bold]: {escape(graph.description)}")
    table = Table(title="subtask factors, in order")
    for col in ("factor", "goal", "scope", "weight", "language goal"):
        table.add_column(col)
    for name in graph.factor_order():
        f = graph.factor(name)
        table.add_row(escape(name), f.goal.type, escape(", ".join(f.scope_names)),
                      f"{f.weight:.2f}", escape(f.description))
    say.print(table)
    graph_file = out / f"{graph.name}.json"
    graph_file.write_text(graph.to_json())
    picture = draw_graph(graph, out / f"{graph.name}-graph.png", title=graph.name)
    say.print(f"graph picture: {picture}", markup=False, highlight=False)

    width = max(len(n) for n in graph.factor_names())

    def show(i: int, planned: Any, info: dict[str, Any]) -> None:
        say.print(f"action {i:2d}: {planned.purpose} -> total reward "
                  f"{info['total_reward']:.2f}", markup=False, highlight=False)
        for n, p in info["factors"].items():
            bar = "#" * round(p * 20)
            say.print(f"    {n:<{width}} |{bar:<20}| {p:4.0%}", markup=False, highlight=False)

    env = _compile(graph, robot)
    recording = _recording(out / f"{graph.name}.gif", 20.0, (320, 240), "front", True)
    _attach(recording, env)
    try:
        with say.status(f"running the oracle ({robot})..."):
            result = run_episode(graph, seed, robot=robot, env=env, on_action=show)
    finally:
        video_info = recording.finish()
        env.close()
    episode_file = out / "episode.json"
    episode_file.write_text(json.dumps(result.to_dict(), indent=2))
    if as_json:
        typer.echo(json.dumps({"task": graph.name, "robot": robot, "seed": seed,
                               "graph": str(graph_file), "picture": str(picture),
                               "video": video_info, "episode_file": str(episode_file),
                               "episode": result.to_dict()}))
    else:
        typer.echo(f"video: {video_info['path']}")  # one line, never wrapped
        status = ("[green]success[/green]" if result.success
                  else f"[red]failed[/red]: {escape(result.failure or '')}")
        console.print(f"episode: reward {result.reward:.3f} in {result.steps} actions — {status}")
    if not result.success:
        raise typer.Exit(1)


@app.command()
def render(
    task: str = typer.Argument(..., help="Library task name, graph FILE.json, or CLIPort "
                               "FILE.py[:Class] (user code: it is executed), or LIBERO FILE.bddl."),
    out: Path = typer.Option(..., "--out", "-o", help="PNG file to write."),
    solved: bool = typer.Option(False, "--solved", help="Draw the oracle's end state "
                                "instead of the reset scene."),
    camera: str = typer.Option("front", "--camera", help=CAMERA_HELP),
    size: str = typer.Option("640x480", "--size", help="Image size WIDTHxHEIGHT."),
    seed: int = typer.Option(0, "--seed", "-s", min=0, max=MAX_SEED),
    robot: str = typer.Option("floating", "--robot", "-r", help=ROBOT_HELP),
    markers: bool = typer.Option(True, "--markers/--no-markers",
                                 help="Draw the translucent goal markers."),
    segmentation: bool = typer.Option(False, "--segmentation", help="Draw the objects' "
                                      "segmentation instead: each variable in a colour of its "
                                      "own, the same in every run."),
    as_json: bool = typer.Option(False, "--json", help=JSON_HELP),
) -> None:
    """Draw a still of a task's scene: at reset, or solved by the oracle."""
    from factask.sim.episode import run_episode
    from factask.sim.render.offscreen import (
        VIEWS,
        RenderError,
        SceneRenderer,
        colorize_segmentation,
        framed_camera,
    )

    check_robot(robot)
    if out.suffix.lower() != ".png":
        raise fail(f"--out {out}: give a .png file")
    width, height = _frame_size(size)
    graph = load_task(task, seed)
    env = _compile(graph, robot)
    check_camera(camera, env.model)
    try:
        episode = None
        if solved:
            episode = run_episode(graph, seed, robot=robot, env=env)
        else:
            env.reset(seed=seed)
        view = (framed_camera(env.model, env.data, camera, width / height)
                if camera in VIEWS else camera)
        with SceneRenderer(env.model, width, height, env.scene.geom_object) as renderer:
            if segmentation:
                objects = [(env.objects[n].variable, env.objects[n].index)
                           for n in env.object_names]
                image = colorize_segmentation(renderer.segmentation(env.data, view), objects)
            else:
                image = renderer.rgb(env.data, view, show_markers=markers)
    except RenderError as exc:
        raise fail(f"cannot render: {exc}") from None
    finally:
        env.close()
    import imageio.v3 as iio

    out.parent.mkdir(parents=True, exist_ok=True)
    iio.imwrite(out, image)
    state = "reset" if episode is None else "solved"
    if as_json:
        typer.echo(json.dumps({
            "task": graph.name, "out": str(out), "size": [width, height], "camera": camera,
            "seed": seed, "robot": robot, "state": state,
            "image": "segmentation" if segmentation else "rgb",
            "episode": episode.to_dict() if episode is not None else None}))
    else:
        if episode is not None:
            state = f"solved: reward {episode.reward:.2f}, success {episode.success}"
        console.print(f"wrote {out} ({width}x{height}, {camera} camera, seed {seed}, {state})",
                      markup=False, highlight=False)
    if episode is not None and not episode.success:
        raise typer.Exit(1)
