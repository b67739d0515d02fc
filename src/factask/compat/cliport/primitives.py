"""Stand-in for ``cliport.tasks.primitives``: the motion primitives a task names.

A task only *chooses* its primitive (``self.primitive = primitives.PickPlace()``);
factask's own oracle does the motion, so these carry their settings and nothing
else. Pushing (``primitives.push``, piles with a spatula) is not modelled.
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
    """Spatula push (unsupported: factask has no pushing primitive).

    Raises:
        Unsupported: always.
    """
    raise Unsupported("primitives.push (spatula pushing) is not supported")


def __getattr__(name: str) -> Any:
    if name.startswith("__"):
        raise AttributeError(name)
    raise Unsupported(f"cliport.tasks.primitives.{name} is not provided by factask")
