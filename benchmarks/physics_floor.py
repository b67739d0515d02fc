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

Both sides are timed in wall time and in this thread's CPU time
(``time.thread_time``): on a machine shared with other jobs, a long run is
preempted while a 30-microsecond step rarely is, so the wall ratio there says
more about the load than about factask; the CPU ratio compares like with like.
Each state's step is timed a few times and the least kept; runs are repeated
and their least kept too.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterator
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

    def counting(m: mujoco.MjModel, d: mujoco.MjData, nstep: int = 1) -> None:
        # mj_step(m, d, n) is n single steps: split it so every kept state is one.
        for _ in range(nstep):
            if rec.steps % rec.every == 0:
                state = np.empty(mujoco.mj_stateSize(m, STATE))
                mujoco.mj_getState(m, d, state, STATE)
                rec.model = m
                rec.states.append((state, m.eq_obj2id.copy(), m.eq_data.copy(), get_sleep(d)))
            rec.steps += 1
            original(m, d)

    mujoco.mj_step = counting
    try:
        yield rec
    finally:
        mujoco.mj_step = original


@dataclass(frozen=True)
class StepCost:
    """Seconds per bare ``mj_step``: wall time and this thread's CPU time."""

    wall: float
    cpu: float


def clock_overhead(clock: Callable[[], float], samples: int = 2000) -> float:
    """The least time two back-to-back calls of ``clock`` measure (subtracted from
    each timed step, which is only tens of microseconds)."""
    best = math.inf
    for _ in range(samples):
        t0 = clock()
        best = min(best, clock() - t0)
    return best


def bare_step_times(rec: Recording, repeats: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """Seconds of one bare ``mj_step`` from each recorded state (wall, CPU).

    Each state is stepped ``repeats`` times and its least time kept (the one least
    disturbed by other jobs on the machine). Callers that time the run itself
    several times can take this once per round and keep each state's least time
    over the rounds: both sides are then measured under the same load.

    Args:
        rec: A recording.
        repeats: Timed steps per state.

    Returns:
        Two arrays, one entry per recorded state (empty when nothing was recorded).
    """
    n = len(rec.states)
    walls, cpus = np.zeros(n), np.zeros(n)
    if not n:
        return walls, cpus
    m = rec.model
    keep = m.eq_obj2id.copy(), m.eq_data.copy()
    d = mujoco.MjData(m)
    wall_0, cpu_0 = clock_overhead(time.perf_counter), clock_overhead(time.thread_time)
    try:
        for i, (state, obj2id, eq_data, sleep) in enumerate(rec.states):
            m.eq_obj2id[:] = obj2id
            m.eq_data[:] = eq_data
            best_w = best_c = math.inf
            for _ in range(repeats):
                mujoco.mj_setState(m, d, state, STATE)
                set_sleep(d, sleep)
                w0, c0 = time.perf_counter(), time.thread_time()
                mujoco.mj_step(m, d)
                c1, w1 = time.thread_time(), time.perf_counter()
                best_w, best_c = min(best_w, w1 - w0), min(best_c, c1 - c0)
            # The wall interval holds two CPU-clock reads, the CPU interval none.
            walls[i] = max(best_w - wall_0 - 2 * cpu_0, 0.0)
            cpus[i] = max(best_c - cpu_0, 0.0)
    finally:
        m.eq_obj2id[:], m.eq_data[:] = keep
    return walls, cpus


def bare_step_cost(rec: Recording, repeats: int = 3) -> StepCost:
    """Mean cost of one bare ``mj_step`` from each recorded state
    (:func:`bare_step_times`, averaged).

    Args:
        rec: A recording with at least one state.
        repeats: Timed steps per state.

    Returns:
        Seconds per step (NaN when nothing was recorded).
    """
    if not rec.states:
        return StepCost(math.nan, math.nan)
    walls, cpus = bare_step_times(rec, repeats)
    return StepCost(float(walls.mean()), float(cpus.mean()))


#: The inputs a caller sets between steps (controls, mocap poses, equality switches,
#: applied forces): what a replay restores before each recorded ``mj_step`` call.
INPUTS = mujoco.mjtState.mjSTATE_USER


@dataclass
class InputLog:
    """A run as the physics saw it: its start and, per ``mj_step`` call, the inputs
    set before it and the step count (see :func:`record_inputs`)."""

    model: Any = None
    start: tuple[np.ndarray, np.ndarray, np.ndarray, dict[str, Any]] | None = None
    #: (steps, inputs, (eq_obj2id, eq_data) when the suction weld changed, else None).
    calls: list[tuple[int, np.ndarray, tuple[np.ndarray, np.ndarray] | None]] = field(
        default_factory=list)
    end_qpos: np.ndarray | None = None

    @property
    def steps(self) -> int:
        """Physics steps of the run."""
        return sum(n for n, _, _ in self.calls)


@contextmanager
def record_inputs(model: mujoco.MjModel, data: mujoco.MjData) -> Iterator[InputLog]:
    """Record what the physics of a run needs to be replayed without the code around
    it: the state at the start, and before each ``mujoco.mj_step`` call its inputs
    (:data:`INPUTS`) and the suction weld when it changed (it lives in the model).

    Args:
        model: The run's model.
        data: Its data, in the state the run starts from.

    Yields:
        The log, filled while the block runs (``end_qpos`` when it ends).
    """
    state = np.empty(mujoco.mj_stateSize(model, STATE))
    mujoco.mj_getState(model, data, state, STATE)
    log = InputLog(model, (state, model.eq_obj2id.copy(), model.eq_data.copy(),
                           get_sleep(data)))
    size = mujoco.mj_stateSize(model, INPUTS)
    last = [model.eq_obj2id.copy(), model.eq_data.copy()]
    original = mujoco.mj_step

    def logging(m: mujoco.MjModel, d: mujoco.MjData, nstep: int = 1) -> None:
        inputs = np.empty(size)
        mujoco.mj_getState(m, d, inputs, INPUTS)
        weld = None
        if not (np.array_equal(m.eq_obj2id, last[0]) and np.array_equal(m.eq_data, last[1])):
            last[:] = m.eq_obj2id.copy(), m.eq_data.copy()
            weld = (last[0], last[1])
        log.calls.append((nstep, inputs, weld))
        original(m, d, nstep)

    mujoco.mj_step = logging
    try:
        yield log
    finally:
        mujoco.mj_step = original
        log.end_qpos = data.qpos.copy()


def replay_time(log: InputLog) -> tuple[StepCost, float]:
    """Time a replay of a recorded run: from its start, each ``mj_step`` call with its
    inputs restored (one ``mj_setState``) and nothing else -- the run's steps in
    sequence, as the physics does them, without the planning, checks and bookkeeping
    around them.

    Args:
        log: A run recorded by :func:`record_inputs`.

    Returns:
        (seconds per step, wall and CPU; the largest difference in m or rad of any
        ``qpos`` from the run's own end: how faithful the replay was).
    """
    m = log.model
    assert log.start is not None and log.end_qpos is not None
    state, obj2id, eq_data, sleep = log.start
    keep = m.eq_obj2id.copy(), m.eq_data.copy()
    d = mujoco.MjData(m)
    step, set_state = mujoco.mj_step, mujoco.mj_setState
    try:
        set_state(m, d, state, STATE)
        set_sleep(d, sleep)
        m.eq_obj2id[:], m.eq_data[:] = obj2id, eq_data
        w0, c0 = time.perf_counter(), time.thread_time()
        for n, inputs, weld in log.calls:
            if weld is not None:
                m.eq_obj2id[:], m.eq_data[:] = weld
            set_state(m, d, inputs, INPUTS)
            step(m, d, n)
        c1, w1 = time.thread_time(), time.perf_counter()
    finally:
        m.eq_obj2id[:], m.eq_data[:] = keep
    steps = max(log.steps, 1)
    drift = float(np.abs(d.qpos - log.end_qpos).max())
    return StepCost((w1 - w0) / steps, (c1 - c0) / steps), drift
