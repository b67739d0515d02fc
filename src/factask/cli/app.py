"""The typer application and the registration of every command module."""

from __future__ import annotations

import importlib

import typer

app = typer.Typer(
    name="factask",
    help="Robot manipulation tasks as factor graphs: validate, show, run, generate, evaluate.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)

# Each module defines its commands with ``@app.command()`` on import. Modules not
# written yet are skipped, so the CLI grows one module at a time.
_COMMAND_MODULES = (
    "factask.cli.graph_cmds",
    "factask.cli.library_cmds",
    "factask.cli.run_cmds",
    "factask.cli.gen_cmds",
    "factask.cli.compat_cmds",
)
for _name in _COMMAND_MODULES:
    try:
        importlib.import_module(_name)
    except ModuleNotFoundError as exc:  # pragma: no cover - only while a module is missing
        if exc.name != _name:
            raise
