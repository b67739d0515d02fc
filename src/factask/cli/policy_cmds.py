"""``factask eval-policy``: a policy over tasks x test seeds, with 95 % intervals."""

from __future__ import annotations

import json
import os
from pathlib import Path

import typer
from rich.table import Table

from factask.cli.app import MAX_EPISODES, ROBOT_HELP, app, check_robot, make_console
from factask.vocabulary.errors import FactaskError

console = make_console()
err_console = make_console(stderr=True)


@app.command("eval-policy")
def eval_policy(
    policy: str = typer.Argument(..., help="'oracle', 'random', or module:callable (a "
                                 "function obs -> action, or an object with act(obs))."),
    tasks: list[str] = typer.Argument(None, help="Library task names, ids or graph files."),
    suite: str | None = typer.Option(None, "--suite", help="'all': every library task."),
    episodes: int = typer.Option(10, "--episodes", "-n", min=1, max=MAX_EPISODES,
                                 help="Seeds per task."),
    split: str = typer.Option("test", "--split", help="Seed split: train, val or test."),
    robot: str = typer.Option("floating", "--robot", "-r", help=ROBOT_HELP),
    obs_mode: str = typer.Option("state", "--obs-mode", help="state, rgbd or heightmap."),
    workers: int = typer.Option(0, "--workers", "-w", min=0, max=256,
                                help="Worker processes (0: the machine's cores)."),
    out: Path | None = typer.Option(None, "--out", "-o", help="Write one JSON line per "
                                    "episode here."),
    chart: Path | None = typer.Option(None, "--chart", help="Write a PNG bar chart of "
                                      "success at the end per task, with 95 % intervals."),
    video_dir: Path | None = typer.Option(None, "--video-dir", help="Write MP4s of the first "
                                          "--videos episodes of each task here."),
    videos: int = typer.Option(1, "--videos", min=0, max=MAX_EPISODES,
                               help="Episodes per task filmed (with --video-dir)."),
    ray: str | None = typer.Option(None, "--ray", help="Run the tasks on Ray: 'auto', "
                                   "'local' or a cluster address (pip install 'factask[ray]')."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object, nothing else."),
) -> None:
    """Evaluate a policy: success once, success at the end and mean total reward per task,
    each with a 95 % confidence interval (Wilson for rates)."""
    from factask.datasets.splits import SPLITS
    from factask.evaluation.policy import evaluate_policy
    from factask.library import task_names

    check_robot(robot)
    names = list(tasks or []) + (task_names() if suite == "all" else [])
    if suite not in (None, "all") or not names or split not in SPLITS:
        err_console.print("give task names or --suite all, and --split train, val or test",
                          style="red", markup=False)
        raise typer.Exit(2)
    try:
        outcomes, scores = evaluate_policy(
            policy, names, episodes, split=split, robot=robot, obs_mode=obs_mode,
            workers=workers or os.cpu_count(),
            video_dir=None if video_dir is None else str(video_dir), videos=videos,
            ray_address=ray)
    except FactaskError as exc:
        err_console.print(str(exc), style="red", markup=False)
        raise typer.Exit(2) from None
    if out is not None:
        out.parent.mkdir(parents=True, exist_ok=True)
        with open(out, "w") as fh:
            for o in outcomes:
                fh.write(json.dumps(o.__dict__) + "\n")
    if chart is not None:
        from factask.evaluation.policy_chart import plot_scores

        plot_scores(scores, chart, title=f"{policy} on {split} seeds ({episodes} per task)")
    if as_json:
        typer.echo(json.dumps({"policy": policy, "split": split,
                               "tasks": [s.to_dict() for s in scores],
                               "chart": None if chart is None else str(chart)}))
        return
    table = Table(title=f"{policy} on {split} seeds ({episodes} per task)")
    for col in ("task", "success once", "success at end", "mean reward"):
        table.add_column(col)
    for s in scores:
        table.add_row(s.task, f"{s.success_once:.0%} [{s.success_once_ci[0]:.0%}, "
                      f"{s.success_once_ci[1]:.0%}]",
                      f"{s.success_at_end:.0%} [{s.success_at_end_ci[0]:.0%}, "
                      f"{s.success_at_end_ci[1]:.0%}]",
                      f"{s.mean_reward:.3f} [{s.mean_reward_ci[0]:.3f}, "
                      f"{s.mean_reward_ci[1]:.3f}]")
    console.print(table)
