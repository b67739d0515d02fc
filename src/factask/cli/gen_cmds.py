"""Commands of LLM generation: ``generate`` and ``benchmark``.

litellm and MuJoCo are imported only when a command runs.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import typer
from rich.console import Console

from factask.cli.app import ROBOT_HELP, app, check_robot

if TYPE_CHECKING:
    from factask.gen.strategies import Generator

console = Console(highlight=False)
err_console = Console(stderr=True, soft_wrap=True, highlight=False)

_APPROACH_HELP = "one-shot (baseline), variables-first (approach 1) or subtasks-first (approach 2)"


def _make_generator(model: str | None, api_base: str | None, cache: Path | None,
                    max_repairs: int, episodes: int, memory: Path | None, robot: str,
                    temperature: float | None, on_step: Any = None) -> Generator:
    """Build the client, verifier, memory and generator from options + environment."""
    check_robot(robot)
    from factask.gen.llm import LLMClient, LLMConfig, LLMConfigError, ResponseCache
    from factask.gen.memory import SubtaskMemory
    from factask.gen.strategies import Generator as _Generator
    from factask.gen.verify import Verifier

    try:
        config = LLMConfig.from_env(model=model, api_base=api_base, temperature=temperature)
    except LLMConfigError as exc:
        err_console.print(f"[red]{exc}[/red]")
        raise typer.Exit(2) from None
    cache_dir = cache or (Path(os.environ["FACTASK_CACHE"]) if os.environ.get("FACTASK_CACHE")
                          else None)
    client = LLMClient(config, ResponseCache(cache_dir) if cache_dir else None)
    verifier = Verifier(episodes=episodes, robot=robot)
    return _Generator(client, verifier, SubtaskMemory.from_env(memory), max_repairs, on_step)


def _print_step(rec: Any) -> None:
    mark = "[green]ok[/green]" if rec.ok else "[red]failed[/red]"
    cached = " [dim](cached)[/dim]" if rec.cached else ""
    console.print(f"  {rec.step} attempt {rec.attempt}: {mark}, level "
                  f"[bold]{rec.level}[/bold]{cached}")
    if rec.feedback:
        for line in rec.feedback.splitlines()[:12]:
            console.print(f"      {line}", markup=False)


@app.command()
def generate(
    proposal: str = typer.Argument(..., help="Task proposal: 'task-name: description' or text."),
    approach: str = typer.Option("variables-first", "--approach", "-a", help=_APPROACH_HELP),
    model: str = typer.Option(None, "--model", "-m",
                              help="litellm model, e.g. openai/gpt-4o (default $FACTASK_MODEL)."),
    api_base: str = typer.Option(None, "--api-base", help="API base URL ($FACTASK_API_BASE)."),
    out: Path = typer.Option(None, "--out", "-o", help="Graph file (default <task>.json)."),
    cache: Path = typer.Option(None, "--cache", help="LLM answer cache dir ($FACTASK_CACHE)."),
    max_repairs: int = typer.Option(3, "--max-repairs", min=0, help="Repairs per step."),
    episodes: int = typer.Option(3, "--episodes", min=1, help="Oracle episodes (completion)."),
    memory: Path = typer.Option(None, "--memory", help="Subtask memory dir ($FACTASK_MEMORY)."),
    robot: str = typer.Option("floating", "--robot", help=f"{ROBOT_HELP} Runs the oracle "
                              "episodes of the completion check."),
    temperature: float = typer.Option(None, "--temperature", help="($FACTASK_TEMPERATURE)"),
) -> None:
    """Generate a task graph with an LLM, verify it, write it; exit 0 iff completion reached."""
    from factask.gen.llm import LLMAuthError
    from factask.gen.results import APPROACHES

    if approach not in APPROACHES:
        err_console.print(f"[red]unknown approach {approach!r}; use {', '.join(APPROACHES)}")
        raise typer.Exit(2)
    gen = _make_generator(model, api_base, cache, max_repairs, episodes, memory, robot,
                          temperature, _print_step)
    console.print(f"[bold]generate[/bold] ({approach}, {gen.client.config.model}): "
                  f"{proposal}")
    try:
        result = gen.generate(proposal, approach)
    except LLMAuthError as exc:
        err_console.print(f"[red]the LLM provider refused the credentials: {exc}[/red]")
        raise typer.Exit(2) from None
    if result.graph is not None:
        path = out or Path(f"{result.task}.json")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(result.graph.to_json())
        console.print(f"graph written to {path}")
    u = result.usage
    console.print(f"level reached: [bold]{result.level_reached}[/bold]; {u.calls} call(s) "
                  f"({u.cached_calls} cached), {u.total_tokens} tokens, ${u.cost_usd:.4f}")
    if result.failure:
        console.print(f"[yellow]failure:[/yellow] {result.failure.splitlines()[0]}")
    raise typer.Exit(0 if result.completed else 1)


@app.command()
def benchmark(
    approach: list[str] = typer.Option(["all"], "--approach", "-a",
                                       help=f"{_APPROACH_HELP}, repeatable, or 'all'."),
    model: str = typer.Option(None, "--model", "-m", help="litellm model ($FACTASK_MODEL)."),
    api_base: str = typer.Option(None, "--api-base", help="API base URL ($FACTASK_API_BASE)."),
    tasks: Path = typer.Option(None, "--tasks",
                               help="Task list JSON (default ../shared/data/gensim_tasks.json)."),
    limit: int = typer.Option(None, "--limit", min=1, help="Only the first N tasks."),
    out: Path = typer.Option(..., "--out", "-o", help="Run directory (resumed if it exists)."),
    cache: Path = typer.Option(None, "--cache",
                               help="LLM cache dir (default $FACTASK_CACHE, else RUN_DIR/cache)."),
    max_repairs: int = typer.Option(3, "--max-repairs", min=0, help="Repairs per step."),
    episodes: int = typer.Option(3, "--episodes", min=1, help="Oracle episodes (completion)."),
    memory: Path = typer.Option(None, "--memory", help="Subtask memory dir ($FACTASK_MEMORY)."),
    robot: str = typer.Option("floating", "--robot", help=f"{ROBOT_HELP} Runs the oracle "
                              "episodes of the completion check."),
    temperature: float = typer.Option(None, "--temperature", help="($FACTASK_TEMPERATURE)"),
) -> None:
    """Run a task list through generation + verification; write JSONL, summary, chart."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn

    from factask.evaluation.benchmark import (
        RESULTS_FILE,
        BenchmarkError,
        default_tasks_path,
        finished_pairs,
        load_tasks,
        read_results,
        run_benchmark,
        summary_table,
    )
    from factask.gen.llm import LLMAuthError
    from factask.gen.results import APPROACHES

    approaches: list[str] = []
    for a in approach:
        for item in (APPROACHES if a == "all" else (a,)):
            if item not in APPROACHES:
                err_console.print(f"[red]unknown approach {item!r}; use "
                                  f"{', '.join(APPROACHES)} or all[/red]")
                raise typer.Exit(2)
            if item not in approaches:
                approaches.append(item)
    tasks_path = tasks or default_tasks_path()
    try:
        task_list = load_tasks(tasks_path)
    except BenchmarkError as exc:
        err_console.print(f"[red]{exc}[/red]")
        raise typer.Exit(2) from None
    if limit:
        task_list = task_list[:limit]
    cache_dir = cache or (Path(os.environ["FACTASK_CACHE"]) if os.environ.get("FACTASK_CACHE")
                          else out / "cache")
    gen = _make_generator(model, api_base, cache_dir, max_repairs, episodes,
                          memory, robot, temperature)
    done = finished_pairs(read_results(out / RESULTS_FILE))
    total = len(task_list) * len(approaches)
    already = sum(1 for t in task_list for a in approaches if (a, t.name) in done)
    if already:
        console.print(f"resuming {out}: {already} of {total} pair(s) already finished")
    with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                  console=console) as progress:
        bar = progress.add_task("benchmark", total=total, completed=already)

        def on_start(a: str, t: Any) -> None:
            progress.update(bar, description=f"{a} {t.name}")

        def on_result(record: dict[str, Any]) -> None:
            progress.advance(bar)
            progress.console.print(f"  {record['approach']:<16} {record['task']:<40} "
                                   f"{record['status']:<15} {record.get('level_reached')}",
                                   markup=False)

        try:
            summary = run_benchmark(task_list, approaches, gen, out, on_start, on_result,
                                    meta={"model": gen.client.config.model,
                                          "tasks_file": str(tasks_path),
                                          "episodes": episodes, "max_repairs": max_repairs})
        except BenchmarkError as exc:
            err_console.print(f"[red]{exc}[/red]")
            raise typer.Exit(2) from None
        except LLMAuthError as exc:
            err_console.print(f"[red]the LLM provider refused the credentials; the run "
                              f"stopped (finished pairs are kept): {exc}[/red]")
            raise typer.Exit(2) from None
    console.print(summary_table(summary), markup=False)
    console.print(f"results: {out / RESULTS_FILE}; summary: {out / 'summary.json'}, "
                  f"{out / 'summary.md'}; chart: {out / 'rates.png'}")
