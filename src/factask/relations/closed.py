"""``closed``: drawers pushed into their cabinets, doors swung shut."""

from __future__ import annotations

from typing import Any, Literal

from factask.relations.drawer import ArticulatedRelation, drawer_example
from factask.vocabulary.tolerances import DRAWER_CLOSED_FRACTION


class Closed(ArticulatedRelation):
    """Shut the drawers and doors ``objects`` (kind drawer or door): each open by at
    most 5% of its travel (a drawer) or range (a door)."""

    target_opening = 0.0
    anchored_goals = "before"

    type: Literal["closed"] = "closed"

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], Closed]:
        return drawer_example(1.0), cls(objects=["drawer"])

    def holds(self, opening: float) -> bool:
        # Within the fraction of its closed place either way: a pose deeper in than
        # closed is no state a drawer on its joint can take.
        return abs(opening) - 1e-9 <= DRAWER_CLOSED_FRACTION

    def _threshold_text(self) -> str:
        return f"needs at most {DRAWER_CLOSED_FRACTION:.0%}"
