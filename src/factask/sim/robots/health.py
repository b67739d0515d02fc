"""Physics health: the one test of whether a simulation state can still be trusted.

The robot checks it during a primitive (a new fatal warning since the primitive
began aborts it), the env after every action (any fatal warning, or a non-finite
state, ends the episode as a failure).
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

#: MuJoCo warnings after which the physics is no longer trustworthy.
FATAL_WARNINGS = (
    mujoco.mjtWarning.mjWARN_BADQACC,
    mujoco.mjtWarning.mjWARN_BADQPOS,
    mujoco.mjtWarning.mjWARN_BADQVEL,
    mujoco.mjtWarning.mjWARN_CONTACTFULL,
    mujoco.mjtWarning.mjWARN_CNSTRFULL,
    mujoco.mjtWarning.mjWARN_BADCTRL,
)
_FATAL_INDEX = np.array([int(w) for w in FATAL_WARNINGS])


def warning_counts(data: mujoco.MjData) -> np.ndarray:
    """How often each of :data:`FATAL_WARNINGS` has been raised so far (a baseline)."""
    return data.warning.number[_FATAL_INDEX].copy()


def physics_problem(data: mujoco.MjData, baseline: np.ndarray | None = None) -> str | None:
    """Why the state of ``data`` can no longer be trusted, or None.

    Args:
        data: The simulation data.
        baseline: :func:`warning_counts` at some earlier time: only warnings raised
            since then count (None: any warning ever raised counts).

    Returns:
        "MuJoCo warning BADQACC at time 1.234s", "non-finite qpos/qvel at time ...",
        or None.
    """
    counts = data.warning.number[_FATAL_INDEX]
    new = counts > (0 if baseline is None else baseline)
    if new.any():
        name = FATAL_WARNINGS[int(np.argmax(new))].name.removeprefix("mjWARN_")
        return f"MuJoCo warning {name} at time {data.time:.3f}s"
    if not (np.isfinite(data.qpos).all() and np.isfinite(data.qvel).all()):
        return f"non-finite qpos/qvel at time {data.time:.3f}s"
    return None


class HealthWatch:
    """:func:`physics_problem` since a baseline, cheap enough for every few steps.

    The views into ``data`` are taken once; a healthy state costs one comparison
    of the warning counters and two sums (a NaN or inf anywhere makes a sum
    non-finite). Only an unhealthy one goes through :func:`physics_problem`.

    Args:
        data: The simulation data watched.
    """

    def __init__(self, data: mujoco.MjData) -> None:
        self.data = data
        self._counts = data.warning.number
        self._qpos = data.qpos
        self._qvel = data.qvel
        self.baseline = warning_counts(data)

    def rebase(self) -> None:
        """Count only warnings raised from now on."""
        self.baseline = self._counts[_FATAL_INDEX].copy()

    def problem(self) -> str | None:
        """Why the state can no longer be trusted (see :func:`physics_problem`), or None."""
        if ((self._counts[_FATAL_INDEX] <= self.baseline).all()
                and math.isfinite(float(self._qpos.sum()) + float(self._qvel.sum()))):
            return None
        return physics_problem(self.data, self.baseline)
