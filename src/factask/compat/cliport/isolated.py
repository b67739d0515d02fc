"""Run one piece of task-file work in a forked child process that is ended, for sure,
at its time limit.

Why a child: in-process, the only way to stop a task's endless loop is to raise into
it, and task code that catches everything (``while True: try: ... except
BaseException: pass``) swallows every stop for ever; ``os._exit`` in task code would
end the caller with it. A child process can be killed whatever its code catches, and
its ending without an answer is seen. ``fork`` makes the child cheap (no imports to
redo) and lets it run a closure; where ``fork`` does not exist the work runs here.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import signal
import sys
import time
from collections.abc import Callable
from multiprocessing import Pipe
from multiprocessing.connection import Connection
from typing import Any, TypeVar

from factask.compat.cliport.errors import CliportImportError, TaskTimeout
from factask.vocabulary.errors import clip

T = TypeVar("T")

#: A child's report that its time was up, sent by the work itself (``note``): where
#: the task's code was stopped, so a killed child still says where it looped.
Note = Callable[[str], None]

FORK_AVAILABLE = hasattr(os, "fork")


def run_in_child(work: Callable[[Note], T], *, time_limit: float | None,
                 what: str) -> T:
    """Run ``work(note)`` in a forked child; return its value or raise its error.

    Args:
        work: Called in the child with ``note``, a function taking the one line
            to report if the child must be killed (the time-out message naming where
            the task's code was stopped); call it at most once. Returns a
            picklable value.
        time_limit: Seconds from the fork until the child is killed; None: no limit.
        what: What the work is (the task file), for the messages.

    Returns:
        The value ``work`` returned in the child.

    Raises:
        TaskTimeout: the child did not answer within ``time_limit`` and was killed.
        CliportImportError: the child ended without answering (``os._exit`` in task
            code, a crash), or raised something that cannot be sent back.
        BaseException: whatever ``work`` raised in the child (sent back pickled).
    """
    reader, writer = Pipe(duplex=False)
    sys.stdout.flush()
    sys.stderr.flush()
    pid = os.fork()
    if pid == 0:  # the child: never returns
        reader.close()
        _child(work, writer, what)
    writer.close()
    deadline = None if time_limit is None else time.monotonic() + time_limit
    stopped_at: str | None = None
    try:
        while True:
            wait = None if deadline is None else max(0.0, deadline - time.monotonic())
            if not reader.poll(wait):
                raise TaskTimeout(
                    f"{stopped_at} (it caught the stop and went on, so its process was "
                    "ended)" if stopped_at else
                    f"{what} ran past the {time_limit:g} s limit (a loop that never "
                    "ends? --time-limit sets the limit); its process was ended")
            try:
                kind, value = reader.recv()
            except EOFError:
                status = _reap(pid)
                pid = 0
                raise CliportImportError(
                    f"{what}: the task's code ended the process ({status}) before the "
                    "import finished: a task file must not call os._exit or kill its "
                    "process") from None
            if kind == "note":
                stopped_at = value
                continue
            if kind == "ok":
                return value
            raise value
    finally:
        reader.close()
        if pid:
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
            _reap(pid)


def _reap(pid: int) -> str:
    """Wait for the child ``pid``; its ending in words."""
    _, status = os.waitpid(pid, 0)
    code = os.waitstatus_to_exitcode(status)
    return f"exit code {code}" if code >= 0 else f"signal {signal.Signals(-code).name}"


def _child(work: Callable[[Note], Any], writer: Connection, what: str) -> None:
    """The child's whole life: run the work, send one answer, leave at once (no
    ``atexit``, no test-runner teardown inherited from the parent)."""
    code = 0
    try:
        signal.signal(signal.SIGINT, signal.SIG_DFL)  # Ctrl-C ends the child quietly
        try:
            answer: tuple[str, Any] = ("ok", work(lambda line: writer.send(("note", line))))
        except Exception as exc:  # every error goes back to the parent
            answer = ("error", _sendable(exc))
        except BaseException as exc:  # KeyboardInterrupt, SystemExit raised by task code
            answer = ("error", CliportImportError(
                f"{what}: the task's code raised {type(exc).__name__}"
                + (f": {clip(exc, 200)}" if str(exc) else "")))
        try:
            writer.send(answer)
        except Exception as exc:  # an answer that does not pickle
            writer.send(("error", CliportImportError(
                f"{what}: the import's answer could not be sent back: {type(exc).__name__}: "
                f"{clip(exc, 200)}")))
    except BaseException:  # the parent reports a child that says nothing
        code = 1
    finally:
        try:
            sys.stdout.flush()
            sys.stderr.flush()
        finally:
            os._exit(code)


def _sendable(exc: Exception) -> Exception:
    """``exc`` if it survives pickling, else a CliportImportError with its text."""
    try:
        pickle.loads(pickle.dumps(exc))
        return exc
    except Exception:  # any class that does not round-trip
        return CliportImportError(f"{type(exc).__name__}: {clip(exc, 300)}")
