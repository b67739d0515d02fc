"""The batched oracle against the single one over the whole library (issue 39).

Every library task the batch runs (no pushes, no rope carries) is run both ways —
``run_oracle`` on a batch of one world per seed (Warp's device, default the CPU) and
``run_episode`` on each seed — and each seed's success and action count are
compared (:func:`factask.batch.agreement.compare_task`). Rows are appended to the
output as each task finishes (JSON lines), and tasks already there are skipped: an
interrupted sweep resumes where it stopped.

    python scripts/batch_agreement.py --out benchmarks/results/batch-agreement.jsonl
    python scripts/batch_agreement.py --tasks stack-block-pyramid,put-block-in-bowl

On this project's 2-core machine the whole sweep takes about an hour and a half on
Warp's CPU device (a warm kernel cache). Exit status: 0 when every seed agrees,
1 when some do not (listed at the end), 2 for bad arguments.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from rich.progress import Progress

from factask.batch.agreement import batched, compare_task
from factask.library import get_task, task_names
from factask.vocabulary.errors import FactaskError


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, required=True, help="JSON lines, appended to")
    parser.add_argument("--tasks", default=None, help="comma-separated names (default: all)")
    parser.add_argument("--seeds", default="0,1", help="comma-separated reset seeds")
    parser.add_argument("--device", default="cpu", help="Warp device (cpu, cuda, cuda:N)")
    args = parser.parse_args(argv)
    try:
        seeds = [int(s) for s in args.seeds.split(",")]
        names = args.tasks.split(",") if args.tasks else task_names()
        graphs = {n: get_task(n) for n in names}
    except (ValueError, FactaskError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    done: set[str] = set()
    if args.out.exists():
        done = {json.loads(line)["task"] for line in args.out.read_text().splitlines() if line}
    todo = [n for n in names if batched(graphs[n]) and n not in done]
    skipped = [n for n in names if not batched(graphs[n])]
    args.out.parent.mkdir(parents=True, exist_ok=True)
    with Progress() as bar:
        job = bar.add_task("tasks", total=len(todo))
        for name in todo:
            bar.update(job, description=name)
            try:
                rows = [r.to_dict() for r in compare_task(name, graphs[name], seeds, args.device)]
            except FactaskError as exc:  # a recorded failure, not a lost sweep
                rows = [{"task": name, "seed": s, "error": f"{type(exc).__name__}: {exc}",
                         "agrees": False} for s in seeds]
            with args.out.open("a") as fh:
                for row in rows:
                    fh.write(json.dumps(row) + "\n")
            bar.advance(job)
    rows = [json.loads(line) for line in args.out.read_text().splitlines() if line]
    differ = [r for r in rows if not r["agrees"]]
    print(f"{len(rows)} seed(s) of {len({r['task'] for r in rows})} task(s); "
          f"{len(rows) - len(differ)} agree; not batched: {len(skipped)} "
          f"({', '.join(skipped) or 'none'})")
    for r in differ:
        print(f"  {r['task']} seed {r['seed']}: batch {r.get('batch_success')} / "
              f"{r.get('batch_actions')} ({r.get('batch_failure') or r.get('error')}), single "
              f"{r.get('single_success')} / {r.get('single_actions')} "
              f"({r.get('single_failure')})")
    return 1 if differ else 0


if __name__ == "__main__":
    raise SystemExit(main())
