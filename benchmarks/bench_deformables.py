"""Step cost of deformable scenes: a 20-segment rope and a 50-block pile (issue 15).

Compiles four scenes with the floating cup (the bare robot on a table; a
50-block pile; a 20-segment rope; both), resets each (seed 0: the pile as a
cluster, the rope straight, everything resting) and times ``mujoco.mj_step``
from that state: the best of ``--repeats`` runs of ``--steps`` steps, in wall
and in this thread's CPU time (``time.thread_time``), per step, and as a ratio
to the bare scene. A resting pile's blocks sleep when MuJoCo's sleeping is on;
the "stirred" column times the same scene with every free body woken and
given a small random velocity (a push in progress).

    .venv/bin/python benchmarks/bench_deformables.py [--steps 2000] [--repeats 3]
"""

from __future__ import annotations

import argparse
import time

import mujoco
import numpy as np

from factask.graph import parse_graph
from factask.graph.taskgraph import TaskGraph
from factask.sim.env import FactaskEnv

ZONE = {"name": "green_zone", "kind": "zone", "color": "green"}
PILE = {"name": "red_pile", "kind": "pile", "color": "red", "count": 50}
ROPE = {"name": "blue_rope", "kind": "rope", "color": "blue", "count": 20}
LINE = {"name": "blue_line", "kind": "line", "color": "blue"}


def scene(name: str, pile: bool, rope: bool) -> TaskGraph:
    """A graph with a zone (and a line), a pile and/or a rope, one goal each."""
    variables: list[dict] = [ZONE, LINE]
    factors: list[dict] = []
    if pile:
        variables.append(PILE)
        factors.append({"name": "sweep", "goal": {"type": "pile_in_zone",
                                                  "objects": ["red_pile"],
                                                  "zone": "green_zone"}})
    if rope:
        variables.append(ROPE)
        factors.append({"name": "lay", "goal": {"type": "rope_along",
                                                "objects": ["blue_rope"],
                                                "along": "blue_line"}})
    if not factors:  # a bare scene: one flat marker goal keeps the graph valid
        variables.append({"name": "marker", "kind": "block"})
        factors.append({"name": "f", "goal": {"type": "in_zone", "objects": ["marker"],
                                              "zone": "green_zone"}})
    for f in factors:
        f["weight"] = 1.0 / len(factors)
    return parse_graph({"name": name.replace("+", "-"), "variables": variables,
                        "factors": factors})


def time_steps(m: mujoco.MjModel, d: mujoco.MjData, state: np.ndarray, steps: int,
               repeats: int, stir: bool) -> tuple[float, float]:
    """Best (wall, CPU) seconds per step over ``repeats`` runs from ``state``."""
    rng = np.random.default_rng(0)
    best_wall = best_cpu = float("inf")
    spec = mujoco.mjtState.mjSTATE_INTEGRATION
    for _ in range(repeats):
        mujoco.mj_setState(m, d, state, spec)
        if stir:
            d.qvel[:] = rng.normal(0.0, 0.05, size=m.nv)
        w0, c0 = time.perf_counter(), time.thread_time()
        mujoco.mj_step(m, d, steps)
        w1, c1 = time.perf_counter(), time.thread_time()
        best_wall = min(best_wall, (w1 - w0) / steps)
        best_cpu = min(best_cpu, (c1 - c0) / steps)
    return best_wall, best_cpu


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--steps", type=int, default=2000, help="steps per timed run")
    ap.add_argument("--repeats", type=int, default=3, help="timed runs (the best is kept)")
    args = ap.parse_args()
    rows = []
    for name, pile, rope in (("bare", False, False), ("pile50", True, False),
                             ("rope20", False, True), ("pile50+rope20", True, True)):
        env = FactaskEnv(scene(name, pile, rope))
        env.reset(seed=0)
        m, d = env.model, env.data
        state = np.empty(mujoco.mj_stateSize(m, mujoco.mjtState.mjSTATE_INTEGRATION))
        mujoco.mj_getState(m, d, state, mujoco.mjtState.mjSTATE_INTEGRATION)
        rest = time_steps(m, d, state, args.steps, args.repeats, stir=False)
        stirred = time_steps(m, d, state, args.steps, args.repeats, stir=True)
        rows.append((name, m.nbody, m.neq, rest, stirred))
        env.close()
    base_rest, base_stir = rows[0][3][1], rows[0][4][1]
    print(f"{'scene':<15}{'bodies':>7}{'eq':>5}{'rest us/step':>14}{'cpu x bare':>11}"
          f"{'stirred us/step':>17}{'cpu x bare':>11}")
    for name, nbody, neq, rest, stirred in rows:
        print(f"{name:<15}{nbody:>7}{neq:>5}{rest[1] * 1e6:>14.1f}{rest[1] / base_rest:>11.2f}"
              f"{stirred[1] * 1e6:>17.1f}{stirred[1] / base_stir:>11.2f}")


if __name__ == "__main__":
    main()
