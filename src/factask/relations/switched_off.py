"""``switched_off``: switches pulled back up."""

from __future__ import annotations

from typing import Any, Literal

from factask.relations.switch import SwitchRelation, switch_example
from factask.vocabulary.tolerances import SWITCH_OFF_FRACTION


class SwitchedOff(SwitchRelation):
    """Switch off the switches ``objects`` (kind switch, mounted on a stove or lamp): each
    button up, pressed by at most 20% of its travel."""

    target_pressed = 0.0

    type: Literal["switched_off"] = "switched_off"

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], SwitchedOff]:
        return switch_example(True), cls(objects=["knob"])

    def holds(self, pressed: Any) -> Any:
        # Within the fraction of its up place: the joint's range keeps it from rising
        # higher, so no lower bound is needed.
        return pressed - 1e-9 <= SWITCH_OFF_FRACTION

    def _threshold_text(self) -> str:
        return f"needs at most {SWITCH_OFF_FRACTION:.0%}"
