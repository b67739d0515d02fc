"""Stand-in for ``cliport.tasks.grippers``: end-effector classes a task names.

Tasks assign a class (``self.ee = Suction``); these are markers. ``Spatula``
with a zone goal over small blocks makes that goal a pile pushed with factask's
spatula (:mod:`factask.compat.cliport.piles`: a task with a ``pile_in_zone`` goal
gets a spatula); a ``Spatula`` task without piles gets a warning and the suction
cup.
"""

from __future__ import annotations

from typing import Any

from factask.compat.cliport.errors import Unsupported


class Gripper:
    """Base end effector (marker class)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        raise Unsupported(f"{type(self).__name__} grippers are created by factask's robot")


class Suction(Gripper):
    """Suction cup (factask's end effector)."""


class Spatula(Gripper):
    """Spatula for pushing piles (factask's spatula, :mod:`factask.sim.robots.spatula`)."""


def __getattr__(name: str) -> Any:
    if name.startswith("__"):
        raise AttributeError(name)
    raise Unsupported(f"cliport.tasks.grippers.{name} is not provided by factask")
