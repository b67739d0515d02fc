"""The typer application, and what several command modules share (the robot option)."""

from __future__ import annotations

import typer
from rich.console import Console

from factask.sim.robots import ROBOT_NAMES, describe_robots

app = typer.Typer(
    name="factask",
    help="Robot manipulation tasks as factor graphs: validate, show, run, generate, evaluate.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)

#: Help text of every ``--robot`` option: the registry's names and what each models.
ROBOT_HELP = f"Robot, one of the registry's: {describe_robots()}."


def check_robot(robot: str) -> None:
    """Exit with status 2 and the registry's names unless ``robot`` is registered."""
    if robot not in ROBOT_NAMES:
        Console(stderr=True, soft_wrap=True).print(
            f"unknown robot {robot!r} (use one of {', '.join(ROBOT_NAMES)})", markup=False)
        raise typer.Exit(2)
