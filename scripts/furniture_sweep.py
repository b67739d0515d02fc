"""The oracle on every library task with furniture (drawers, doors, switches, shelves),
with both robots, on seeds no test uses: the issue-38 bar is 9 of 10 per task and robot.

Writes ``benchmarks/results/furniture-sweep.json`` (task/robot -> successes) and
prints one line per task and robot. Run with::

    .venv/bin/python scripts/furniture_sweep.py [--seed 100] [--episodes 10]
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from factask.library.builders import FAMILIES
from factask.library.tasks import get_task
from factask.sim.episode import evaluate_task

#: The catalogue families whose tasks have furniture with moving parts or levels.
FURNITURE_FAMILIES = ("articulated", "switches", "furniture")
OUT = Path(__file__).resolve().parents[1] / "benchmarks" / "results" / "furniture-sweep.json"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=100, help="first seed")
    parser.add_argument("--episodes", type=int, default=10, help="episodes per task and robot")
    args = parser.parse_args()
    names = sorted(n for n, f in FAMILIES.items() if f in FURNITURE_FAMILIES)
    results: dict[str, int] = {}
    for name in names:
        for robot in ("floating", "arm"):
            start = time.monotonic()
            run = evaluate_task(get_task(name), episodes=args.episodes, seed=args.seed,
                                robot=robot)
            results[f"{name}/{robot}"] = sum(e.success for e in run.episodes)
            print(f"{name:45s} {robot:8s} {results[f'{name}/{robot}']}/{args.episodes} "
                  f"({time.monotonic() - start:.0f} s)", flush=True)
    below = [k for k, v in results.items() if v < 0.9 * args.episodes]
    OUT.write_text(json.dumps({"seed": args.seed, "episodes": args.episodes,
                               "results": results, "below_bar": below}, indent=1) + "\n")
    print(f"{len(names)} tasks; below 9/10: {below or 'none'}; wrote {OUT}")


if __name__ == "__main__":
    main()
