"""Fuzz the graph parser with corrupted library graphs (issue 37's "done when").

Each case takes a library task's graph JSON, applies one to three random corruptions
(a key deleted, renamed or repeated; a value of the wrong type, huge, empty, NaN or
negative; a list emptied, doubled or nested; a name pointing nowhere; the text cut
or a byte flipped) and parses it with :func:`factask.graph.parse_graph`. A case
passes when the parse returns a valid graph or raises ``GraphValidationError``
whose every problem is at most 1 KB, within a second. Anything else (another
exception, a message over 1 KB, a slow case) is printed and makes the exit status 1.

    python scripts/fuzz_graphs.py --cases 24000 --seed 0
"""

from __future__ import annotations

import argparse
import copy
import json
import math
import random
import sys
import time
from typing import Any

from factask.graph import parse_graph
from factask.library import get_task, task_names
from factask.vocabulary.errors import GraphValidationError

#: Values a corruption puts where a field was.
JUNK: list[Any] = [None, True, -1, 0, 1e308, -1e-9, math.nan, math.inf, "", "x" * 100_000,
                   [], {}, [[[]]], {"a": {"b": {}}}, "nonexistent_thing", "RED", "🙂",
                   [0.04, "a", None], 2**70, "\u0000", -0.0]
#: Longest a case may take, seconds.
CASE_LIMIT_S = 1.0
#: Longest a problem's text may be, characters.
PROBLEM_LIMIT = 1024


def json_paths(node: Any, path: tuple = ()) -> list[tuple]:
    """Every path into the JSON tree (dict keys and list indices); tests/test_fuzz.py
    draws from it too."""
    out = [path]
    if isinstance(node, dict):
        for k, v in node.items():
            out += json_paths(v, (*path, k))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out += json_paths(v, (*path, i))
    return out


def _get(node: Any, path: tuple) -> Any:
    for p in path:
        node = node[p]
    return node


def corrupt(data: dict, rng: random.Random) -> dict | str:
    """``data`` with one random corruption; a string when the text itself is broken."""
    data = copy.deepcopy(data)
    paths = [p for p in json_paths(data) if p]
    if not paths:  # corrupted down to an empty object: nothing left to corrupt
        return data
    path = rng.choice(paths)
    parent, key = _get(data, path[:-1]), path[-1]
    kind = rng.randrange(9)
    if kind == 0 and isinstance(parent, dict):
        del parent[key]
    elif kind == 1 and isinstance(parent, dict):
        parent[f"{key}_x"] = parent.pop(key)
    elif kind == 2 and isinstance(parent, list):
        parent.extend(copy.deepcopy(parent) * rng.randint(1, 40))
    elif kind == 3 and isinstance(parent, list):
        parent.clear()
    elif kind == 4:
        variables = data.get("variables")
        names = [v["name"] for v in (variables if isinstance(variables, list) else [])
                 if isinstance(v, dict) and isinstance(v.get("name"), str)]
        parent[key] = rng.choice(names) if names and rng.random() < 0.5 else "nowhere"
    elif kind == 5:
        text = json.dumps(data)
        cut = rng.randrange(len(text))
        return text[:cut] if rng.random() < 0.5 else text[:cut] + chr(rng.randrange(1, 256)) \
            + text[cut + 1:]
    elif kind == 6 and isinstance(parent, dict):  # the key given twice
        text = json.dumps(data)
        needle = f'"{key}": '
        at = text.find(needle)
        if at >= 0:
            return text[:at] + f'"{key}": null, ' + text[at:]
        parent[key] = rng.choice(JUNK)
    else:
        parent[key] = copy.deepcopy(rng.choice(JUNK))
    return data


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=24_000)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    graphs = {n: json.loads(get_task(n).to_json()) for n in task_names()}
    names = sorted(graphs)
    counts = {"valid": 0, "refused": 0, "bad": 0}
    slowest = 0.0
    started = time.monotonic()
    for case in range(args.cases):
        name = rng.choice(names)
        source: Any = graphs[name]
        for _ in range(rng.randint(1, 3)):
            source = corrupt(source, rng) if isinstance(source, dict) else source
        text = source if isinstance(source, str) else json.dumps(source, allow_nan=True)
        t = time.monotonic()
        outcome = "valid"
        try:
            parse_graph(text)
        except GraphValidationError as exc:
            outcome = "refused"
            long = [p for p in exc.problems if len(str(p)) > PROBLEM_LIMIT]
            if long or len(str(exc)) > 64 * PROBLEM_LIMIT:
                outcome = "bad"
                print(f"case {case} ({name}): a message over 1 KB: {str(long[:1])[:200]}")
        except Exception as exc:  # the defect this script looks for
            outcome = "bad"
            print(f"case {case} ({name}): untyped {type(exc).__name__}: {str(exc)[:200]}")
        took = time.monotonic() - t
        slowest = max(slowest, took)
        if took > CASE_LIMIT_S:
            outcome = "bad"
            print(f"case {case} ({name}): took {took:.1f} s")
        counts[outcome] += 1
        if (case + 1) % 2000 == 0:
            print(f"{case + 1}/{args.cases} cases: {counts}", file=sys.stderr, flush=True)
    print(f"{args.cases} corrupted graphs in {time.monotonic() - started:.0f} s: "
          f"{counts['valid']} still valid, {counts['refused']} refused with typed "
          f"problems, {counts['bad']} bad (untyped, over 1 KB or over {CASE_LIMIT_S:g} s); "
          f"slowest case {slowest * 1000:.0f} ms")
    return 1 if counts["bad"] else 0


if __name__ == "__main__":
    sys.exit(main())
