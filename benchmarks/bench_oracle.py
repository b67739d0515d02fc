"""Measure the scripted oracle: wall time per episode for each library task.

Run: ``.venv/bin/python benchmarks/bench_oracle.py [--quick] [--episodes K]
[--robot floating|arm|both] [--tasks a,b,...]``.

For every library task and robot, one environment is compiled (its time is the
``compile s`` column) and the oracle runs episodes with seeds ``0 .. K-1``
(default K = 2). Printed per row: mean wall seconds per episode (reset + oracle
planning + physics), mean simulated seconds per episode (the actions' physics
time), mean pick-and-place actions per episode and the success rate
(total reward >= 0.99), and the physics lower bound of an episode (its physics
steps x a bare ``mj_step`` from the states it went through, :mod:`physics_floor`,
measured by replaying the same seeds) with wall / lower bound; the same in this
thread's CPU time (what other jobs on a shared machine cannot inflate). Each
episode runs 3 times (same seed, same work) and its least time is kept. The plot
``benchmarks/out/oracle_vs_physics.png`` shows both per row. Rows are printed as
they finish; totals at the end.
``--quick`` runs three small tasks with K = 1. Wall times depend on the machine
and its load; nothing here asserts a time.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import physics_floor

from factask.library import get_task, task_names
from factask.sim.env import FactaskEnv
from factask.sim.episode import EpisodeResult, run_episode
from factask.vocabulary.errors import FactaskError

#: The fast robot and the default arm (two names of :data:`factask.sim.robots.registry.ROBOTS`).
ROBOTS = ("floating", "arm")
#: Tasks of ``--quick``: one placing, one stacking, one structure task.
QUICK_TASKS = ("place-red-in-green", "rainbow-stack", "build-bridge")
#: Where the wall-vs-physics plot goes.
PLOT = Path(__file__).resolve().parent / "out" / "oracle_vs_physics.png"


@dataclass(frozen=True)
class OracleTiming:
    """Oracle figures of one (task, robot) pair."""

    task: str
    robot: str
    compile_s: float
    wall_s: float
    sim_s: float
    actions: float
    success_rate: float
    episodes: int
    error: str | None = None
    floor_s: float = float("nan")
    cpu_s: float = float("nan")
    cpu_floor_s: float = float("nan")

    @property
    def overhead(self) -> float:
        """Wall time over the physics lower bound (1.0: nothing but physics)."""
        return self.wall_s / self.floor_s if self.floor_s > 0 else float("nan")

    @property
    def cpu_overhead(self) -> float:
        """CPU time over the physics lower bound in CPU time."""
        return self.cpu_s / self.cpu_floor_s if self.cpu_floor_s > 0 else float("nan")


def bench_task(task: str, robot: str, episodes: int, repeats: int = 3) -> OracleTiming:
    """Compile ``task`` once for ``robot`` and time ``episodes`` oracle episodes (each
    run ``repeats`` times, its least wall and CPU time kept)."""
    try:
        t0 = time.perf_counter()
        env = FactaskEnv(get_task(task), robot=robot)
        compile_s = time.perf_counter() - t0
    except FactaskError as exc:
        return OracleTiming(task, robot, 0.0, 0.0, 0.0, 0.0, 0.0, 0, f"compile: {exc}")
    try:
        walls: list[float] = []
        cpus: list[float] = []
        results: list[EpisodeResult] = []
        for seed in range(episodes):
            # The same episode (same seed: the same work) `repeats` times, the least kept.
            best_w = best_c = math.inf
            for _ in range(repeats):
                w0, c0 = time.perf_counter(), time.thread_time()
                result = run_episode(env.graph, seed, robot=robot, env=env)
                best_c = min(best_c, time.thread_time() - c0)
                best_w = min(best_w, time.perf_counter() - w0)
            results.append(result)
            walls.append(best_w)
            cpus.append(best_c)
        # Same episodes again (deterministic) to count their physics steps and time a
        # bare mj_step from the states they pass through: the physics lower bound.
        floors, cpu_floors = [], []
        for seed in range(episodes):
            with physics_floor.record(every=20) as rec:
                run_episode(env.graph, seed, robot=robot, env=env)
            cost = physics_floor.bare_step_cost(rec)
            floors.append(rec.steps * cost.wall)
            cpu_floors.append(rec.steps * cost.cpu)
    finally:
        env.close()
    failures = [r.failure for r in results if not r.success and r.failure]
    return OracleTiming(
        task=task, robot=robot, compile_s=compile_s, wall_s=statistics.fmean(walls),
        sim_s=statistics.fmean(r.sim_seconds for r in results),
        actions=statistics.fmean(r.steps for r in results),
        success_rate=sum(r.success for r in results) / len(results), episodes=len(results),
        error=failures[0] if failures else None, floor_s=statistics.fmean(floors),
        cpu_s=statistics.fmean(cpus), cpu_floor_s=statistics.fmean(cpu_floors),
    )


HEADER = (f"{'task':42s} {'robot':8s} {'compile s':>9s} {'wall s/ep':>9s} {'floor s':>7s} "
          f"{'wall/floor':>10s} {'cpu s/ep':>8s} {'cpu/floor':>9s} {'sim s/ep':>8s} "
          f"{'actions/ep':>10s} {'success':>7s}")


def format_row(t: OracleTiming) -> str:
    """One aligned table row (with the first failure reason, shortened, if any)."""
    row = (f"{t.task:42s} {t.robot:8s} {t.compile_s:9.3f} {t.wall_s:9.3f} {t.floor_s:7.3f} "
           f"{t.overhead:10.2f} {t.cpu_s:8.3f} {t.cpu_overhead:9.2f} {t.sim_s:8.1f} "
           f"{t.actions:10.1f} {t.success_rate:7.0%}")
    if t.error:
        row += f"  ({t.error[:70]})"
    return row


def run(quick: bool = False, episodes: int | None = None, robots: tuple[str, ...] = ROBOTS,
        tasks: list[str] | None = None, plot_path: Path | None = PLOT) -> list[OracleTiming]:
    """Measure, printing rows as they finish and totals at the end."""
    names = tasks or (list(QUICK_TASKS) if quick else task_names())
    k = episodes or (1 if quick else 2)
    print(f"oracle wall time per episode ({len(names)} tasks, seeds 0..{k - 1})")
    print(HEADER)
    out = []
    for robot in robots:
        for name in names:
            t = bench_task(name, robot, k, repeats=3 if quick else 1)
            out.append(t)
            print(format_row(t), flush=True)
            sys.stdout.flush()
    for robot in robots:
        rows = [t for t in out if t.robot == robot and t.episodes]
        if not rows:
            continue
        n_ep = sum(t.episodes for t in rows)
        wall = sum(t.wall_s * t.episodes for t in rows)
        sim = sum(t.sim_s * t.episodes for t in rows)
        acts = sum(t.actions * t.episodes for t in rows)
        ok = sum(t.success_rate * t.episodes for t in rows)
        floor = sum(t.floor_s * t.episodes for t in rows)
        cpu = sum(t.cpu_s * t.episodes for t in rows)
        cpu_floor = sum(t.cpu_floor_s * t.episodes for t in rows)
        print(f"{robot}: {n_ep} episodes, mean {wall / n_ep:.3f} wall s/episode, physics "
              f"lower bound {floor / n_ep:.3f} s ({wall / floor:.2f}x); CPU "
              f"{cpu / n_ep:.3f} s/episode, lower bound {cpu_floor / n_ep:.3f} s "
              f"({cpu / cpu_floor:.2f}x); "
              f"{sim / n_ep:.1f} sim s/episode ({sim / wall:.1f}x real time), "
              f"{wall / acts:.2f} wall s/action, success {ok / n_ep:.0%}, "
              f"compile mean {statistics.fmean(t.compile_s for t in rows):.2f} s")
    if plot_path is not None and out:
        plot(out, plot_path)
        print(f"plot: {plot_path}")
    return out


def plot(rows: list[OracleTiming], path: Path) -> None:
    """Save wall time per episode beside its physics lower bound, per task and robot.

    Args:
        rows: Timings from :func:`run`.
        path: Where the PNG goes.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = [r for r in rows if r.episodes]
    labels = [f"{r.task} ({r.robot})" for r in rows]
    y = range(len(rows))
    fig, ax = plt.subplots(figsize=(7.0, 1.8 + 0.45 * len(rows)), dpi=110)
    ax.barh([i - 0.27 for i in y], [r.wall_s for r in rows], height=0.27, color="tab:blue",
            label="wall s per episode (reset + oracle + physics)")
    ax.barh(list(y), [r.cpu_s for r in rows], height=0.27, color="tab:orange",
            label="CPU s per episode (what other jobs cannot add)")
    ax.barh([i + 0.27 for i in y], [r.cpu_floor_s for r in rows], height=0.27,
            color="tab:gray", label="physics lower bound (steps x bare mj_step, CPU)")
    for i, r in zip(y, rows, strict=True):
        ax.text(r.cpu_s, i, f" {r.cpu_overhead:.2f}x", va="center", fontsize=7)
    ax.set_yticks(list(y), labels, fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("seconds")
    ax.set_title("Oracle episode: time vs the physics limit")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=1)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help=f"tasks {QUICK_TASKS}, K = 1")
    parser.add_argument("--episodes", "-k", type=int, default=None, help="seeds per task")
    parser.add_argument("--robot", choices=[*ROBOTS, "both"], default="both")
    parser.add_argument("--tasks", default=None, help="comma-separated library task names")
    args = parser.parse_args()
    robots = ROBOTS if args.robot == "both" else (args.robot,)
    tasks = [t.strip() for t in args.tasks.split(",") if t.strip()] if args.tasks else None
    run(args.quick, args.episodes, robots, tasks)


if __name__ == "__main__":
    main()
