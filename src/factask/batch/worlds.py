"""What the lockstep primitive and the device observations read of a batch.

:class:`factask.batch.env.BatchEnv` is the one implementation. The env imports
:mod:`factask.batch.primitive` and :mod:`factask.batch.interop`, so those two name
this protocol, not the class: no import (annotations included) runs back up to the env.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

import numpy as np


class LockstepWorlds(Protocol):
    """Many worlds of one compiled model, commanded together.

    Attributes:
        num_envs: The number of worlds.
        device: The Warp device the worlds live on (``"cpu"``, ``"cuda:0"``).
        object_names: Every object instance, in the batch's order.
        model: The host ``mujoco.MjModel`` (its timestep).
        wp_data: The worlds' Warp data (qpos, mocap, sites).
        command: (W, command_dim) each world's low-level command now.
        command_dim: 4 for the floating cup (x, y, z, yaw).
        suction: The per-world suction grasp (its ``held`` objects, contact reads).
    """

    num_envs: int
    device: str
    object_names: list[str]
    model: Any
    wp_data: Any
    command: np.ndarray
    command_dim: int
    suction: Any

    def step(self, command: np.ndarray, substeps: int = ...) -> None: ...

    def scene(self) -> Any: ...

    def suction_on(self, worlds: Sequence[int] | np.ndarray | None = ...) -> np.ndarray: ...

    def suction_off(self, worlds: Sequence[int] | np.ndarray | None = ...) -> None: ...
