"""Prove that a change left the oracle's seeded episodes untouched.

    python scripts/compare_episodes.py record OUT.json [--robots floating,arm] [--episodes 2]
                                                      [--tasks a,b] [--seed 0] [--workers 2]
    python scripts/compare_episodes.py compare BEFORE.json AFTER.json
    python scripts/compare_episodes.py against REF [--robots ...] [--episodes ...] [--tasks ...]
                                                  [--out-before B.json] [--out-after A.json]

``record`` runs the oracle over every library task for each robot, exactly as
``factask eval-library`` does (one environment per task, episodes with seeds
``seed, seed + 1, ...``, default 0..N-1), and writes a fingerprint per episode:
seed, success, every factor satisfied, the number of env steps (actions), the
total reward after every step and the actions themselves (floats as ``repr``,
full precision), the final per-factor progress, simulated seconds, and the
oracle's failure; per task and robot the completion summary eval-library reports
(success rate, completed), and per robot the library summary. An exception of a
task is recorded (type and message), not raised.

``compare`` prints every difference (task, robot, episode, field, before, after)
and exits 1 if there is any, else prints ``identical: N episodes over M tasks``.

``against REF`` records git ref REF in a temporary ``git worktree`` (a subprocess
with the worktree's ``src`` alone on PYTHONPATH; it checks that ``factask`` was
imported from there), records the working tree the same way, compares them and
removes the worktree. ``--current-ref REF2`` records a second worktree (of REF2)
instead of the working tree.

Only factask's public API is used (``factask.get_task``, ``task_names``,
``FactaskEnv``, ``run_episode``, ``TaskResult``), so old and new code both run.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
FORMAT = 2
#: Top-level keys that describe a run (paths, versions, timings) and are not compared.
META = "meta"

Job = tuple[str, str, int, int]  # task, robot, first seed, episodes


# ------------------------------------------------------------------ recording
def _src_root() -> str:
    import factask as ft

    return str(Path(ft.__file__).resolve().parents[1])


def _clean(text: str | None) -> str | None:
    """Text without the path of the imported source tree (differs between worktrees)."""
    return None if text is None else text.replace(_src_root(), "<src>")


def _floats(values: Any) -> list[str]:
    return [repr(float(v)) for v in values]


def _episode(r: Any, rewards: list[str], actions: list[dict[str, list[str]]]) -> dict[str, Any]:
    return {
        "seed": r.seed,
        "success": bool(r.success),
        "all_satisfied": bool(getattr(r, "all_satisfied", False)),
        "steps": int(r.steps),
        "reward": repr(float(r.reward)),
        "rewards": rewards,
        "actions": actions,
        "factors": {k: repr(float(v)) for k, v in sorted(r.factors.items())},
        "details": {k: _clean(str(v)) for k, v in sorted(getattr(r, "details", {}).items())},
        "sim_seconds": repr(float(getattr(r, "sim_seconds", 0.0))),
        "failure": _clean(r.failure),
    }


def _record_task(job: Job) -> tuple[Job, dict[str, Any], str, float]:
    """One task with one robot, as ``evaluate_task`` runs it: one env, seeds seed..seed+n-1.

    Returns (job, entry, factask.__file__, seconds). The entry has ``episodes``,
    ``success_rate`` and ``completed``, or ``error`` (and the episodes before it).
    """
    import factask as ft

    name, robot, first, n = job
    start = time.perf_counter()
    entry: dict[str, Any] = {"episodes": []}
    results = []
    try:
        graph = ft.get_task(name)
        env = ft.FactaskEnv(graph, robot=robot)
        try:
            for seed in range(first, first + n):
                rewards: list[str] = []
                actions: list[dict[str, list[str]]] = []

                def on_action(_i: int, planned: Any, info: dict[str, Any],
                              rewards: list[str] = rewards,
                              actions: list[dict[str, list[str]]] = actions) -> None:
                    rewards.append(repr(float(info["total_reward"])))
                    act = planned.as_env_action()
                    actions.append({k: _floats(v) for k, v in sorted(act.items())})

                r = ft.run_episode(graph, seed, robot=robot, env=env, on_action=on_action)
                results.append(r)
                entry["episodes"].append(_episode(r, rewards, actions))
        finally:
            env.close()
    except Exception as exc:  # recorded: a crash is a difference, not a lost run
        entry["error"] = {"type": type(exc).__name__, "message": _clean(str(exc))}
    else:
        tr = ft.TaskResult(name, results)
        entry["success_rate"] = repr(float(tr.success_rate))
        entry["completed"] = bool(tr.completed)
    return job, entry, ft.__file__, time.perf_counter() - start


def _summary(entries: list[dict[str, Any]]) -> dict[str, Any]:
    """eval-library's summary (``factask.sim.episode.summarize``) over clean task runs."""
    ok = [e for e in entries if "error" not in e]
    eps = [x for e in ok for x in e["episodes"]]
    return {"tasks_total": len(ok), "tasks_completed": sum(e["completed"] for e in ok),
            "episode_success_rate": repr(sum(x["success"] for x in eps) / len(eps)
                                         if eps else 0.0),
            "task_errors": len(entries) - len(ok)}


def _order(jobs: list[Job]) -> list[Job]:
    """Longest first (arm before floating, more movable objects first): a shorter tail."""
    import factask as ft

    try:
        movable = {i.name: i.n_movable for i in ft.list_tasks()}
    except Exception:
        movable = {}
    return sorted(jobs, key=lambda j: (j[1] == "floating", -movable.get(j[0], 0)))


def _run_jobs(jobs: list[Job], workers: int, quiet: bool
              ) -> list[tuple[Job, dict[str, Any], str, float]]:
    from rich import progress as rp
    from rich.console import Console

    done: list[tuple[Job, dict[str, Any], str, float]] = []
    progress = rp.Progress(rp.TextColumn("{task.description:<48}"), rp.BarColumn(),
                           rp.MofNCompleteColumn(), rp.TimeElapsedColumn(),
                           console=Console(stderr=True), disable=quiet)
    with progress:
        bar = progress.add_task("recording", total=len(jobs))
        pending = list(jobs)
        size = workers
        while pending:
            finished: set[Job] = set()
            try:
                with ProcessPoolExecutor(max_workers=size) as pool:
                    futures = [pool.submit(_record_task, j) for j in pending]
                    for fut in as_completed(futures):
                        out = fut.result()
                        done.append(out)
                        finished.add(out[0])
                        progress.update(bar, advance=1,
                                        description=f"{out[0][1]:<9}{out[0][0]}")
                pending = []
            except BrokenProcessPool:
                # A worker died (a crash, not an exception). Retry one job per pool:
                # the job that kills a single-worker pool is the culprit.
                pending = [j for j in pending if j not in finished]
                if size == 1:
                    job = pending.pop(0)
                    done.append((job, {"episodes": [], "error": {
                        "type": "BrokenProcessPool",
                        "message": "the worker process died (crash or killed)"}}, "", 0.0))
                    progress.update(bar, advance=1)
                size = 1
    return done


def record(path: Path, robots: list[str], episodes: int, tasks: list[str] | None, seed: int = 0,
           workers: int = 2, expect_root: Path | None = None, quiet: bool = False) -> int:
    import factask as ft

    def outside(file: str) -> bool:
        return expect_root is not None and not Path(file).resolve().is_relative_to(
            expect_root.resolve())

    if outside(ft.__file__):
        print(f"factask was imported from {ft.__file__}, not from {expect_root}", file=sys.stderr)
        return 3
    names = tasks or list(ft.task_names())
    start = time.perf_counter()
    done = _run_jobs(_order([(n, r, seed, episodes) for r in robots for n in names]),
                     workers, quiet)
    wall = time.perf_counter() - start
    files = sorted({f for _, _, f, _ in done if f})
    if any(outside(f) for f in files):
        print(f"a worker imported factask from {files}, not from {expect_root}", file=sys.stderr)
        return 3
    by_job = {job: entry for job, entry, _, _ in done}
    result = {n: {r: by_job[(n, r, seed, episodes)] for r in robots} for n in names}
    import mujoco
    import numpy

    data = {
        "format": FORMAT, "robots": robots, "episodes": episodes, "seed": seed,
        "tasks": result,
        "summary": {r: _summary([result[n][r] for n in names]) for r in robots},
        META: {"factask": ft.__file__, "worker_factask": files, "python": platform.python_version(),
               "mujoco": mujoco.__version__, "numpy": numpy.__version__,
               "pythonhashseed": os.environ.get("PYTHONHASHSEED"), "workers": workers,
               "wall_seconds": round(wall, 2),
               "task_seconds": {f"{j[1]}/{j[0]}": round(s, 2) for j, _, _, s in done}},
    }
    path.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")
    n_eps = sum(len(e["episodes"]) for t in result.values() for e in t.values())
    errors = sum("error" in e for t in result.values() for e in t.values())
    print(f"recorded {n_eps} episodes of {len(names)} tasks x {len(robots)} robot(s) in "
          f"{wall:.1f} s ({errors} task error(s)) -> {path}", file=sys.stderr)
    return 0


# ------------------------------------------------------------------ comparing
def _show(value: Any) -> str:
    text = "—" if value is None else value if isinstance(value, str) else json.dumps(value)
    return text if len(text) <= 100 else text[:97] + "..."


def _diff(rows: list[tuple[str, ...]], where: tuple[str, str, str], field: str,
          a: Any, b: Any) -> None:
    """Append (task, robot, episode, field, before, after) rows for a != b."""
    if a == b:
        return
    if isinstance(a, list) and isinstance(b, list):
        pairs = enumerate(zip(a, b, strict=False))
        i = next((k for k, (x, y) in pairs if x != y), min(len(a), len(b)))
        extra = f" (len {len(a)} vs {len(b)})" if len(a) != len(b) else ""
        rows.append((*where, f"{field}[{i}]{extra}", _show(a[i] if i < len(a) else None),
                     _show(b[i] if i < len(b) else None)))
    elif isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            _diff(rows, where, f"{field}.{k}", a.get(k), b.get(k))
    else:
        rows.append((*where, field, _show(a), _show(b)))


def compare(a: Path, b: Path) -> int:
    before, after = json.loads(a.read_text()), json.loads(b.read_text())
    for side, data in (("before", before), ("after", after)):
        if data.get("format") != FORMAT:
            print(f"{side} ({data.get('format')!r}) is not a format-{FORMAT} recording: "
                  "record it again with this script", file=sys.stderr)
            return 2
    rows: list[tuple[str, ...]] = []
    for key in ("robots", "episodes", "seed"):
        _diff(rows, ("*", "*", "-"), key, before[key], after[key])
    count = errors = 0
    tasks = sorted(set(before["tasks"]) | set(after["tasks"]))
    for name in tasks:
        ra, rb = before["tasks"].get(name), after["tasks"].get(name)
        if ra is None or rb is None:
            rows.append((name, "*", "-", "task", "absent" if ra is None else "recorded",
                         "absent" if rb is None else "recorded"))
            continue
        for robot in sorted(set(ra) | set(rb)):
            ea, eb = ra.get(robot), rb.get(robot)
            if ea is None or eb is None:
                _diff(rows, (name, robot, "-"), "run", ea and "recorded", eb and "recorded")
                continue
            errors += "error" in ea and "error" in eb
            for field in ("error", "success_rate", "completed"):
                _diff(rows, (name, robot, "-"), field, ea.get(field), eb.get(field))
            xs, ys = ea["episodes"], eb["episodes"]
            for k in range(max(len(xs), len(ys))):
                x, y = (xs[k] if k < len(xs) else {}), (ys[k] if k < len(ys) else {})
                seed = str(x.get("seed", y.get("seed", "?")))
                if not x or not y:
                    rows.append((name, robot, seed, "episode", "recorded" if x else "absent",
                                 "recorded" if y else "absent"))
                    continue
                count += 1
                for field in sorted(set(x) | set(y)):
                    _diff(rows, (name, robot, seed), field, x.get(field), y.get(field))
    for robot in sorted(set(before.get("summary", {})) | set(after.get("summary", {}))):
        _diff(rows, ("(library)", robot, "-"), "summary", before["summary"].get(robot),
              after["summary"].get(robot))
    ma, mb = before.get(META, {}), after.get(META, {})
    for key in ("python", "mujoco", "numpy"):
        if ma.get(key) != mb.get(key):
            print(f"note: {key} {ma.get(key)} before, {mb.get(key)} after", file=sys.stderr)
    if rows:
        from rich.console import Console
        from rich.table import Table

        table = Table(title=f"{len(rows)} difference(s): {a} -> {b}", show_lines=False)
        for col in ("task", "robot", "episode", "field", "before", "after"):
            table.add_column(col, overflow="fold")
        for row in rows:
            table.add_row(*row)
        Console(width=max(shutil.get_terminal_size().columns, 160)).print(
            table, markup=False, highlight=False)
        return 1
    if errors:
        print(f"note: {errors} task run(s) raised the same error on both sides", file=sys.stderr)
    print(f"identical: {count} episodes over {len(tasks)} tasks")
    return 0


# ------------------------------------------------------------------ against a git ref
def _git(*args: str) -> str:
    return subprocess.run(["git", "-C", str(REPO), *args], check=True, capture_output=True,
                          text=True).stdout.strip()


def _record_in(src: Path, out: Path, opts: list[str]) -> None:
    """``record`` in a subprocess importing factask from ``src`` alone."""
    env = dict(os.environ, PYTHONPATH=str(src))
    cmd = [sys.executable, str(Path(__file__).resolve()), "record", str(out), *opts,
           "--expect-root", str(src)]
    print(f"recording {src} ...", file=sys.stderr)
    subprocess.run(cmd, check=True, env=env, cwd=src.parent)


def against(ref: str, opts: list[str], current_ref: str | None = None,
            out_before: Path | None = None, out_after: Path | None = None) -> int:
    with tempfile.TemporaryDirectory(prefix="compare-episodes-") as tmp:
        trees: list[Path] = []
        try:
            sides = []
            for label, r in (("before", ref), ("after", current_ref)):
                if r is None:
                    sides.append((label, REPO / "src"))
                    continue
                commit = _git("rev-parse", "--verify", f"{r}^{{commit}}")
                tree = Path(tmp) / label
                _git("worktree", "add", "--detach", str(tree), commit)
                trees.append(tree)
                print(f"{label}: {r} = {commit[:12]} in {tree}", file=sys.stderr)
                sides.append((label, tree / "src"))
            paths = {}
            for label, src in sides:
                paths[label] = Path(tmp) / f"{label}.json"
                _record_in(src, paths[label], opts)
            for label, keep in (("before", out_before), ("after", out_after)):
                if keep is not None:
                    shutil.copyfile(paths[label], keep)
            return compare(paths["before"], paths["after"])
        except subprocess.CalledProcessError as exc:
            what = " ".join(exc.cmd[:4]) if isinstance(exc.cmd, list) else exc.cmd
            print(f"failed (exit {exc.returncode}): {what} ...", file=sys.stderr)
            if exc.stderr:
                print(exc.stderr, file=sys.stderr)
            return 2
        finally:
            for tree in trees:
                subprocess.run(["git", "-C", str(REPO), "worktree", "remove", "--force",
                                str(tree)], check=False, capture_output=True)
            subprocess.run(["git", "-C", str(REPO), "worktree", "prune"], check=False,
                           capture_output=True)


# ------------------------------------------------------------------ command line
def _split(text: str) -> list[str]:
    return [t.strip() for t in text.split(",") if t.strip()]


def main(argv: list[str] | None = None) -> int:
    # One BLAS/OpenMP thread per process (before numpy loads): the pool uses every core.
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, "1")
    p = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    for name in ("record", "against"):
        s = sub.add_parser(name)
        s.add_argument("target", help="output JSON (record) or git ref (against)")
        s.add_argument("--robots", default="floating,arm", help="comma-separated robot names")
        s.add_argument("--episodes", type=int, default=2, help="episodes per task and robot")
        s.add_argument("--seed", type=int, default=0, help="first seed (as eval-library's)")
        s.add_argument("--tasks", default="", help="comma-separated task names (default all)")
        s.add_argument("--workers", type=int, default=2, help="worker processes")
        s.add_argument("--quiet", action="store_true", help="no progress bar")
        if name == "record":
            s.add_argument("--expect-root", type=Path, help=argparse.SUPPRESS)
        else:
            s.add_argument("--current-ref", help=argparse.SUPPRESS)
            s.add_argument("--out-before", type=Path, help="keep REF's recording here")
            s.add_argument("--out-after", type=Path, help="keep the working tree's recording")
    c = sub.add_parser("compare")
    c.add_argument("before", type=Path)
    c.add_argument("after", type=Path)
    args = p.parse_args(argv)
    if args.cmd == "compare":
        return compare(args.before, args.after)
    robots, tasks = _split(args.robots), _split(args.tasks) or None
    if args.cmd == "record":
        return record(args.target if isinstance(args.target, Path) else Path(args.target),
                      robots, args.episodes, tasks, args.seed, args.workers, args.expect_root,
                      args.quiet)
    opts = ["--robots", ",".join(robots), "--episodes", str(args.episodes),
            "--seed", str(args.seed), "--workers", str(args.workers)]
    if tasks:
        opts += ["--tasks", ",".join(tasks)]
    if args.quiet:
        opts.append("--quiet")
    return against(args.target, opts, args.current_ref, args.out_before, args.out_after)


if __name__ == "__main__":
    raise SystemExit(main())
