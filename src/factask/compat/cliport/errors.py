"""Typed errors of the CLIPort compatibility layer."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar

from factask.vocabulary.errors import FactaskError, InvalidValueError

#: Messages of the Unsupported errors raised while a task file runs (user code may
#: catch them: the import still reports them).
_REFUSALS: ContextVar[list[str] | None] = ContextVar("cliport_refusals", default=None)


class CliportImportError(FactaskError):
    """A CLIPort/GenSim task file could not be turned into a task graph.

    The message names the file, and where it applies the line of the user's code
    that failed (syntax errors, exceptions raised in ``reset``), so the author can
    fix it without reading factask's code.
    """


class Unsupported(CliportImportError):
    """The task code uses a CLIPort/PyBullet feature factask does not model.

    Examples: deformables (cloth, rope, piles), spatula pushing, Google scanned
    objects, an unknown URDF, a PyBullet call with no recorded meaning. The
    message names the call or the asset. Every one raised inside
    :func:`recording_refusals` is remembered, even if the task's code catches it.
    """

    def __init__(self, *args: object) -> None:
        super().__init__(*args)
        seen = _REFUSALS.get()
        if seen is not None:
            seen.append(str(self))


class UnsupportedAttribute(Unsupported, AttributeError):
    """An attribute of the recording env that factask does not provide. An
    ``AttributeError`` too, so task code that probes for it (``hasattr(env, 'x')``,
    ``getattr(env, 'x', None)``) takes its own fallback, as it would on an env
    without it; the refusal is still remembered (a warning if the task goes on)."""


class TaskTimeout(CliportImportError):
    """The task file's own code (its module or ``reset``) ran past the import's time
    limit: a loop that never ends (a rejection loop whose test never passes, a
    ``while True`` waiting for something the recording env never does). The message
    names the line it was stopped at."""


class NoGoals(CliportImportError):
    """``reset`` ran but queued no goal (``add_goal`` never called). ``derived``:
    the class of the file that derives from the one imported, where there is
    exactly one line of them (the import then tries that one)."""

    derived: str | None = None


@contextmanager
def recording_refusals() -> Iterator[list[str]]:
    """Collect the messages of every :class:`Unsupported` raised in the block."""
    seen: list[str] = []
    token = _REFUSALS.set(seen)
    try:
        yield seen
    finally:
        _REFUSALS.reset(token)


class PoseError(InvalidValueError):
    """A pose or quaternion in CLIPort/PyBullet form is malformed (not four finite
    numbers, a zero quaternion, no 3-D position). A ``ValueError``, as PyBullet's."""


class UnknownColorNameError(FactaskError, KeyError):
    """``utils.COLORS[name]`` with a name the palette lacks (a ``KeyError``, as
    looking up CLIPort's colour dict is)."""
