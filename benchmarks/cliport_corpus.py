"""Run every task class of a folder of CLIPort/GenSim task files through factask and
print the research's table: syntax, runtime, completion.

    python benchmarks/cliport_corpus.py src/factask/data/cliport_tasks --episodes 4
    python benchmarks/cliport_corpus.py my_tasks/ --robot arm --out results.jsonl

Levels, per task class (as in the research; a class reaching a level has reached
the ones before it):

* **syntax** — the file parses and the class loads;
* **runtime** — its ``reset`` ran, the recorded scene converted to a valid graph,
  and factask reset it (layout and targets solved);
* **completion** — the oracle succeeded in at least half of ``--episodes`` episodes
  (seeds 0, 1, ...) under factask's own checks.

Every episode is also scored as Ravens scores it (``factask run --ravens``: goals in
queue order, XY and yaw only); the table shows both episode counts, and the last
line both completion rates.

Task classes are found by reading each file's syntax tree (nothing is executed in
this process); each class runs in its own ``factask run FILE:CLASS --json`` child
process with a wall-clock limit, because task files are code: they may hang, exit
or crash, and that is recorded as a failure of that class only. Task files are
executed: run only folders you trust.
"""

from __future__ import annotations

import argparse
import ast
import json
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.progress import Progress
from rich.table import Table

LEVELS = ("none", "syntax", "runtime", "completion")


def task_classes(path: Path) -> tuple[list[str], str | None]:
    """Names of the classes a task file defines that derive from some ``...Task``
    base, and the syntax error, if the file does not parse."""
    try:
        tree = ast.parse(path.read_text(encoding="utf-8", errors="replace"))
    except SyntaxError as exc:
        return [], f"SyntaxError: {exc.msg} (line {exc.lineno})"
    out = []
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            bases = [ast.unparse(b) for b in node.bases]
            if any(b.split(".")[-1].endswith("Task") or b in out for b in bases):
                out.append(node.name)
    return out, None


def run_class(path: Path, cls: str | None, episodes: int, robot: str,
              timeout: float) -> dict[str, Any]:
    """One class through ``factask run``: its level, episodes and the first error."""
    rec: dict[str, Any] = {"file": path.name, "class": cls, "level": "none",
                           "successes": 0, "ravens_successes": 0, "episodes": episodes,
                           "error": None}
    if cls is None:
        return rec
    cmd = [sys.executable, "-m", "factask", "run", f"{path}:{cls}", "-n", str(episodes),
           "--robot", robot, "--json", "--ravens"]
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        rec["level"], rec["error"] = "syntax", f"timed out after {timeout:.0f} s"
        return rec
    lines = [ln for ln in done.stdout.splitlines() if ln.strip().startswith("{")]
    # `factask run` exits 1 when the task was not completed but still prints its JSON.
    if not lines:
        err_lines = [ln.strip() for ln in done.stderr.splitlines() if ln.strip()]
        err = next((ln for ln in err_lines if "cannot" in ln or "Error" in ln),
                   err_lines[-1] if err_lines else f"exit {done.returncode}")
        # A file whose class loaded but whose reset or conversion failed is at "syntax".
        rec["level"] = "none" if "cannot load" in err or "SyntaxError" in err else "syntax"
        rec["error"] = err[:300]
        return rec
    result = json.loads(lines[-1])
    eps = result.get("episodes", [])
    rec["successes"] = sum(bool(e.get("success")) for e in eps)
    rec["ravens_successes"] = sum(bool(e.get("success")) for e in result.get("ravens", []))
    reset_failed = [e for e in eps if str(e.get("failure") or "").startswith("reset:")]
    if len(reset_failed) == len(eps):
        rec["level"], rec["error"] = "syntax", reset_failed[0]["failure"][:300]
        return rec
    rec["level"] = "completion" if rec["successes"] * 2 >= max(len(eps), 1) else "runtime"
    if rec["level"] != "completion":
        rec["error"] = next((str(e["failure"])[:300] for e in eps if e.get("failure")), None)
    return rec


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder", type=Path, help="folder of task files (*.py); executed")
    ap.add_argument("--episodes", type=int, default=4, help="oracle episodes per class")
    ap.add_argument("--robot", default="floating", help="robot of the oracle episodes")
    ap.add_argument("--timeout", type=float, default=600.0, help="seconds per class")
    ap.add_argument("--workers", type=int, default=2, help="classes run at once")
    ap.add_argument("--out", type=Path, help="also write one JSON line per class here")
    args = ap.parse_args()
    files = sorted(p for p in args.folder.glob("*.py") if not p.name.startswith("_"))
    if not files:
        print(f"no task files (*.py) in {args.folder}", file=sys.stderr)
        return 2
    console = Console(stderr=True)
    # not on a terminal (CI, a log file) a live bar shows nothing until the end: one
    # line per file listed and per class finished instead
    lines = not console.is_terminal
    if lines:
        print(f"listing the task classes of {len(files)} file(s)...", file=sys.stderr,
              flush=True)
    jobs: list[tuple[Path, str | None, str | None]] = []
    for path in files:
        classes, error = task_classes(path)
        jobs += [(path, c, None) for c in classes] or [(path, None, error or "no Task class")]
    records: list[dict[str, Any]] = []
    with Progress(console=console, disable=lines) as progress, \
            ThreadPoolExecutor(args.workers) as pool:
        bar = progress.add_task("task classes", total=len(jobs))
        futures = [pool.submit(run_class, p, c, args.episodes, args.robot, args.timeout)
                   for p, c, _ in jobs]
        for k, ((_, _, why), fut) in enumerate(zip(jobs, futures, strict=True), 1):
            rec = fut.result()
            rec["error"] = rec["error"] or why
            records.append(rec)
            progress.advance(bar)
            if lines:
                print(f"[{k}/{len(jobs)}] {rec['file']} {rec['class'] or '-'}: {rec['level']}, "
                      f"{rec['successes']}/{rec['episodes']}", file=sys.stderr, flush=True)
    if args.out:
        args.out.write_text("".join(json.dumps(r) + "\n" for r in records))
    table = Table(title=f"{args.folder} — {args.robot}, {args.episodes} episode(s) per class")
    for col in ("file", "class", "level", "factask", "Ravens", "first error"):
        table.add_column(col)
    for r in records:
        table.add_row(r["file"], r["class"] or "-", r["level"],
                      f"{r['successes']}/{r['episodes']}",
                      f"{r['ravens_successes']}/{r['episodes']}", (r["error"] or "")[:90])
    out = Console(width=None if sys.stdout.isatty() else 160)
    out.print(table)
    n = len(records)
    reached = {lvl: sum(LEVELS.index(r["level"]) >= LEVELS.index(lvl) for r in records)
               for lvl in LEVELS[1:]}
    ravens_done = sum(r["ravens_successes"] * 2 >= max(r["episodes"], 1)
                      and LEVELS.index(r["level"]) >= LEVELS.index("runtime") for r in records)
    total_eps = sum(r["episodes"] for r in records if r["class"])
    out.print("  ".join(f"{lvl} {k}/{n} ({k / n:.0%})" for lvl, k in reached.items())
              + f"  episodes {sum(r['successes'] for r in records)}/{total_eps}")
    out.print(f"under Ravens scoring: completion {ravens_done}/{n} ({ravens_done / n:.0%})  "
              f"episodes {sum(r['ravens_successes'] for r in records)}/{total_eps}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
