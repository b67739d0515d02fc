"""The typer application, and what several command modules share (the robot option)."""

from __future__ import annotations

import typer
from rich.console import Console

from factask.sim.robots import ROBOT_NAMES, describe_robots

app = typer.Typer(
    name="factask",
    help="Robot manipulation tasks as factor graphs: validate, show, run, generate, evaluate. "
    "Exit codes: 0 success; 1 the task or a check failed; 2 bad usage or input.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)

def _version(value: bool) -> None:
    if value:
        from importlib.metadata import PackageNotFoundError, version

        try:
            typer.echo(f"factask {version('factask')}")
        except PackageNotFoundError:  # running from a source tree that is not installed
            typer.echo("factask (not installed)")
        raise typer.Exit(0)


@app.callback()
def _main(
    show_version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                      help="Print the version and exit."),
) -> None:
    """Robot manipulation tasks as factor graphs: validate, show, run, generate, evaluate.

    Exit codes: 0 success; 1 the task or a check failed; 2 bad usage or input.
    """


#: Help text of every ``--robot`` option: the registry's names and what each models.
ROBOT_HELP = f"Robot, one of the registry's: {describe_robots()}."
#: Largest seed an option accepts (gymnasium and numpy take 32-bit seeds).
MAX_SEED = 2**31 - 1
#: Most episodes one command runs.
MAX_EPISODES = 100_000
#: File types ``--video`` can write.
VIDEO_SUFFIXES = (".gif", ".mp4")


def check_video(path: object) -> None:
    """Exit with status 2, before any work, unless ``path`` is None or a writable
    video file name."""
    if path is None:
        return
    from pathlib import Path

    video = Path(str(path))
    err = Console(stderr=True, soft_wrap=True)
    if video.suffix.lower() not in VIDEO_SUFFIXES:
        err.print(f"--video {video}: give a file ending in {' or '.join(VIDEO_SUFFIXES)}",
                  style="red", markup=False)
        raise typer.Exit(2)
    folder = video.parent if str(video.parent) else Path(".")
    if not folder.is_dir():
        err.print(f"--video {video}: folder {folder} does not exist", style="red", markup=False)
        raise typer.Exit(2)


def check_robot(robot: str) -> None:
    """Exit with status 2 and the registry's names unless ``robot`` is registered."""
    if robot not in ROBOT_NAMES:
        Console(stderr=True, soft_wrap=True).print(
            f"unknown robot {robot!r} (use one of {', '.join(ROBOT_NAMES)})", markup=False)
        raise typer.Exit(2)
