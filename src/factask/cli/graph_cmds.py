"""Commands on task-graph files: ``validate`` and ``schema``."""

from __future__ import annotations

import json
from pathlib import Path

import typer
from rich.console import Console

from factask.cli.app import app
from factask.model import GraphValidationError, TaskGraph, parse_graph

console = Console()
err_console = Console(stderr=True, soft_wrap=True)


@app.command()
def validate(
    file: Path = typer.Argument(..., help="Task graph JSON file ('-' reads standard input)."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="Print nothing when valid."),
) -> None:
    """Check a task-graph JSON file; exit 1 and list every problem if it is invalid."""
    try:
        text = typer.get_text_stream("stdin").read() if str(file) == "-" else file.read_text()
    except OSError as exc:
        err_console.print(f"cannot read {file}: {exc.strerror or exc}", style="red",
                          markup=False)
        raise typer.Exit(2) from None
    except UnicodeDecodeError:
        err_console.print(f"{file}: invalid (not UTF-8 text; a task graph is JSON)",
                          style="red", markup=False)
        raise typer.Exit(1) from None
    try:
        graph = parse_graph(text)
    except GraphValidationError as exc:
        err_console.print(f"{file}: invalid ({len(exc.problems)} problem(s))", style="red",
                          markup=False)
        for p in exc.problems:
            err_console.print(f"  - {p}", markup=False, highlight=False)
        raise typer.Exit(1) from None
    if not quiet:
        console.print(
            f"[green]{file}: valid[/green] task {graph.name!r}: "
            f"{len(graph.variables)} variable(s), {len(graph.factors)} factor(s), "
            f"order {' -> '.join(graph.factor_order())}"
        )


@app.command()
def schema() -> None:
    """Print the JSON Schema of a task graph."""
    typer.echo(json.dumps(TaskGraph.json_schema(), indent=2))
