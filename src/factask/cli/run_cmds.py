"""Commands that run the oracle: ``run``, ``eval-library`` and ``demo``."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import typer
from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table

from factask.cli.app import MAX_EPISODES, MAX_SEED, ROBOT_HELP, app, check_robot, check_video
from factask.model import FactaskError, GraphValidationError, TaskGraph, parse_graph

console = Console()
err_console = Console(stderr=True, soft_wrap=True)

def _progress(quiet: bool) -> Progress:
    return Progress(
        TextColumn("[bold]{task.description}"), BarColumn(), MofNCompleteColumn(),
        TimeElapsedColumn(), console=err_console, disable=quiet, transient=True,
    )


def load_task(spec: str, seed: int = 0) -> TaskGraph:
    """A task from a library name, a graph JSON file, or a CLIPort task file
    (see :func:`load_task_source`)."""
    return load_task_source(spec, seed)[0]


def load_task_source(spec: str, seed: int = 0) -> tuple[TaskGraph, Any]:
    """A task and, for a CLIPort task file, its import result (None otherwise).

    Args:
        spec: ``NAME`` (library), ``FILE.json``, or ``FILE.py[:ClassName]``.
        seed: Seed for CLIPort task files (their ``reset`` samples poses).

    Raises:
        typer.Exit: with code 2 and a message when the task cannot be loaded.
    """
    path_part, _, class_name = spec.partition(":") if ".py" in spec else (spec, "", "")
    if path_part.endswith(".py"):
        from factask.compat.cliport import import_cliport

        try:
            result = import_cliport(path_part, class_name or None, seed=seed)
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
               e.failure or ""]
        if ravens:
            row[3:3] = [f"{ravens[k].reward:.3f}", "yes" if ravens[k].success else "no"]
        table.add_row(*row)
    return table


@app.command()
def run(
    task: str = typer.Argument(..., help="Library task name, graph FILE.json, or "
                               "CLIPort FILE.py[:Class] (user code: it is executed)."),
    episodes: int = typer.Option(1, "--episodes", "-n", min=1, max=MAX_EPISODES,
                                 help="Oracle episodes."),
    seed: int = typer.Option(0, "--seed", "-s", min=0, max=MAX_SEED,
                             help="First seed; episode k uses seed + k."),
    robot: str = typer.Option("floating", "--robot", "-r", help=ROBOT_HELP),
    video: Path | None = typer.Option(None, "--video", help="Write a video of the first "
                                      "episode: .mp4 (H.264) or .gif, by suffix."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object, nothing else."),
    ravens: bool = typer.Option(
        False, "--ravens", help="Also score every episode as Ravens does: goals in queue "
        "order (a task file's own goals; a graph's factors in order, each worth its "
        "weight), XY within pos_eps and yaw within rot_eps modulo symmetry (z ignored), "
        "a finished goal never re-checked, success at reward >= 0.99. Shown beside "
        "factask's own checks."),
) -> None:
    """Run the scripted oracle on a task and report reward and success per episode.

    An episode succeeds at total reward >= 0.99; the task is completed when at
    least half of its episodes succeed (factask's checks decide, also with --ravens).
    """
    from factask.compat.cliport.scoring import scored_episode
    from factask.sim.env import FactaskEnv
    from factask.sim.episode import TaskResult, run_episode

    check_robot(robot)
    check_video(video)
    graph, source = load_task_source(task, seed)
    try:
        env = FactaskEnv(graph, robot=robot)
    except FactaskError as exc:
        err_console.print(f"cannot compile {graph.name}: {exc}", style="red", markup=False)
        raise typer.Exit(2) from None
    results = []
    scores: list[Any] = []
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

                if ravens:
                    episode, score = scored_episode(source or graph, seed + k, robot=robot,
                                                    env=env, on_action=show,
                                                    video=video if k == 0 else None)
                    results.append(episode)
                    scores.append(score)
                else:
                    results.append(run_episode(graph, seed + k, robot=robot, env=env,
                                               video=video if k == 0 else None,
                                               on_action=show))
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
        typer.echo(json.dumps(out))
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
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object, nothing else."),
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
    results = []
    lines = not as_json and not err_console.is_terminal
    with _progress(as_json or lines) as progress:
        bar = progress.add_task("library", total=len(names) * episodes)
        for k, name in enumerate(names, 1):
            graph = load_task(name)
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
                          "; ".join(fails)[:80])
        console.print(table)
        console.print(f"tasks completed: {summary['tasks_completed']}/{summary['tasks_total']}, "
                      f"episode success rate: {summary['episode_success_rate']:.1%}")
    if summary["tasks_completed"] < summary["tasks_total"]:
        raise typer.Exit(1)


@app.command()
def demo(
    out: Path = typer.Option(Path("out/demo"), "--out", help="Folder for the demo's files."),
    task: str = typer.Option("stack-block-pyramid", "--task", help="Library task to show."),
    robot: str = typer.Option("floating", "--robot", "-r", help=ROBOT_HELP),
    seed: int = typer.Option(0, "--seed", "-s", min=0, max=MAX_SEED),
) -> None:
    """The main demo: a library task's graph, then the oracle solving it, on video."""
    from factask.sim.episode import run_episode
    from factask.viz import draw_graph

    check_robot(robot)
    graph = load_task(task)
    out.mkdir(parents=True, exist_ok=True)
    console.rule(f"[bold]{graph.name}[/bold]: {graph.description}")
    table = Table(title="subtask factors, in order")
    for col in ("factor", "goal", "scope", "weight", "language goal"):
        table.add_column(col)
    for name in graph.factor_order():
        f = graph.factor(name)
        table.add_row(name, f.goal.type, ", ".join(f.scope_names), f"{f.weight:.2f}",
                      f.description)
    console.print(table)
    (out / f"{graph.name}.json").write_text(graph.to_json())
    picture = draw_graph(graph, out / f"{graph.name}-graph.png", title=graph.name)
    console.print(f"graph picture: {picture}")

    width = max(len(n) for n in graph.factor_names())

    def show(i: int, planned: Any, info: dict[str, Any]) -> None:
        console.print(f"action {i:2d}: {planned.purpose} -> total reward "
                      f"{info['total_reward']:.2f}", markup=False, highlight=False)
        for n, p in info["factors"].items():
            bar = "#" * round(p * 20)
            console.print(f"    {n:<{width}} |{bar:<20}| {p:4.0%}", markup=False,
                          highlight=False)

    with console.status(f"running the oracle ({robot})..."):
        result = run_episode(graph, seed, robot=robot, video=out / f"{graph.name}.gif",
                             on_action=show)
    (out / "episode.json").write_text(json.dumps(result.to_dict(), indent=2))
    console.print(f"video: {out / (graph.name + '.gif')}")
    status = "[green]success[/green]" if result.success else f"[red]failed[/red]: {result.failure}"
    console.print(f"episode: reward {result.reward:.3f} in {result.steps} actions — {status}")
    if not result.success:
        sys.exit(1)


def _size(text: str) -> tuple[int, int]:
    """``WxH`` -> (width, height); exit 2 on anything else."""
    w, sep, h = text.lower().partition("x")
    if not (sep and w.isdigit() and h.isdigit() and 16 <= int(w) <= 4096
            and 16 <= int(h) <= 4096):
        err_console.print(f"--size {text}: give WIDTHxHEIGHT, each 16 to 4096 (e.g. 640x480)",
                          style="red", markup=False)
        raise typer.Exit(2)
    return int(w), int(h)


@app.command()
def render(
    task: str = typer.Argument(..., help="Library task name, graph FILE.json, or CLIPort "
                               "FILE.py[:Class] (user code: it is executed)."),
    out: Path = typer.Option(..., "--out", "-o", help="PNG file to write."),
    solved: bool = typer.Option(False, "--solved", help="Draw the oracle's end state "
                                "instead of the reset scene."),
    camera: str = typer.Option("front", "--camera", help="Camera: front or top."),
    size: str = typer.Option("640x480", "--size", help="Image size WIDTHxHEIGHT."),
    seed: int = typer.Option(0, "--seed", "-s", min=0, max=MAX_SEED),
    robot: str = typer.Option("floating", "--robot", "-r", help=ROBOT_HELP),
    markers: bool = typer.Option(True, "--markers/--no-markers",
                                 help="Draw the translucent goal markers."),
) -> None:
    """Draw a still of a task's scene: at reset, or solved by the oracle."""
    from factask.sim.env import FactaskEnv
    from factask.sim.episode import run_episode

    check_robot(robot)
    if out.suffix.lower() != ".png":
        err_console.print(f"--out {out}: give a .png file", style="red", markup=False)
        raise typer.Exit(2)
    if camera not in ("front", "top"):
        err_console.print(f"--camera {camera}: use front or top", style="red", markup=False)
        raise typer.Exit(2)
    width, height = _size(size)
    graph = load_task(task, seed)
    env = FactaskEnv(graph, robot=robot, render_size=(width, height), camera=camera)
    try:
        episode = None
        if solved:
            episode = run_episode(graph, seed, robot=robot, env=env)
        else:
            env.reset(seed=seed)
        image = env.render_rgb(markers=markers)
    finally:
        env.close()
    import imageio.v3 as iio

    out.parent.mkdir(parents=True, exist_ok=True)
    iio.imwrite(out, image)
    state = "reset" if episode is None else (
        f"solved: reward {episode.reward:.2f}, success {episode.success}")
    console.print(f"wrote {out} ({width}x{height}, {camera} camera, seed {seed}, {state})",
                  markup=False, highlight=False)
    if episode is not None and not episode.success:
        raise typer.Exit(1)
