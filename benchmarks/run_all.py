"""Run every benchmark in one process and print all figures, ratios included.

Run: ``make bench`` (= ``.venv/bin/python benchmarks/run_all.py``), or with
``--quick`` for a short pass (fewer sizes, actions, tasks and seeds).

Sections, in order: compile time vs objects (bench_compile), env step cost vs
bare mj_step (bench_env), the robots' primitive and IK (bench_robot), the oracle
per library task (bench_oracle), then a summary of the ratios. Ratios compare
figures measured side by side in this one run, so machine load affects both
sides alike; absolute wall times depend on the machine. Nothing asserts a time.
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_compile
import bench_env
import bench_oracle
import bench_robot

from factask.sim.robots.registry import ROBOTS


def _section(title: str) -> float:
    print(f"\n=== {title} " + "=" * max(0, 70 - len(title)), flush=True)
    return time.perf_counter()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="a short pass of every benchmark")
    parser.add_argument("--episodes", "-k", type=int, default=None,
                        help="oracle seeds per task (default 2, quick 1)")
    parser.add_argument("--skip-oracle", action="store_true",
                        help="leave out the oracle sweep over the library (the longest part)")
    args = parser.parse_args()
    start = time.perf_counter()
    print(f"factask benchmarks{' (quick)' if args.quick else ''}: python "
          f"{platform.python_version()}, {platform.machine()}, {os.cpu_count()} CPU cores, "
          f"MUJOCO_GL={os.environ.get('MUJOCO_GL', '')!r}")

    t = _section("compile time vs number of objects (bench_compile)")
    compile_rows = bench_compile.run(quick=args.quick)
    print(f"[{time.perf_counter() - t:.0f} s]")

    t = _section("env step cost vs bare mj_step (bench_env)")
    env_rows = bench_env.run(quick=args.quick)
    print(f"[{time.perf_counter() - t:.0f} s]")

    t = _section("robots: IK and pick-and-place primitive (bench_robot)")
    bench_robot.bench_ik()
    kinds = ("floating", "arm") if args.quick else tuple(ROBOTS)  # quick: fast + default arm
    for kind in kinds:
        bench_robot.bench_primitive(kind, 1 if args.quick else 2)
    print(f"[{time.perf_counter() - t:.0f} s]")

    oracle_rows: list[bench_oracle.OracleTiming] = []
    if not args.skip_oracle:
        t = _section("oracle per library task (bench_oracle)")
        oracle_rows = bench_oracle.run(quick=args.quick, episodes=args.episodes)
        print(f"[{time.perf_counter() - t:.0f} s]")

    _section("summary of ratios (measured side by side in this run)")
    for layout in bench_compile.LAYOUTS:
        rows = {r.n: r for r in compile_rows if r.layout == layout}
        parts = [f"n={n}: {1000 * r.total:.2f} ms ({1000 * r.total_cpu:.2f} ms CPU)"
                 + (f" (+ {1000 * r.validate:.2f} ms validating the graph)" if r.validate else "")
                 + (f", {r.mjcf / (r.total + r.validate):.1f}x faster than the MJCF path"
                    if r.mjcf else "")
                 for n, r in rows.items() if n in (10, 98, 200)]
        if parts:
            print(f"compile ({layout}): " + "; ".join(parts))
    for e in env_rows:
        print(f"env ({e.robot}): one physics step inside env.step costs {e.cpu_ratio:.2f}x a "
              f"bare mj_step from the same states in CPU time ({e.env_cpu_us:.0f} vs "
              f"{e.bare_cpu_us:.0f} us), {e.ratio:.2f}x in wall time ({e.env_step_us:.0f} vs "
              f"{e.bare_step_us:.0f} us); of it {e.replay_cpu_us / e.bare_cpu_us:.2f}x the same "
              f"steps replayed in sequence with nothing around them, "
              f"{e.env_cpu_us / e.replay_cpu_us:.2f}x what env.step adds around them; "
              f"{e.pick_place_sim_s:.2f} simulated s per pick-and-place (median), "
              f"{e.realtime_factor:.1f}x real time")
    for robot in ("floating", "arm"):
        rows_r = [r for r in oracle_rows if r.robot == robot and r.episodes]
        if rows_r:
            n_ep = sum(r.episodes for r in rows_r)
            wall = sum(r.wall_s * r.episodes for r in rows_r) / n_ep
            floor = sum(r.floor_s * r.episodes for r in rows_r) / n_ep
            cpu = sum(r.cpu_s * r.episodes for r in rows_r) / n_ep
            cpu_floor = sum(r.cpu_floor_s * r.episodes for r in rows_r) / n_ep
            print(f"oracle ({robot}): {wall:.3f} wall s per episode, physics lower bound "
                  f"{floor:.3f} s: {wall / floor:.2f}x the limit; CPU {cpu:.3f} s per episode, "
                  f"lower bound {cpu_floor:.3f} s: {cpu / cpu_floor:.2f}x")
    print(f"\ntotal {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
