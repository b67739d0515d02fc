"""Commands on task-graph files: ``validate`` and ``schema``."""

from __future__ import annotations

import json
from pathlib import Path

import typer

from factask.cli.app import app, check_readable_file, make_console
from factask.graph import GraphValidationError, TaskGraph, parse_graph
from factask.vocabulary.errors import Problem, problem_lines

console = make_console()
err_console = make_console(stderr=True)


@app.command()
def validate(
    file: Path = typer.Argument(..., help="Task graph JSON file ('-' reads standard input)."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="Print nothing when valid."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object: file, valid, "
                                 "task, problems (node, field, message, fix)."),
) -> None:
    """Check a task-graph JSON file; exit 1 and list every problem if it is invalid
    (2 if it cannot be read)."""
    if str(file) != "-":
        check_readable_file(file)
    try:
        text = typer.get_text_stream("stdin").read() if str(file) == "-" else file.read_text()
    except OSError as exc:
        err_console.print(f"cannot read {file}: {exc.strerror or exc}", style="red",
                          markup=False)
        raise typer.Exit(2) from None
    except UnicodeDecodeError:
        _report(file, as_json, [Problem("", "", "not UTF-8 text", "a task graph is JSON")])
        raise typer.Exit(1) from None
    try:
        graph = parse_graph(text)
    except GraphValidationError as exc:
        _report(file, as_json, exc.problems)
        raise typer.Exit(1) from None
    if graph.task_problems():  # valid as a graph, but no task `run` would take
        _report(file, as_json, graph.task_problems())
        raise typer.Exit(1)
    if as_json:
        typer.echo(json.dumps({"file": str(file), "valid": True, "task": graph.name,
                               "problems": [], "order": graph.factor_order()}))
    elif not quiet:
        console.print(f"{file}: valid task {graph.name!r}: {len(graph.variables)} "
                      f"variable(s), {len(graph.factors)} factor(s), order "
                      f"{' -> '.join(graph.factor_order())}", markup=False, highlight=False)


def _report(file: Path, as_json: bool, problems: list[Problem]) -> None:
    """Print the problems of an invalid file (as a validation report lists them)."""
    if as_json:
        typer.echo(json.dumps({"file": str(file), "valid": False, "task": None,
                               "problems": [vars(p) for p in problems]}))
        return
    err_console.print(f"{file}: invalid ({len(problems)} problem(s))", style="red",
                      markup=False)
    for line in problem_lines(problems):
        err_console.print(line, markup=False, highlight=False)


@app.command()
def schema() -> None:
    """Print the JSON Schema of a task graph."""
    typer.echo(json.dumps(TaskGraph.json_schema(), indent=2))
