"""One goal the words of a proposal state (:class:`ReadGoal`): what the clause reading
(:mod:`factask.gen.reading.clauses`) finds and its passes
(:mod:`factask.gen.reading.goal_order`) refine. Its own module so both can use it.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class ReadGoal:
    """One goal the words state.

    Attributes:
        relation: The relation type (``inside``, ``stack``, ...).
        objects: The names of the objects it moves, in the words' order.
        anchor: The name of the object it anchors on (None: none).
        ordered: Whether the order of ``objects`` is the task's (a stack's bottom first).
        step: The part of the proposal it comes from, counted in sequence words:
            a goal comes after every goal of a lower step.
        field: The anchor field ``anchor`` fills where the relation has several
            (a row ``on`` other objects, not ``along`` them); None: any.
    """

    relation: str
    objects: tuple[str, ...]
    anchor: str | None = None
    ordered: bool = False
    step: int = 0
    field: str | None = None


__all__ = ["ReadGoal"]
