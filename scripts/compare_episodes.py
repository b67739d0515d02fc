"""Prove that a change left the oracle's seeded episodes untouched.

    python scripts/compare_episodes.py record OUT.json [--robots floating,arm] [--episodes 2]
    python scripts/compare_episodes.py compare BEFORE.json AFTER.json
    python scripts/compare_episodes.py against REF [--robots ...] [--episodes ...]

``record`` runs the oracle over every library task (seeds 0..N-1, as
``factask eval-library`` does) for each robot and writes a fingerprint per
episode: success, every factor satisfied, the number of actions, the total reward
after every action (full precision), the final per-factor progress and the
oracle's failure. ``compare`` prints every difference and exits 1 if there is
any. ``against REF`` records git ref REF (in a temporary worktree, its own
``src`` on PYTHONPATH) and the working tree, and compares them.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]


def _record_task(args: tuple[str, str, int]) -> tuple[str, str, Any]:
    import factask as ft

    name, robot, episodes = args
    graph = ft.get_task(name)
    out = []
    try:
        env = ft.FactaskEnv(graph, robot=robot)
        try:
            for seed in range(episodes):
                rewards: list[str] = []

                def on_action(_i: int, _planned: Any, info: dict[str, Any],
                              rewards: list[str] = rewards) -> None:
                    rewards.append(repr(float(info["total_reward"])))

                r = ft.run_episode(graph, seed, robot=robot, env=env, on_action=on_action)
                out.append({"seed": seed, "success": r.success,
                            "all_satisfied": r.all_satisfied, "steps": r.steps,
                            "rewards": rewards, "reward": repr(r.reward),
                            "factors": {k: repr(v) for k, v in r.factors.items()},
                            "failure": r.failure})
        finally:
            env.close()
    except Exception as exc:  # recorded, so a crash is a difference, not a lost run
        return name, robot, {"error": f"{type(exc).__name__}: {exc}"}
    return name, robot, out


def record(path: Path, robots: list[str], episodes: int, tasks: list[str] | None) -> None:
    import factask as ft

    names = tasks or list(ft.task_names())
    jobs = [(n, r, episodes) for r in robots for n in names]
    result: dict[str, dict[str, Any]] = {}
    with ProcessPoolExecutor(max_workers=2) as pool:
        for k, (name, robot, eps) in enumerate(pool.map(_record_task, jobs), 1):
            result.setdefault(name, {})[robot] = eps
            print(f"\r{k}/{len(jobs)} {robot:8s} {name:40s}", end="", file=sys.stderr)
    print(file=sys.stderr)
    path.write_text(json.dumps({"factask": ft.__file__, "episodes": episodes,
                                "tasks": result}, indent=1, sort_keys=True))


def compare(a: Path, b: Path) -> int:
    before, after = json.loads(a.read_text()), json.loads(b.read_text())
    diffs = []
    count = 0
    for name in sorted(set(before["tasks"]) | set(after["tasks"])):
        ra, rb = before["tasks"].get(name, {}), after["tasks"].get(name, {})
        for robot in sorted(set(ra) | set(rb)):
            ea, eb = ra.get(robot), rb.get(robot)
            if isinstance(ea, dict) or isinstance(eb, dict) or ea is None or eb is None:
                if ea != eb:
                    diffs.append((name, robot, "-", "run", ea, eb))
                continue
            for x, y in zip(ea, eb, strict=False):
                count += 1
                for field in sorted(set(x) | set(y)):
                    if x.get(field) != y.get(field):
                        diffs.append((name, robot, x["seed"], field, x.get(field), y.get(field)))
            if len(ea) != len(eb):
                diffs.append((name, robot, "-", "episodes", len(ea), len(eb)))
    for d in diffs:
        print(" | ".join(str(v)[:120] for v in d))
    if diffs:
        print(f"{len(diffs)} difference(s)")
        return 1
    print(f"identical: {count} episodes over {len(after['tasks'])} tasks")
    return 0


def against(ref: str, robots: list[str], episodes: int, tasks: list[str] | None) -> int:
    opts = ["--robots", ",".join(robots), "--episodes", str(episodes)]
    if tasks:
        opts += ["--tasks", ",".join(tasks)]
    with tempfile.TemporaryDirectory() as tmp:
        tree = Path(tmp) / "ref"
        subprocess.run(["git", "-C", str(REPO), "worktree", "add", "--detach", str(tree), ref],
                       check=True, capture_output=True)
        try:
            env = dict(os.environ, PYTHONPATH=str(tree / "src"))
            before, after = Path(tmp) / "before.json", Path(tmp) / "after.json"
            subprocess.run([sys.executable, __file__, "record", str(before), *opts],
                           check=True, env=env)
            recorded = json.loads(before.read_text())["factask"]
            if not recorded.startswith(str(tree)):
                raise SystemExit(f"the reference run imported {recorded}, not the worktree")
            env = dict(os.environ, PYTHONPATH=str(REPO / "src"))
            subprocess.run([sys.executable, __file__, "record", str(after), *opts],
                           check=True, env=env)
            return compare(before, after)
        finally:
            subprocess.run(["git", "-C", str(REPO), "worktree", "remove", "--force", str(tree)],
                           check=False, capture_output=True)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="cmd", required=True)
    for name in ("record", "against"):
        s = sub.add_parser(name)
        s.add_argument("target", help="output JSON (record) or git ref (against)")
        s.add_argument("--robots", default="floating,arm")
        s.add_argument("--episodes", type=int, default=2)
        s.add_argument("--tasks", default="", help="comma-separated task names (default all)")
    c = sub.add_parser("compare")
    c.add_argument("before")
    c.add_argument("after")
    args = p.parse_args()
    if args.cmd == "compare":
        return compare(Path(args.before), Path(args.after))
    robots = [r for r in args.robots.split(",") if r]
    tasks = [t for t in args.tasks.split(",") if t] or None
    if args.cmd == "record":
        record(Path(args.target), robots, args.episodes, tasks)
        return 0
    return against(args.target, robots, args.episodes, tasks)


if __name__ == "__main__":
    raise SystemExit(main())
