"""Typed errors of the graph model.

Every problem names *where* it is (a node of the graph and, where it applies, a
field) and *how to fix it*, so a person or an LLM reading the message can act on it
without opening the code.
"""

from __future__ import annotations

from dataclasses import dataclass

#: User text quoted in a message is cut to this many characters.
QUOTE_LIMIT = 80
#: A validation report lists at most this many problems, then says how many more.
MAX_PROBLEMS_LISTED = 25
#: Most characters of each part of a :class:`Problem` (node, field, message, fix): a
#: problem is under 1 KB in every output form, text or JSON, whatever the input held.
PROBLEM_PART_LIMITS = {"node": 120, "field": 160, "message": 400, "fix": 240}


def quote(text: object, limit: int = QUOTE_LIMIT) -> str:
    """User text as it may appear in a message: escaped like ``repr`` (newlines and
    control characters cannot fake further lines) and cut to ``limit`` characters,
    with the full length stated when cut."""
    raw = text if isinstance(text, str) else str(text)
    if len(raw) <= limit:
        return repr(raw)
    return f"{raw[:limit]!r}... ({len(raw):,} characters)"


def clip(text: object, limit: int = 200) -> str:
    """Free text (an error from elsewhere, a line of code) cut to ``limit``
    characters on one line, with the full length stated when cut."""
    raw = str(text).replace("\r", " ").replace("\n", " ")
    return raw if len(raw) <= limit else f"{raw[:limit]}... ({len(raw):,} characters)"


def name_list(names: list[str], limit: int = 8) -> str:
    """At most ``limit`` names, for a fix such as "use one of [...]" (a message
    listing every name would grow with the square of the graph)."""
    shown = [n if len(n) <= QUOTE_LIMIT else n[:QUOTE_LIMIT] + "..." for n in names[:limit]]
    more = f" and {len(names) - limit} more" if len(names) > limit else ""
    return f"{shown}{more}"


class FactaskError(Exception):
    """Base class of every error factask raises on purpose."""


@dataclass(frozen=True)
class Problem:
    """One thing wrong with a task graph.

    Attributes:
        node: The variable or factor the problem is about ("" for the graph itself).
        field: The field of that node (dotted path), or "" for the node as a whole.
        message: What is wrong.
        fix: How to fix it.
    """

    node: str
    field: str
    message: str
    fix: str = ""

    def __post_init__(self) -> None:
        # A message may quote the input (pydantic quotes a whole bad value): each part
        # is cut here, once, so no output form has to remember to.
        for part, limit in PROBLEM_PART_LIMITS.items():
            value = getattr(self, part)
            if not isinstance(value, str) or len(value) > limit:
                object.__setattr__(self, part, clip(value, limit - 24))

    def __str__(self) -> str:
        # Node names come from the user's input: quoted when they could mislead.
        node = self.node if _plain(self.node) else quote(self.node)
        where = node or "<graph>"
        if self.field:
            where = f"{where}.{self.field if _plain(self.field) else quote(self.field)}"
        text = f"{where}: {self.message}"
        if self.fix:
            text += f" (fix: {self.fix})"
        return text


def problem_lines(problems: list[Problem]) -> list[str]:
    """A report's lines: at most :data:`MAX_PROBLEMS_LISTED` problems, each cut short,
    then how many more there are."""
    lines = [f"  - {clip(p, 600)}" for p in problems[:MAX_PROBLEMS_LISTED]]
    if len(problems) > MAX_PROBLEMS_LISTED:
        lines.append(f"  ... and {len(problems) - MAX_PROBLEMS_LISTED} more")
    return lines


def _plain(text: str) -> bool:
    """Short, printable, one line: safe to show as it is."""
    return len(text) <= QUOTE_LIMIT and text.isprintable()


class InvalidValueError(FactaskError, ValueError):
    """A value factask was given is not acceptable: an argument out of range, a
    malformed pose, a field a validator rejects, a name registered twice.

    Also a ``ValueError``, as Python callers (and pydantic's validators) expect.
    """


class GraphValidationError(FactaskError):
    """A task graph (or fragment, or template) is not valid.

    Attributes:
        problems: Every problem found, not only the first.
    """

    def __init__(self, problems: list[Problem], what: str = "task graph") -> None:
        self.problems = list(problems)
        lines = "\n".join(problem_lines(self.problems))
        super().__init__(f"invalid {what}: {len(self.problems)} problem(s)\n{lines}")

    @property
    def nodes(self) -> set[str]:
        """Names of every node that has at least one problem."""
        return {p.node for p in self.problems}


class SubjectError(FactaskError):
    """An error about one named thing, worded ``"<subject>: <message> (fix: <fix>)"``.

    Attributes:
        subject: What the error is about ("" for nothing in particular).
        message: What is wrong.
        fix: How to fix it ("" if there is no advice).
    """

    def __init__(self, subject: str, message: str, fix: str = "") -> None:
        self.subject, self.message, self.fix = subject, message, fix
        text = f"{subject}: {message}" if subject else message
        if fix:
            text += f" (fix: {fix})"
        super().__init__(text)


class CompositionError(FactaskError):
    """Graphs or templates cannot be combined as asked (name clash, bad binding)."""
