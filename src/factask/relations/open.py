"""``open``: drawers pulled out of their cabinets, doors swung open."""

from __future__ import annotations

from typing import Any, Literal

from factask.relations.drawer import ArticulatedRelation, drawer_example
from factask.vocabulary.tolerances import DRAWER_OPEN_FRACTION


class Open(ArticulatedRelation):
    """Open the drawers and doors ``objects`` (kind drawer or door): each drawer
    pulled out by at least 90% of its travel, each door swung out by at least 90%
    of its range."""

    target_opening = 1.0

    type: Literal["open"] = "open"

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], Open]:
        return drawer_example(0.0), cls(objects=["drawer"])

    def holds(self, opening: float) -> bool:
        return opening + 1e-9 >= DRAWER_OPEN_FRACTION

    def _threshold_text(self) -> str:
        return f"needs at least {DRAWER_OPEN_FRACTION:.0%}"
