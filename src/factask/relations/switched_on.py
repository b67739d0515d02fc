"""``switched_on``: switches pressed down."""

from __future__ import annotations

from typing import Any, Literal

from factask.relations.switch import SwitchRelation, switch_example
from factask.vocabulary.tolerances import SWITCH_ON_FRACTION


class SwitchedOn(SwitchRelation):
    """Switch on the switches ``objects`` (kind switch, mounted on a stove or lamp): each
    button pressed down by at least 80% of its travel."""

    target_pressed = 1.0

    type: Literal["switched_on"] = "switched_on"

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], SwitchedOn]:
        return switch_example(False), cls(objects=["knob"])

    def holds(self, pressed: Any) -> Any:
        return pressed + 1e-9 >= SWITCH_ON_FRACTION

    def _threshold_text(self) -> str:
        return f"needs at least {SWITCH_ON_FRACTION:.0%}"
