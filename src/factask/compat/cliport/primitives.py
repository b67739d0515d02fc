"""Stand-in for ``cliport.tasks.primitives``: the motion primitives a task names.

A task only *chooses* its primitive (``self.primitive = primitives.PickPlace()``);
factask's own oracle does the motion, so these carry their settings and nothing
else. ``primitives.push`` marks a task that sweeps piles with a spatula
(:mod:`factask.compat.cliport.piles`); factask's oracle pushes.
"""

from __future__ import annotations

from typing import Any

from factask.compat.cliport.errors import Unsupported

#: Ravens' default approach height and speed of a pick-and-place.
DEFAULT_HEIGHT = 0.32
DEFAULT_SPEED = 0.01


class PickPlace:
    """Suction pick-and-place (the only primitive factask runs)."""

    def __init__(self, height: float = DEFAULT_HEIGHT, speed: float = DEFAULT_SPEED) -> None:
        self.height = height
        self.speed = speed

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        raise Unsupported("primitives.PickPlace is run by factask's oracle, not by task code")


def push(*args: Any, **kwargs: Any) -> Any:
    """Spatula push (run by factask's oracle, :mod:`factask.sim.robots.spatula`, not by task code).

    Raises:
        Unsupported: always.
    """
    raise Unsupported("primitives.push is run by factask's oracle, not by task code")


def __getattr__(name: str) -> Any:
    if name.startswith("__"):
        raise AttributeError(name)
    raise Unsupported(f"cliport.tasks.primitives.{name} is not provided by factask")
