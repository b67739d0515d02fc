"""The physics lower bound of a run: its physics steps x a bare ``mj_step`` in the same states.

A run (an env action, an oracle episode) is timed first as it is. Then it is run
again, unchanged (same seed, same actions: the physics is deterministic), with
``mujoco.mj_step`` wrapped to count the steps and keep a copy of every
``every``-th state (``mj_getState``, plus the suction weld's target, which lives
in the model, and the sleep state of the kinematic trees, which ``mj_getState``
does not hold: a resting object asleep in the run must be asleep in the bare
step). A bare ``mj_step`` is then timed from each kept state: the mean is the
cost of one step of exactly the states the run went through (contacts while
carrying included), and steps x that mean is the fastest the run could be with
no Python around the physics. ``wall / lower bound`` is the overhead ratio.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import mujoco
import numpy as np

#: State parts restored before each timed bare step (what mj_step reads).
STATE = mujoco.mjtState.mjSTATE_INTEGRATION
#: MjData fields of the sleep state (arrays, then counts), copied beside the state.
SLEEP_ARRAYS = ("tree_asleep", "tree_awake", "body_awake", "body_awake_ind",
                "parent_awake_ind", "dof_awake_ind")
SLEEP_COUNTS = ("ntree_awake", "nbody_awake", "nparent_awake", "nv_awake")


def get_sleep(d: mujoco.MjData) -> dict[str, Any]:
    """A copy of the sleep state of ``d`` (see :func:`set_sleep`)."""
    out: dict[str, Any] = {k: getattr(d, k).copy() for k in SLEEP_ARRAYS}
    out.update({k: int(getattr(d, k)) for k in SLEEP_COUNTS})
    return out


def set_sleep(d: mujoco.MjData, sleep: dict[str, Any]) -> None:
    """Write a sleep state taken by :func:`get_sleep` into ``d``."""
    for k in SLEEP_ARRAYS:
        getattr(d, k)[:] = sleep[k]
    for k in SLEEP_COUNTS:
        setattr(d, k, sleep[k])


@dataclass
class Recording:
    """Steps counted and states kept while :func:`record` was active."""

    every: int
    steps: int = 0
    model: Any = None
    states: list[tuple[np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]] = field(
        default_factory=list)


@contextmanager
def record(every: int = 10) -> Iterator[Recording]:
    """Count ``mujoco.mj_step`` calls and keep every ``every``-th state.

    Args:
        every: Keep one state in this many steps.

    Yields:
        The recording, filled while the block runs.
    """
    rec = Recording(every)
    original = mujoco.mj_step

    def counting(m: mujoco.MjModel, d: mujoco.MjData, *args: Any) -> None:
        if rec.steps % rec.every == 0:
            state = np.empty(mujoco.mj_stateSize(m, STATE))
            mujoco.mj_getState(m, d, state, STATE)
            rec.model = m
            rec.states.append((state, m.eq_obj2id.copy(), m.eq_data.copy(), get_sleep(d)))
        rec.steps += 1
        original(m, d, *args)

    mujoco.mj_step = counting
    try:
        yield rec
    finally:
        mujoco.mj_step = original


def bare_step_seconds(rec: Recording) -> float:
    """Mean wall seconds of one bare ``mj_step`` from each recorded state.

    Args:
        rec: A recording with at least one state.

    Returns:
        Seconds per step (NaN when nothing was recorded).
    """
    if not rec.states:
        return float("nan")
    m = rec.model
    keep = m.eq_obj2id.copy(), m.eq_data.copy()
    d = mujoco.MjData(m)
    total = 0.0
    try:
        for state, obj2id, eq_data, sleep in rec.states:
            mujoco.mj_setState(m, d, state, STATE)
            set_sleep(d, sleep)
            m.eq_obj2id[:] = obj2id
            m.eq_data[:] = eq_data
            t0 = time.perf_counter()
            mujoco.mj_step(m, d)
            total += time.perf_counter() - t0
    finally:
        m.eq_obj2id[:], m.eq_data[:] = keep
    return total / len(rec.states)
