"""Stand-in for ``cliport.tasks.grippers``: end-effector classes a task names.

Tasks assign a class (``self.ee = Suction``); factask's robot is always a
suction cup, so these are markers. A task that keeps ``Spatula`` gets a warning
in the import report (see :mod:`factask.compat.cliport.convert`).
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
    """Spatula for pushing piles (unsupported)."""


def __getattr__(name: str) -> Any:
    if name.startswith("__"):
        raise AttributeError(name)
    raise Unsupported(f"cliport.tasks.grippers.{name} is not provided by factask")
