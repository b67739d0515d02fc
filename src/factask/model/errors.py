"""Typed errors of the graph model.

Every problem names *where* it is (a node of the graph and, where it applies, a
field) and *how to fix it*, so a person or an LLM reading the message can act on it
without opening the code.
"""

from __future__ import annotations

from dataclasses import dataclass


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

    def __str__(self) -> str:
        where = self.node or "<graph>"
        if self.field:
            where = f"{where}.{self.field}"
        text = f"{where}: {self.message}"
        if self.fix:
            text += f" (fix: {self.fix})"
        return text


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
        lines = "\n".join(f"  - {p}" for p in self.problems)
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
