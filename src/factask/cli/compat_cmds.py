"""Commands importing outside task files: GenSim/CLIPort's (``import-cliport`` and its
batch form) and LIBERO's BDDL files (``import-libero``).

Task files are Python and **are executed**. ``import-cliport`` runs the file in
this process; ``import-cliport-batch`` runs each file in a child process with a
time limit. Import only code you trust.
"""

from __future__ import annotations

import json
from pathlib import Path

import typer
from rich.markup import escape

from factask.cli.app import (
    JSON_HELP,
    MAX_SEED,
    ROBOT_HELP,
    TIME_LIMIT_HELP,
    app,
    check_readable_file,
    check_robot,
    fail,
    make_console,
)
from factask.graph import TaskGraph
from factask.vocabulary.errors import FactaskError

console = make_console()
err_console = make_console(stderr=True)

_EXEC_WARNING = ("The task file is Python code and IS EXECUTED (not sandboxed): "
                 "only import files you trust.")


@app.command("import-cliport", help=(
    "Import a GenSim/CLIPort task file (a Task subclass) as a factask task graph. "
    "Its reset(env) runs against a recording environment; the objects and goals it "
    "adds become variables and factors. " + _EXEC_WARNING))
def import_cliport_cmd(
    file: Path = typer.Argument(..., help="The task's .py file (it is executed)."),
    class_name: str | None = typer.Option(None, "--class", help="Task class to import "
                                          "(default: the one the file defines)."),
    seed: int = typer.Option(0, "--seed", min=0, max=MAX_SEED,
                             help="Seed of the reset's random draws."),
    out: Path = typer.Option(..., "--out", "-o", help="Where to write the graph JSON."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="Do not print the warnings."),
    time_limit: float | None = typer.Option(None, "--time-limit", min=0.1, max=86_400,
                                            help=TIME_LIMIT_HELP),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object: file, ok, "
                                 "class, task, variables, factors, milestones, warnings, "
                                 "error, out."),
) -> None:
    """Write the graph JSON; print the import warnings; exit 1 with the reason on failure."""
    from factask.compat.cliport import CliportImportError, import_cliport

    # an input that cannot be read is bad input (exit 2) as everywhere; a file that
    # runs and fails to import is a failed import (exit 1)
    check_readable_file(file)
    if not Path(file).is_file():
        raise fail(f"cannot read {file}: no such file")
    try:
        limit = {} if time_limit is None else {"time_limit": time_limit}
        result = import_cliport(file, class_name=class_name, seed=seed, **limit)
    except CliportImportError as exc:
        if as_json:
            typer.echo(json.dumps({"file": str(file), "ok": False, "error": str(exc)}))
            raise typer.Exit(1) from None
        err_console.print(f"[red]{escape(str(file))}: import failed[/red]")
        err_console.print(str(exc), markup=False, highlight=False)
        raise typer.Exit(1) from None
    try:
        out.write_text(result.graph.to_json(), encoding="utf-8")
    except OSError as exc:
        err_console.print(f"[red]{escape(f'cannot write {out}: {exc.strerror or exc}')}[/red]")
        raise typer.Exit(2) from None
    g = result.graph
    if as_json:
        typer.echo(json.dumps({"file": str(file), "ok": True, "class": result.class_name,
                               "task": g.name, "variables": len(g.variables),
                               "factors": len(g.factors), "milestones": g.milestones(),
                               "warnings": result.warnings, "error": None, "out": str(out)}))
        return
    console.print(f"[green]{escape(str(file))}: imported[/green] "
                  + escape(f"{result.class_name} as {g.name!r}: {len(g.variables)} "
                           f"variable(s), {len(g.factors)} factor(s) -> {out}"))
    if not quiet:
        for w in result.warnings:
            err_console.print(f"  warning: {w}", markup=False, highlight=False)


@app.command("import-cliport-batch", help=(
    "Import every .py task file of a folder, each in a child process with a time "
    "limit, writing one JSON line per file (file, class, loaded, imported, compiled, "
    "oracle_success_rate, error) as soon as it finishes. " + _EXEC_WARNING))
def import_cliport_batch_cmd(
    folder: Path = typer.Argument(..., help="Folder of task files (each is executed)."),
    out: Path = typer.Option(..., "--out", "-o", help="Results file (JSON lines)."),
    timeout: float = typer.Option(120.0, "--timeout", min=0.1,
                                  help="Wall-clock seconds per file before it is killed."),
    seed: int = typer.Option(0, "--seed", min=0, max=MAX_SEED,
                             help="Seed of each reset's random draws."),
    episodes: int = typer.Option(0, "--episodes", min=0, help="Oracle episodes per file "
                                 "(0: do not run the oracle; needs factask.sim.episode)."),
    graphs: Path | None = typer.Option(None, "--graphs", help="Also write each imported "
                                       "graph to this folder as <file stem>.json."),
    ravens: bool = typer.Option(False, "--ravens", help="Also score every oracle episode "
                                "as Ravens does (goals in queue order, XY within pos_eps, "
                                "yaw within rot_eps modulo symmetry, a finished goal never "
                                "re-checked, success at reward >= 0.99): ravens_success_rate "
                                "and per-episode scores beside factask's own checks."),
    robot: str = typer.Option("floating", "--robot", "-r", help=ROBOT_HELP + " Runs the "
                              "oracle episodes."),
    as_json: bool = typer.Option(False, "--json", help=JSON_HELP + " It holds folder, out, "
                                 "files, imported and every file's record."),
) -> None:
    """Run the batch; exit 0 even if files fail (their lines say why); 2 for a
    folder that is missing or holds no ``.py`` file."""
    from factask.compat.cliport.batch import run_batch, task_files

    check_robot(robot)
    if not folder.is_dir():
        err_console.print(f"[red]{escape(str(folder))} is not a folder[/red]")
        raise typer.Exit(2)
    n = len(task_files(folder))
    if n == 0:  # nothing to measure is a mistake in the command, not a result
        err_console.print(f"[red]{escape(str(folder))} has no .py files: give the folder "
                          "that holds the task files[/red]")
        raise typer.Exit(2)

    def show(rec: dict) -> None:
        ok = rec.get("imported") and not rec.get("error")
        mark = "[green]ok[/green]" if ok else "[red]failed[/red]"
        line = Path(rec["file"]).name
        if rec.get("oracle_success_rate") is not None:
            line += f" (oracle {rec['oracle_success_rate']:.0%}"
            if rec.get("ravens_success_rate") is not None:
                line += f", Ravens {rec['ravens_success_rate']:.0%}"
            line += ")"
        if rec.get("error"):
            line += f": {(str(rec['error']).splitlines() or [''])[0][:200]}"
        err_console.print(f"{mark} {escape(line)}", highlight=False)

    try:
        with out.open("w", encoding="utf-8") as fh:
            records = run_batch(folder, fh, timeout=timeout, seed=seed, episodes=episodes,
                                graphs_dir=graphs, on_result=show, ravens=ravens,
                                robot=robot)
    except OSError as exc:
        err_console.print(f"[red]{escape(f'cannot write {out}: {exc.strerror or exc}')}[/red]")
        raise typer.Exit(2) from None
    good = sum(1 for r in records if r.get("imported") and not r.get("error"))
    if as_json:
        typer.echo(json.dumps({"folder": str(folder), "out": str(out), "files": len(records),
                               "imported": good, "records": records}))
        return
    console.print(escape(f"{good}/{len(records)} file(s) imported -> {out}"), highlight=False)


def load_libero_task(file: str | Path) -> TaskGraph:
    """A LIBERO ``.bddl`` file as a graph, its warnings printed; exit 2 with one line
    when it cannot be read or imported (``run`` and the other task-loading commands)."""
    from factask.compat.libero import import_libero

    try:
        result = import_libero(file)
    except FactaskError as exc:
        err_console.print(f"cannot import {file}: {exc}", style="red", markup=False)
        raise typer.Exit(2) from None
    for warning in result.warnings:
        err_console.print(f"warning: {warning}", style="yellow", markup=False)
    return result.graph


@app.command("import-libero", help=(
    "Import a LIBERO BDDL task file as a factask task graph: its objects become "
    "factask stand-ins, its On/In goals on/inside factors. Articulated fixtures "
    "(Open, Close, Turnon, drawers) are refused (exit 2)."))
def import_libero_cmd(
    file: Path = typer.Argument(..., help="The task's .bddl file."),
    out: Path | None = typer.Option(None, "--out", "-o", help="Write the graph JSON here."),
) -> None:
    """Print a short summary of the import; write the graph with ``--out``."""
    check_readable_file(file)
    graph = load_libero_task(file)
    if out is not None:
        try:
            out.write_text(graph.to_json(), encoding="utf-8")
        except OSError as exc:
            raise fail(f"cannot write {out}: {exc.strerror or exc}") from None
    goals = ", ".join(f"{f.goal.type}({', '.join(f.goal.variable_names())})"
                      for f in graph.factors)
    console.print(escape(f"{file}: imported as {graph.name!r}: {len(graph.variables)} "
                         f"variable(s), goals {goals}" + (f" -> {out}" if out else "")),
                  highlight=False)
