"""The ``factask`` command line (typer + rich).

Each command group lives in its own module and registers its commands on
:data:`app` when imported (below); heavy dependencies (MuJoCo, litellm) are
imported inside the commands so that ``factask --help`` and ``factask validate``
stay fast. :func:`main` is the console script: the app, with standard streams that
are closed or full reported in one line (exit 2) instead of a traceback or a silent
exit 0.
"""

from __future__ import annotations

import contextlib
import errno
import io
import os
import sys

from factask.cli import (  # noqa: F401 - importing a module registers its commands
    compat_cmds,
    data_cmds,
    gen_cmds,
    graph_cmds,
    library_cmds,
    policy_cmds,
    run_cmds,
)
from factask.cli.app import app
from factask.vocabulary.errors import FactaskError

#: Exit status when the output cannot be written (as for bad usage or input).
EXIT_STREAM = 2


class ClosedStreamError(FactaskError, OSError):
    """A standard stream the shell closed was read or written (an ``OSError`` too, as
    a stream's own errors are, so :func:`main` and the commands treat it alike)."""


class _ClosedStream(io.TextIOBase):
    """Stands for a standard stream the shell closed (``>&-``, ``<&-``): Python starts
    with ``None`` there, and writes to ``None`` vanish; these raise instead."""

    def __init__(self, name: str) -> None:
        self.stream_name = name

    def _closed(self, *_: object) -> None:
        raise ClosedStreamError(errno.EBADF, f"standard {self.stream_name} is closed")

    write = read = readline = _closed

    def flush(self) -> None:
        pass


def _fail(message: str) -> None:
    with contextlib.suppress(OSError, AttributeError):
        print(f"factask: {message}", file=sys.stderr, flush=True)
    os._exit(EXIT_STREAM)  # stdout is unusable: no flush at exit may raise again


def main() -> None:
    """Run the command line; an output that cannot be written (stdout closed, full, a
    broken pipe) or a closed stdin is one line on stderr and exit 2."""
    if sys.stdout is None:
        sys.stdout = _ClosedStream("output")
    if sys.stdin is None:
        sys.stdin = _ClosedStream("input")
    code: int | str | None = 0
    try:
        app()
    except SystemExit as exc:
        code = exc.code
    except OSError as exc:
        _fail(f"cannot write the output: {exc.strerror or exc}")
    try:
        sys.stdout.flush()
    except OSError as exc:
        _fail(f"cannot write the output: {exc.strerror or exc}")
    sys.exit(code)


__all__ = ["ClosedStreamError", "app", "main"]
