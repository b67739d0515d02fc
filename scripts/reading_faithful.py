"""How often the reading alone means the proposal: one-shot, no model, no physics.

For each proposal of a task list, the graph the reader-only model would write in
one-shot (the first choice of the grounded one-shot schema, expanded) is compared
with the proposal's reference graph by the meaning metric (``factask.gen.compare``,
colours the words leave open matching any). No LLM call, no oracle episode: the
faithful column of ``factask benchmark --model local/reader -a one-shot`` in about
a minute per 100 proposals, for working on the reading (``factask.gen.reading``).

    python scripts/reading_faithful.py                     # the 192 list and the set
    python scripts/reading_faithful.py --tasks tests/data/proposals.json --limit 20
    python scripts/reading_faithful.py --out runs/reading.json   # every record

Exit status: 0 (the rates are printed, whatever they are), 2 a task list that
cannot be read.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import Counter
from pathlib import Path
from typing import Any

from factask.evaluation.benchmark import BenchmarkError, load_tasks, reference_graph
from factask.gen.compare import compare
from factask.gen.first_choice import first_choice
from factask.gen.reading import grounded
from factask.gen.reading.clauses import read_goals
from factask.gen.reading.mentions import mentions
from factask.graph.taskgraph import parse_graph
from factask.vocabulary.errors import FactaskError

ROOT = Path(__file__).resolve().parents[1]
DEFAULT_LISTS = [ROOT.parent / "shared" / "data" / "gensim_tasks.json",
                 ROOT / "tests" / "data" / "proposals.json"]


def judge(name: str, description: str, reference: Any) -> dict[str, Any]:
    """One proposal: the reader's one-shot graph against its reference."""
    found = mentions(f"{description} {name}")
    record: dict[str, Any] = {"task": name, "stated": read_goals(description, found) is not None}
    if not grounded.applies(found):
        return {**record, "faithful": False, "why": "no movable object the reading can ground"}
    try:
        schema = grounded.compact_graph_schema(found, description)
        graph = parse_graph(grounded.expand_graph(first_choice(schema), found, name,
                                                  description))
    except (FactaskError, ValueError) as exc:
        return {**record, "faithful": False, "why": f"{type(exc).__name__}: {exc}"[:300]}
    result = compare(graph, reference, description)
    return {**record, "faithful": result.equivalent, "differences": result.differences}


def run(path: Path, limit: int | None) -> list[dict[str, Any]]:
    """Every proposal of the list that has a reference, judged."""
    out = []
    for task in load_tasks(path)[:limit]:
        reference = reference_graph(task)
        if reference is not None:
            out.append(judge(task.name, task.description, reference))
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--tasks", type=Path, action="append",
                        help="task list JSON (repeat it; default: the 192 list and the set)")
    parser.add_argument("--limit", type=int, default=None, help="only the first N of each")
    parser.add_argument("--out", type=Path, default=None, help="write every record here")
    args = parser.parse_args(argv)
    records: dict[str, list[dict[str, Any]]] = {}
    for path in args.tasks or DEFAULT_LISTS:
        try:
            records[str(path)] = rows = run(path, args.limit)
        except (OSError, BenchmarkError) as exc:
            print(f"error: {path}: {exc}", file=sys.stderr)
            return 2
        faithful = sum(r["faithful"] for r in rows)
        stated = sum(r["stated"] for r in rows)
        print(f"{path.name}: faithful {faithful} / {len(rows)} "
              f"({100 * faithful / max(len(rows), 1):.1f} %); the words state every goal "
              f"in {stated}")
        kinds = Counter(d.split(":")[0] for r in rows for d in r.get("differences", []))
        if kinds:
            print("  differences: " + ", ".join(f"{k} {n}" for k, n in kinds.most_common()))
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(json.dumps(records, indent=1))
        print(f"records: {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
