"""The typer application and the registration of every command module."""

from __future__ import annotations

import typer

app = typer.Typer(
    name="factask",
    help="Robot manipulation tasks as factor graphs: validate, show, run, generate, evaluate.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)

