"""Commands on the task library: ``list`` and ``show``.

Kept light: the library and the graph model only (matplotlib is imported only
when ``show --png`` draws; MuJoCo never).
"""

from __future__ import annotations

import json
from pathlib import Path

import typer
from rich.markup import escape
from rich.table import Table

from factask.cli.app import app, fail, make_console
from factask.graph import SubtaskFactor, TaskGraph
from factask.library import UnknownTaskError, get_task, list_tasks, task_names
from factask.library.tags import matches_tags, reuse_stats
from factask.vocabulary.errors import quote

console = make_console()
err_console = make_console(stderr=True)


@app.command("list")
def list_cmd(
    as_json: bool = typer.Option(False, "--json", help="Print a JSON list instead of a table."),
    tag: list[str] = typer.Option(
        [], "--tag", help="Only tasks with this tag (repeat or comma-separate: all must "
        "match); a bare value matches any prefix, e.g. stacking = family:stacking."),
    stats: bool = typer.Option(False, "--stats", help="Also print the subtask-reuse figure "
                               "(factors built from shared templates / all factors)."),
) -> None:
    """List the library's tasks with their sizes, templates and tags."""
    wanted = [t.strip() for item in tag for t in item.split(",") if t.strip()]
    infos = [i for i in list_tasks() if matches_tags(i.tags, wanted)]
    if as_json:
        typer.echo(json.dumps([i.to_dict() for i in infos], indent=2))
        if stats:
            typer.echo(_stats_text(), err=True)
        return
    if not console.is_terminal:  # piped: plain tab-separated lines, nothing cut
        typer.echo("task\tvars\tfactors\tmovable\ttemplates\ttags")
        for i in infos:
            typer.echo(f"{i.name}\t{i.n_variables}\t{i.n_factors}\t{i.n_movable}\t"
                       + ",".join(i.templates) + "\t" + ",".join(i.tags))
    else:
        table = Table(title=f"factask library: {len(infos)} tasks")
        table.add_column("task", style="bold")
        table.add_column("vars", justify="right")
        table.add_column("factors", justify="right")
        table.add_column("movable", justify="right")
        table.add_column("templates")
        table.add_column("tags")
        for i in infos:
            table.add_row(escape(i.name), str(i.n_variables), str(i.n_factors),
                          str(i.n_movable), ", ".join(i.templates), escape(", ".join(i.tags)))
        console.print(table)
    if stats:
        typer.echo(_stats_text())


def _stats_text() -> str:
    """The reuse figure of the whole library (whatever --tag listed), then one line
    per template."""
    st = reuse_stats({name: get_task(name) for name in task_names()})
    lines = [f"tasks: {st.tasks}, factors: {st.factors}, built from shared templates: "
             f"{st.shared} ({100 * st.reuse:.1f} % subtask reuse)"]
    for name, (tasks, factors) in sorted(st.per_template.items(), key=lambda kv: -kv[1][1]):
        lines.append(f"  {name}: {factors} factors in {tasks} tasks")
    return "\n".join(lines)


def _goal_text(f: SubtaskFactor) -> str:
    """One-line summary of a factor's goal relation, e.g. ``on(objects=[a], support=b)``."""
    data = f.goal.model_dump(mode="json", exclude_none=True, exclude_defaults=True)
    data.pop("type", None)
    parts = [f"objects={f.goal.objects}"]
    parts += [f"{k}={v}" for k, v in data.items() if k != "objects"]
    return f"{f.goal.type}({', '.join(parts)})"


def _start_text(graph: TaskGraph, name: str) -> str:
    """Where a variable starts, in a few words."""
    init = graph.variable(name).initial
    data = init.model_dump(mode="json")
    if init.type == "table":
        return "free spot"
    if init.type == "on":
        return f"on {data['support']}"
    if init.type == "inside":
        return f"inside {data['container']}"
    if init.type == "pose":
        return f"at ({data['x']:g}, {data['y']:g}), yaw {data['yaw_deg']:g}"
    return f"region x{tuple(data['x'])} y{tuple(data['y'])}"


def _print_graph(graph: TaskGraph) -> None:
    """Pretty print: description, variables table, factors in order with goals."""
    console.print(f"[bold]{escape(graph.name)}[/bold]", highlight=False)
    if graph.description:
        console.print(graph.description, highlight=False, markup=False)
    vt = Table(title="state variables", title_justify="left", show_lines=False)
    vt.add_column("name", style="bold", no_wrap=True)
    vt.add_column("kind", no_wrap=True)
    vt.add_column("size (m)", no_wrap=True)
    vt.add_column("colour", no_wrap=True)
    vt.add_column("starts", overflow="fold")
    for v in graph.variables:
        kind = v.kind + (f" x{v.count}" if v.count > 1 else "") + (" (fixed)" if v.is_fixed
                                                                    else "")
        vt.add_row(escape(v.name), kind, "x".join(f"{s:g}" for s in v.extents), v.color,
                   escape(_start_text(graph, v.name)))
    console.print(vt)
    order = graph.factor_order()
    dep = graph.dependency_graph()
    console.print("[bold]subtask factors, in order[/bold]")
    for i, name in enumerate(order, 1):
        f = graph.factor(name)
        before = [str(order.index(p) + 1) for p in sorted(dep.predecessors(name),
                                                          key=order.index)]
        after = f", after {', '.join(before)}" if before else ""
        tpl = f", template {f.template}" if f.template else ""
        kind = ", milestone" if f.milestone else ""
        console.print(f"  {i}. [bold]{escape(name)}[/bold] "
                      + escape(f"(weight {f.weight:.3f}{kind}{after}{tpl})"),
                      highlight=False)
        console.print(f"     goal: {_goal_text(f)}", highlight=False, markup=False)
        console.print(f"     \"{f.description}\"", highlight=False, markup=False)
        if f.initial_setup:
            console.print(f"     needs: {f.initial_setup}", highlight=False, markup=False)
    console.print(f"order: {' -> '.join(order)}", highlight=False, markup=False)
    if graph.milestones():
        console.print("milestones count once reached, in this order; the other factors "
                      "must hold at the end", highlight=False)


@app.command()
def show(
    task: str = typer.Argument(..., help="Library task name (see `factask list`), graph "
                               "FILE.json (from generate, import-cliport, ...), or CLIPort "
                               "FILE.py[:Class] (user code: it is executed), or LIBERO FILE.bddl."),
    as_json: bool = typer.Option(False, "--json",
                                 help="Print the graph JSON (what `factask validate` reads)."),
    png: Path | None = typer.Option(None, "--png", help="Also draw the graph to this PNG."),
) -> None:
    """Show a task: variables, factors, their order and language goals."""
    if png is not None and png.suffix.lower() != ".png":  # refused before any work
        raise fail(f"--png {png}: give a .png file")
    if task.endswith((".json", ".py")) or ".py:" in task or Path(task).is_file():
        from factask.cli.run_cmds import load_task

        graph = load_task(task)
        if as_json:
            typer.echo(graph.to_json())
        else:
            _print_graph(graph)
        _draw(graph, png, as_json)
        return
    try:
        graph = get_task(task)
    except UnknownTaskError as exc:
        err_console.print(f"unknown task {quote(task)}", style="red", highlight=False,
                          markup=False)
        if exc.suggestions:
            err_console.print("did you mean: " + ", ".join(exc.suggestions), highlight=False)
        err_console.print("see `factask list` for every task", highlight=False)
        raise typer.Exit(2) from None
    if as_json:
        typer.echo(graph.to_json())
    else:
        _print_graph(graph)
    _draw(graph, png, as_json)


def _draw(graph: TaskGraph, png: Path | None, as_json: bool) -> None:
    if png is not None:
        from factask.viz import draw_graph  # matplotlib only when asked for

        out = draw_graph(graph, png)
        # Keep stdout pure JSON with --json: report the picture on stderr then.
        (err_console if as_json else console).print(f"wrote {out}", highlight=False,
                                                    markup=False)
