"""The batched backend against the single env and ``mujoco.rollout``, measured in one run.

Run: ``.venv/bin/python benchmarks/bench_batch.py --device cpu`` (or ``--device cuda``
on a machine with an NVIDIA GPU; ``--quick`` for a smoke run).

For the stacking, placing and packing tasks (``stack-block-pyramid``,
``put-block-in-bowl``, ``packing-boxes``; ``--tasks`` to choose), on the device given:

- **first batch**: making the first batch, its first reset and its first step (with
  the step's graph capture): on a cold Warp kernel cache this is the kernels'
  compilation (minutes on a CPU, seconds on a GPU); printed apart from everything else.
- **physics**: world steps per second of the batch holding every world's cup still
  for ``--steps`` physics steps after a reset, for each ``num_envs``;
- **oracle**: :func:`factask.batch.oracle.run_oracle` from a reset of every world
  (seeds 0–255, repeated past 256 worlds) —
  episodes per second, success, lockstep actions, host planning time per action and
  per world, and the share of actions the scalar oracle planned (fallbacks);
- **planning at scale** (host only, no device): the plan of each lockstep action
  of the oracle's episode for ``num_envs`` worlds (the states of 16 seeds' episodes
  before each action, repeated to fill the worlds), the least of three; the slowest
  action, the mean, per world; and the batched status the plan reads;
- **single env, one core**: the same oracle one episode after another
  (:func:`factask.sim.episode.run_episode`), and bare ``mujoco.mj_step`` on the task's
  model from its reset state;
- **mujoco.rollout, all cores**: ``mujoco.rollout.rollout`` of the task's model from its
  reset state, one ``MjData`` per core.

Without a GPU the batch runs on Warp's CPU device with small ``num_envs`` (it steps
each world about a hundred times slower than one core's CPU MuJoCo: it is there for
correctness) and the table says so; planning at scale is measured to 4,096 worlds on
any machine. Writes ``benchmarks/results/batch-<device>.json`` and a plot
``benchmarks/results/img/batch-<device>.png``. Wall times depend on the machine and
its load; nothing here asserts a time.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path
from typing import Any

import mujoco
import numpy as np
from rich.console import Console
from rich.table import Table

from factask.batch.device import BatchBackendMissing, DeviceUnavailableError
from factask.batch.planner import LockstepPlanner
from factask.batch.scene import BatchScene
from factask.batch.status import check_task_batch
from factask.batch.targets import BatchTargets
from factask.library import get_task
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.oracle.scripted import Oracle, OracleAction

HERE = Path(__file__).resolve().parent
TASKS = ("stack-block-pyramid", "put-block-in-bowl", "packing-boxes")
#: Worlds per size: physics and oracle on the device, planning on the host.
SIZES = {"cpu": ((1, 16), (1, 8), (1, 16, 256, 4096)),
         "cuda": ((1, 16, 256, 4096, 32768), (1, 16, 256, 4096), (1, 16, 256, 4096))}
QUICK = ((1, 4), (1, 2), (1, 16, 256))
#: Distinct layouts behind the planning at scale (repeated to fill the worlds).
LAYOUTS = 16


def _timed(fn: Any, *args: Any, **kwargs: Any) -> tuple[Any, float]:
    start = time.perf_counter()
    out = fn(*args, **kwargs)
    return out, time.perf_counter() - start


def first_batch(task: str, device: str) -> dict[str, float]:
    """Make, reset and step a first batch: Warp compiles its kernels here when cold."""
    from factask.batch.env import make_batch

    batch, make = _timed(make_batch, task, 1, device=device)
    _, reset = _timed(batch.reset, seed=0)
    _, step = _timed(batch.step, batch.home_command(), 2)
    return {"make_s": make, "reset_s": reset, "first_step_s": step}


def physics(task: str, device: str, sizes: tuple[int, ...], steps: int) -> list[dict]:
    """World steps per second of the batch, the cups held still after a reset."""
    from factask.batch.env import make_batch

    rows = []
    for n in sizes:
        batch = make_batch(task, n, device=device)
        batch.reset(seed=[k % LAYOUTS for k in range(n)])
        cmd = batch.home_command()
        batch.step(cmd, 2)  # the captured graph
        _, took = _timed(batch.step, cmd, steps)
        rows.append({"task": task, "num_envs": n, "world_steps_per_s": n * steps / took})
    return rows


def oracle(task: str, device: str, sizes: tuple[int, ...]) -> list[dict]:
    """The lockstep oracle from a reset of every world."""
    from factask.batch.env import make_batch
    from factask.batch.oracle import run_oracle

    rows = []
    for n in sizes:
        batch = make_batch(task, n, device=device)
        # Up to 256 layouts (a reset is the single env's, one world after another;
        # a seed repeated is reset once): the episodes' work, not the resets', is timed.
        batch.reset(seed=[k % 256 for k in range(n)])
        result, took = _timed(run_oracle, batch)
        planned = result.planned_arrays + result.planned_fallback
        plan = np.array(result.planning_seconds) / n
        rows.append({"task": task, "num_envs": n, "episodes_per_s": n / took,
                     "success": float(result.success.mean()),
                     "lockstep_actions": len(result.planning_seconds),
                     "planning_us_per_world": float(plan.mean() * 1e6) if len(plan) else 0.0,
                     "fallback_share": result.planned_fallback / planned if planned else 0.0,
                     "world_steps_per_s": n * result.sim_steps / took})
    return rows


def _episode_states(graph: Any, env: FactaskEnv, seed: int) -> list[tuple]:
    """The state before each action of the oracle's episode on ``seed``: poses,
    held objects, reached factors."""
    env.reset(seed=seed)
    oracle = Oracle(env, seed=seed)
    states = []
    for _ in range(graph.max_actions()):
        state = (env.object_poses(), env.held_objects(), set(env.status().reached))
        planned = oracle.plan()
        if not isinstance(planned, OracleAction):
            break
        states.append(state)
        env.step(planned.as_env_action())
    return states


def planning(task: str, sizes: tuple[int, ...]) -> list[dict]:
    """Host time of each lockstep action's plan over ``num_envs`` worlds (the states
    of 16 seeds' oracle episodes before each action, repeated to fill the worlds;
    worlds whose episode ended are not planned), and of the status it reads."""
    graph = get_task(task)
    env = FactaskEnv(graph)
    episodes = []
    for s in range(LAYOUTS):
        states = _episode_states(graph, env, s)
        episodes.append((dict(env.solved), states))
    names = list(env.object_names)
    objects = {n: env.objects[n] for n in names}
    env.close()
    rows = []
    length = max(len(states) for _, states in episodes)
    for n in sizes:
        solved = [episodes[k % LAYOUTS][0] for k in range(n)]
        targets = {f.name: BatchTargets.stack([s[f.name] for s in solved])
                   for f in graph.factors}
        per_action, checks, fallbacks = [], [], 0
        for a in range(length):
            states = [episodes[k % LAYOUTS][1][min(a, len(episodes[k % LAYOUTS][1]) - 1)]
                      for k in range(n)]
            running = np.array([a < len(episodes[k % LAYOUTS][1]) for k in range(n)])
            scene = BatchScene.from_poses(objects, [st[0] for st in states],
                                          [st[1] for st in states])
            reached = np.array([[f in st[2] for f in graph.factor_names()] for st in states])
            best_plan, best_check = np.inf, np.inf
            for _ in range(3):
                status, took = _timed(check_task_batch, graph, targets, scene, reached)
                best_check = min(best_check, took)
                planner = LockstepPlanner(graph, objects, names, solved, list(range(n)))
                plan, took = _timed(planner.plan, scene, status, running)
                best_plan = min(best_plan, took)
            per_action.append(best_plan)
            checks.append(best_check)
            fallbacks += int(plan.fallback.sum())
        rows.append({"task": task, "num_envs": n, "actions": length,
                     "plan_s_max": max(per_action), "plan_s_mean": float(np.mean(per_action)),
                     "plan_us_per_world": max(per_action) / n * 1e6,
                     "status_s_max": max(checks),
                     "fallback_share": fallbacks / max(1, n * length)})
    return rows


def single(task: str, episodes: int, steps: int) -> dict[str, float]:
    """The single env on one core: oracle episodes one after another, and bare
    ``mj_step`` from its reset state."""
    graph = get_task(task)
    env = FactaskEnv(graph)
    start = time.perf_counter()
    ok = sum(run_episode(graph, s, env=env).success for s in range(episodes))
    per_episode = (time.perf_counter() - start) / episodes
    env.reset(seed=0)
    data = mujoco.MjData(env.model)
    state = np.empty(mujoco.mj_stateSize(env.model, mujoco.mjtState.mjSTATE_FULLPHYSICS))
    mujoco.mj_getState(env.model, env.data, state, mujoco.mjtState.mjSTATE_FULLPHYSICS)
    mujoco.mj_setState(env.model, data, state, mujoco.mjtState.mjSTATE_FULLPHYSICS)
    start = time.perf_counter()
    for _ in range(steps):
        mujoco.mj_step(env.model, data)
    step_rate = steps / (time.perf_counter() - start)
    rollout_rate = _rollout(env.model, env.data, steps)
    env.close()
    return {"task": task, "episodes_per_s": 1.0 / per_episode, "success": ok / episodes,
            "world_steps_per_s": step_rate, "rollout_world_steps_per_s": rollout_rate,
            "rollout_threads": os.cpu_count() or 1}


def _rollout(model: mujoco.MjModel, data: mujoco.MjData, steps: int) -> float:
    """World steps per second of ``mujoco.rollout`` on every core, from ``data``'s state."""
    from mujoco import rollout

    threads = os.cpu_count() or 1
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state = np.empty(mujoco.mj_stateSize(model, spec))
    mujoco.mj_getState(model, data, state, spec)
    nbatch = 8 * threads
    initial = np.tile(state, (nbatch, 1))
    datas = [mujoco.MjData(model) for _ in range(threads)]
    rollout.rollout(model, datas, initial, nstep=2)  # the thread pool's start
    _, took = _timed(rollout.rollout, model, datas, initial, nstep=steps)
    return nbatch * steps / took


def _table(console: Console, title: str, rows: list[dict], keys: list[str]) -> None:
    table = Table(title=title)
    for k in keys:
        table.add_column(k.replace("_", " "), justify="right" if k != "task" else "left")
    for r in rows:
        table.add_row(*[f"{r[k]:,.4g}" if isinstance(r[k], float) else str(r[k]) for k in keys])
    console.print(table)


def plot(result: dict, path: Path) -> None:
    """World steps/s and planning time per world against the number of worlds."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for task in result["tasks"]:
        rows = [r for r in result["physics"] if r["task"] == task]
        left.plot([r["num_envs"] for r in rows], [r["world_steps_per_s"] for r in rows],
                  marker="o", label=f"batch ({result['device']}): {task}")
        one = next(r for r in result["single"] if r["task"] == task)
        left.axhline(one["world_steps_per_s"], linestyle=":", color="grey")
        left.axhline(one["rollout_world_steps_per_s"], linestyle="--", color="black")
        rows = [r for r in result["planning"] if r["task"] == task]
        right.plot([r["num_envs"] for r in rows], [r["plan_us_per_world"] for r in rows],
                   marker="o", label=task)
    left.plot([], [], ":", color="grey", label="single env, one core (mj_step)")
    left.plot([], [], "--", color="black", label="mujoco.rollout, all cores")
    left.set(xscale="log", yscale="log", xlabel="worlds", ylabel="world steps / s",
             title="physics")
    right.axhline(50, linestyle="--", color="red", label="50 us per world (issue 39)")
    right.set(xscale="log", yscale="log", xlabel="worlds", ylabel="us per world",
              title="planning the slowest lockstep action (host)")
    for ax, key in ((left, "physics"), (right, "planning")):
        sizes = sorted({r["num_envs"] for r in result[key]})
        ax.set_xticks(sizes, [f"{n:,}" for n in sizes])
        ax.minorticks_off()
    left.legend(fontsize=7)
    right.legend(fontsize=7)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--device", default="cpu", help="cpu, cuda or cuda:N")
    parser.add_argument("--tasks", default=",".join(TASKS), help="comma-separated names")
    parser.add_argument("--steps", type=int, default=200, help="physics steps timed")
    parser.add_argument("--quick", action="store_true", help="small sizes: a smoke run")
    parser.add_argument("--out", type=Path, default=HERE / "results")
    args = parser.parse_args(argv)
    console = Console(width=150)
    kind = "cuda" if args.device.startswith("cuda") else "cpu"
    phys_sizes, oracle_sizes, plan_sizes = QUICK if args.quick else SIZES[kind]
    tasks = args.tasks.split(",")
    if kind == "cpu":
        console.print("[yellow]No GPU: the batch runs on Warp's CPU device, with "
                      f"{', '.join(map(str, phys_sizes))} worlds (it is there for correctness, "
                      "not speed); planning is measured to "
                      f"{max(plan_sizes):,} worlds on the host.[/yellow]")
    try:
        compile_times = first_batch(tasks[0], args.device)
    except (BatchBackendMissing, DeviceUnavailableError) as exc:
        console.print(f"[red]{exc}[/red]")
        return 2
    console.print(f"first batch ({tasks[0]}, 1 world): make {compile_times['make_s']:.1f} s, "
                  f"reset {compile_times['reset_s']:.1f} s, first step + capture "
                  f"{compile_times['first_step_s']:.1f} s (Warp's kernels compile here on a "
                  "cold cache)")
    result: dict[str, Any] = {"device": args.device, "tasks": tasks, "first_batch": compile_times,
                              "cpu_count": os.cpu_count(), "physics": [], "oracle": [],
                              "planning": [], "single": []}
    for task in tasks:
        result["physics"] += physics(task, args.device, phys_sizes, args.steps)
        result["oracle"] += oracle(task, args.device, oracle_sizes)
        result["planning"] += planning(task, plan_sizes)
        result["single"].append(single(task, 3 if args.quick else 8, 2000))
        console.print(f"[green]{task} done[/green]")
    _table(console, f"physics on {args.device} (cups held still)", result["physics"],
           ["task", "num_envs", "world_steps_per_s"])
    _table(console, f"oracle in lockstep on {args.device}", result["oracle"],
           ["task", "num_envs", "episodes_per_s", "success", "lockstep_actions",
            "planning_us_per_world", "fallback_share", "world_steps_per_s"])
    _table(console, "planning each lockstep action on the host (slowest action of the episode; "
           "16 seeds' episode states repeated)", result["planning"],
           ["task", "num_envs", "actions", "plan_s_max", "plan_s_mean", "plan_us_per_world",
            "status_s_max", "fallback_share"])
    _table(console, f"single env, one core; mujoco.rollout on {os.cpu_count()} cores",
           result["single"], ["task", "episodes_per_s", "success", "world_steps_per_s",
                              "rollout_world_steps_per_s"])
    name = f"batch-{kind}{'-quick' if args.quick else ''}"
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / f"{name}.json").write_text(json.dumps(result, indent=1))
    plot(result, args.out / "img" / f"{name}.png")
    console.print(f"wrote {args.out / (name + '.json')} and {args.out / 'img' / (name + '.png')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
