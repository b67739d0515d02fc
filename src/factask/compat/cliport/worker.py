"""Child-process entry of the batch import: one task file, one JSON line.

Run as ``python -m factask.compat.cliport.worker FILE [--seed S] [--episodes N]
[--graph-out PATH]``. The file **is executed**; the parent
(:mod:`factask.compat.cliport.batch`) runs this in its own process with a time
limit, so a crashing or hanging task never stops the batch.

The JSON line has: ``file``, ``class``, ``task``, ``loaded`` (the file ran and
has a Task subclass), ``imported`` (its reset produced a valid graph),
``compiled`` (the graph compiled to MuJoCo; null if the backend is missing),
``oracle_success_rate`` (null unless episodes were run), ``warnings`` and
``error`` (null on success).
"""

from __future__ import annotations

import argparse
import importlib
import json
import sys
from pathlib import Path
from typing import Any

from factask.compat.cliport.errors import CliportImportError
from factask.compat.cliport.loader import import_cliport, load_task_class
from factask.model.errors import FactaskError


def _optional(module: str, attr: str) -> Any:
    """``module.attr`` if that part of factask exists yet, else None."""
    try:
        return getattr(importlib.import_module(module), attr)
    except (ImportError, AttributeError):
        return None


def run_file(path: str, seed: int = 0, episodes: int = 0,
             graph_out: str | None = None) -> dict[str, Any]:
    """Load, import, compile and (optionally) run one task file.

    Args:
        path: The task file (executed).
        seed: Seed of the import and of the first episode.
        episodes: Oracle episodes to run (0: do not run the oracle).
        graph_out: Where to write the imported graph's JSON, if given.

    Returns:
        The result record (see the module docstring); never raises for the
        task's own errors.
    """
    rec: dict[str, Any] = {"file": path, "class": None, "task": None, "loaded": False,
                           "imported": False, "compiled": None, "oracle_success_rate": None,
                           "warnings": [], "error": None}
    try:
        cls = load_task_class(path)
        rec["class"], rec["loaded"] = cls.__name__, True
        result = import_cliport(path, class_name=cls.__name__, seed=seed)
        rec["task"], rec["imported"] = result.task_name, True
        rec["warnings"] = result.warnings
        if graph_out:
            Path(graph_out).write_text(result.graph.to_json(), encoding="utf-8")
    except CliportImportError as exc:
        rec["error"] = str(exc)
        return rec
    compile_graph = _optional("factask.sim.compile", "compile_graph")
    if compile_graph is None:
        rec["compile_note"] = "factask.sim.compile is not available: not compiled"
    else:
        try:
            compile_graph(result.graph)
            rec["compiled"] = True
        except FactaskError as exc:
            rec["compiled"] = False
            rec["error"] = f"compile failed: {exc}"
            return rec
    if episodes > 0:
        run_episode = _optional("factask.sim.episode", "run_episode")
        if run_episode is None:
            rec["oracle_note"] = "factask.sim.episode is not available: oracle not run"
            return rec
        wins, failures = 0, []
        for k in range(episodes):
            try:
                ep = run_episode(result.graph, seed=seed + k, robot="floating")
            except FactaskError as exc:
                rec["error"] = f"episode {k} failed: {exc}"
                break
            wins += bool(getattr(ep, "success", False))
            if getattr(ep, "failure", None):
                failures.append(f"episode {k}: {ep.failure}")
        else:
            rec["oracle_success_rate"] = wins / episodes
        rec["oracle_failures"] = failures
    return rec


def main(argv: list[str] | None = None) -> int:
    """Command-line entry: print one JSON line; exit 0 even when the task fails."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    ap.add_argument("file")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--episodes", type=int, default=0)
    ap.add_argument("--graph-out", default=None)
    args = ap.parse_args(argv)
    try:
        rec = run_file(args.file, args.seed, args.episodes, args.graph_out)
    except Exception as exc:  # the last line of defence: always report, never hang the batch
        rec = {"file": args.file, "class": None, "task": None, "loaded": False,
               "imported": False, "compiled": None, "oracle_success_rate": None,
               "warnings": [], "error": f"internal error: {type(exc).__name__}: {exc}"}
    sys.stdout.write(json.dumps(rec) + "\n")
    sys.stdout.flush()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
