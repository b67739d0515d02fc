"""The typer application, and what several command modules share (the robot option)."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import typer
from rich.console import Console
from typer.core import TyperGroup

from factask.sim.robots.registry import ROBOT_NAMES, describe_robots


def _click_class(name: str) -> type[Exception]:
    """One of click's exception classes as typer raises it (typer ≥ 0.20 vendors its
    own click; earlier versions use click's): found from ``typer.BadParameter``."""
    return next(c for c in typer.BadParameter.__mro__ if c.__name__ == name)


_UsageError = _click_class("UsageError")
_ClickException = _click_class("ClickException")


class OneLineErrorsGroup(TyperGroup):
    """The app's group: a usage error (an unknown option, a value out of range, a
    missing argument) is one line on stderr, exit 2, as docs/cli.md promises, instead
    of click's four-line block."""

    def main(self, args: Any = None, prog_name: str | None = None,
             complete_var: str | None = None, standalone_mode: bool = True,
             **extra: Any) -> Any:
        if not standalone_mode:
            return super().main(args, prog_name, complete_var, standalone_mode=False,
                                **extra)
        try:
            value = super().main(args, prog_name, complete_var, standalone_mode=False,
                                 **extra)
        except _UsageError as exc:
            if type(exc).__name__ == "NoArgsIsHelpError":  # bare ``factask``: the help
                exc.show()  # type: ignore[attr-defined]
                sys.exit(exc.exit_code)  # type: ignore[attr-defined]
            ctx = getattr(exc, "ctx", None)
            where = ctx.command_path if ctx is not None else "factask"
            message = " ".join(exc.format_message().split())  # type: ignore[attr-defined]
            print(f"{where}: {message} (see '{where} --help')", file=sys.stderr)
            sys.exit(exc.exit_code)  # type: ignore[attr-defined]
        except _ClickException as exc:
            exc.show()  # type: ignore[attr-defined]
            sys.exit(exc.exit_code)  # type: ignore[attr-defined]
        except typer.Abort:
            print("Aborted!", file=sys.stderr)
            sys.exit(1)
        sys.exit(value if isinstance(value, int) and not isinstance(value, bool) else 0)


app = typer.Typer(
    cls=OneLineErrorsGroup,
    name="factask",
    help="Robot manipulation tasks as factor graphs: validate, show, run, generate, evaluate. "
    "Exit codes: 0 success; 1 the task or a check failed; 2 bad usage or input; 3 "
    "(generate, benchmark) no LLM call succeeded. The contract: docs/cli.md.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    # Help text is plain text: with rich markup on, "pip install 'factask[ray]'" lost
    # its "[ray]" (read as a style tag).
    rich_markup_mode=None,
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

    Exit codes: 0 success; 1 the task or a check failed; 2 bad usage or input; 3
    (generate, benchmark) no LLM call succeeded. The contract: docs/cli.md.
    """


#: Help text of every ``--robot`` option: the registry's names and what each models.
ROBOT_HELP = f"Robot, one of the registry's: {describe_robots()}."
#: Largest seed an option accepts (gymnasium and numpy take 32-bit seeds).
MAX_SEED = 2**31 - 1
#: Most episodes one command runs.
MAX_EPISODES = 100_000
#: File types ``--video`` can write.
VIDEO_SUFFIXES = (".gif", ".mp4")
#: Help text of every ``--camera`` option (the names are
#: :data:`factask.sim.render.offscreen.VIEWS`; kept here so ``--help`` needs no MuJoCo).
CAMERA_HELP = ("Camera: a view framed so the robot and every object are whole (front, top, "
               "left, right, back), or the name of a camera of the scene.")
#: Help text of every ``--json`` option of a command that reports results.
JSON_HELP = "Print one JSON object on stdout, nothing else (messages go to stderr)."


def fail(message: str, code: int = 2) -> typer.Exit:
    """Print ``message`` (plain text: square brackets stay) in red on stderr and
    return the exit to raise: ``raise fail("--size x: ...")``."""
    Console(stderr=True, soft_wrap=True).print(message, style="red", markup=False,
                                               highlight=False)
    return typer.Exit(code)


def parse_size(text: str, largest: tuple[int, int]) -> tuple[int, int]:
    """``WxH`` -> (width, height).

    Args:
        text: What the user gave to ``--size``.
        largest: The largest (width, height) allowed (the scenes' offscreen buffer,
            ``factask.sim.build.mjcf.OFFSCREEN_SIZE``).

    Raises:
        typer.Exit: code 2, with the expected form, on anything else.
    """
    w, sep, h = text.lower().partition("x")
    if not (sep and w.isdigit() and h.isdigit() and 16 <= int(w) <= largest[0]
            and 16 <= int(h) <= largest[1]):
        raise fail(f"--size {text}: give WIDTHxHEIGHT, from 16x16 to "
                   f"{largest[0]}x{largest[1]} (e.g. 640x480)")
    return int(w), int(h)


def check_camera(camera: str, model: object) -> None:
    """Exit with status 2 unless ``camera`` is a framed view or a camera of ``model``."""
    from factask.sim.render.offscreen import VIEWS

    names = [model.camera(i).name for i in range(model.ncam)]  # type: ignore[attr-defined]
    if camera not in VIEWS and camera not in names:
        raise fail(f"--camera {camera}: use a view ({', '.join(VIEWS)}) or a camera of the "
                   f"scene ({', '.join(names) or 'none'})")


def check_video(path: object) -> None:
    """Exit with status 2, before any work, unless ``path`` is None or a writable
    video file name."""
    if path is None:
        return
    from pathlib import Path

    video = Path(str(path))
    if video.suffix.lower() not in VIDEO_SUFFIXES:
        raise fail(f"--video {video}: give a file ending in {' or '.join(VIDEO_SUFFIXES)} "
                   "(MP4 is H.264, GIF plays anywhere)")
    folder = video.parent if str(video.parent) else Path(".")
    if not folder.is_dir():
        raise fail(f"--video {video}: folder {folder} does not exist (fix: create it)")


def check_robot(robot: str) -> None:
    """Exit with status 2 and the registry's names unless ``robot`` is registered."""
    if robot not in ROBOT_NAMES:
        Console(stderr=True, soft_wrap=True).print(
            f"unknown robot {robot!r} (use one of {', '.join(ROBOT_NAMES)})", markup=False)
        raise typer.Exit(2)


#: ``--time-limit``'s help (``run``, ``import-cliport``): what it bounds and why.
TIME_LIMIT_HELP = ("Seconds a CLIPort task file's own code (module and reset) may run "
                   "before it is stopped (default 60, the loader's TIME_LIMIT_S): a real "
                   "reset takes milliseconds, so only a loop that never ends reaches it.")


#: Width of a console whose stream is not a terminal: rich's default there is 80
#: columns, which cut table cells and split long lines of a piped run.
PIPE_WIDTH = 1000


def make_console(stderr: bool = False, **kwargs: Any) -> Console:
    """A command's console: on a terminal as rich sizes it; piped or redirected, lines
    are never wrapped and tables never cut (``render ... | cat`` kept ``success=True``
    whole, ``validate g.json | cat`` its order line).

    Args:
        stderr: Write to stderr (messages, progress) instead of stdout.
        **kwargs: Other :class:`rich.console.Console` options (``highlight`` ...).
    """
    stream = sys.stderr if stderr else sys.stdout
    piped = not (stream is not None and hasattr(stream, "isatty") and stream.isatty())
    return Console(stderr=stderr, soft_wrap=True, width=PIPE_WIDTH if piped else None,
                   **kwargs)


def check_readable_file(path: str | Path) -> None:
    """Refuse (exit 2, one line) a path that exists but is not a regular file: reading a
    FIFO or a device blocks until something writes to it, a folder cannot be read."""
    p = Path(path)
    if p.exists() and not p.is_file():
        raise fail(f"cannot read {path}: not a regular file (a FIFO, a device or a folder)")
