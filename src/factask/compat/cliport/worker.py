"""Child-process entry of the batch import: one task file, one result record.

Run as ``python -m factask.compat.cliport.worker FILE [--seed S] [--episodes N]
[--graph-out PATH] [--ravens] [--robot NAME]``. The file **is executed**; the parent
(:mod:`factask.compat.cliport.batch`) runs this in its own process with a time
limit, so a crashing or hanging task never stops the batch.

A record has: ``file``, ``class``, ``task``, ``loaded`` (the file ran and
has a Task subclass), ``imported`` (its reset produced a valid graph),
``compiled`` (the graph compiled to MuJoCo; null if the backend is missing),
``oracle_success_rate`` (null unless episodes were run; factask's checks),
with ``--ravens`` also ``ravens_success_rate`` and per episode ``ravens``
(seed, factask's success, Ravens' reward and success), ``warnings`` and
``error`` (null on success). One JSON line is printed (and flushed) after each
stage, with a ``stage`` key (``loaded``, ``imported``, ``compiled``), and the
final one with ``"stage": "done"``: a parent that kills a hanging child keeps
the stages it already reported. Before any of them, once its own imports are
done, it prints :data:`~factask.compat.cliport.batch.READY_LINE`: the parent's
time limit covers the task file, not the worker's start-up.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from factask.compat.cliport.batch import READY_LINE
from factask.compat.cliport.errors import CliportImportError
from factask.compat.cliport.loader import import_cliport
from factask.compat.cliport.scoring import scored_episode
from factask.sim.build.compile import compile_graph
from factask.sim.episode import run_episode

#: Data memory (heap and private mappings) a task file's worker may use, MiB; a
#: file allocating more gets a ``MemoryError`` (reported like any exception) in
#: seconds instead of swapping the machine until its time limit.
#: ``FACTASK_WORKER_MEMORY_MB`` overrides it.
DEFAULT_MEMORY_MB = 4096


def limit_memory(megabytes: int | None = None) -> int:
    """Cap this process's data memory (``RLIMIT_DATA``); returns the cap in MiB.

    Args:
        megabytes: The cap; default ``FACTASK_WORKER_MEMORY_MB`` or
            :data:`DEFAULT_MEMORY_MB`. A hard limit already lower is kept.
    """
    mb = megabytes or int(os.environ.get("FACTASK_WORKER_MEMORY_MB") or DEFAULT_MEMORY_MB)
    want = mb * 1024 * 1024
    _, hard = resource.getrlimit(resource.RLIMIT_DATA)
    if hard != resource.RLIM_INFINITY:
        want = min(want, hard)
    resource.setrlimit(resource.RLIMIT_DATA, (want, hard))
    return want // (1024 * 1024)


def new_record(path: str) -> dict[str, Any]:
    """The record of a file nothing has been done with yet (every stage false)."""
    return {"file": path, "class": None, "task": None, "loaded": False,
            "imported": False, "compiled": None, "oracle_success_rate": None,
            "warnings": [], "error": None}


def run_file(path: str, seed: int = 0, episodes: int = 0, graph_out: str | None = None,
             emit: Callable[[dict[str, Any]], None] | None = None,
             ravens: bool = False, robot: str = "floating") -> dict[str, Any]:
    """Load, import, compile and (optionally) run one task file.

    The file is executed once (:func:`import_cliport` loads it and reports the
    loaded stage through its ``on_loaded`` callback).

    Args:
        path: The task file (executed).
        seed: Seed of the import and of the first episode.
        episodes: Oracle episodes to run (0: do not run the oracle).
        graph_out: Where to write the imported graph's JSON, if given.
        emit: Called with a copy of the record after each stage that succeeded
            (loaded, imported, compiled; not with the final record, which is
            returned), so a parent that has to kill this process still knows how
            far it got.
        ravens: Also score every episode as Ravens does.
        robot: The robot of the oracle episodes (a name of the registry).

    Returns:
        The result record (see the module docstring); never raises: a late
        failure keeps the stages already done true.
    """
    rec = new_record(path)

    def report() -> None:
        if emit is not None:
            emit(dict(rec))

    def loaded(cls: type) -> None:
        rec["class"], rec["loaded"] = cls.__name__, True
        report()

    try:
        _run_stages(rec, path, seed, episodes, graph_out, loaded, report, ravens, robot)
    except Exception as exc:  # never lose the stages already done
        rec["error"] = f"internal error: {type(exc).__name__}: {exc}"
    return rec


def _run_stages(rec: dict[str, Any], path: str, seed: int, episodes: int,
                graph_out: str | None, loaded: Callable[[type], None],
                report: Callable[[], None], ravens: bool = False,
                robot: str = "floating") -> None:
    try:
        result = import_cliport(path, seed=seed, on_loaded=loaded, isolate=False)
    except CliportImportError as exc:
        rec["error"] = str(exc)
        return
    rec["class"], rec["loaded"] = result.class_name, True
    rec["task"], rec["imported"] = result.task_name, True
    rec["warnings"] = result.warnings
    report()
    if graph_out:
        Path(graph_out).write_text(result.graph.to_json(), encoding="utf-8")
    try:
        compile_graph(result.graph)
    except Exception as exc:
        rec["compiled"] = False
        rec["error"] = f"compile failed: {type(exc).__name__}: {exc}"
        return
    rec["compiled"] = True
    report()
    if episodes > 0:
        rec["robot"] = robot
        wins, failures, scores = 0, [], []
        for k in range(episodes):
            try:
                if ravens:
                    ep, score = scored_episode(result, seed + k, robot=robot)
                    scores.append({"seed": seed + k, "success": ep.success,
                                   "ravens_reward": score.reward,
                                   "ravens_success": score.success})
                else:
                    ep = run_episode(result.graph, seed=seed + k, robot=robot)
            except Exception as exc:
                rec["error"] = f"episode {k} failed: {type(exc).__name__}: {exc}"
                break
            wins += bool(getattr(ep, "success", False))
            if getattr(ep, "failure", None):
                failures.append(f"episode {k}: {ep.failure}")
        else:
            rec["oracle_success_rate"] = wins / episodes
            if ravens:
                rec["ravens_success_rate"] = sum(s["ravens_success"] for s in scores) / episodes
        rec["oracle_failures"] = failures
        if ravens:
            rec["ravens"] = scores


def main(argv: list[str] | None = None) -> int:
    """Command-line entry: print JSON lines; exit 0 even when the task fails.

    One line (a full record with an extra ``"stage"`` key) is written and
    flushed after each stage: ``loaded``, ``imported``, ``compiled``, and
    ``done`` for the final record. The task's own prints go to stderr, so
    stdout holds only these lines.
    """
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    ap.add_argument("file")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--episodes", type=int, default=0)
    ap.add_argument("--graph-out", default=None)
    ap.add_argument("--ravens", action="store_true")
    ap.add_argument("--robot", default="floating")
    args = ap.parse_args(argv)
    limit_memory()
    out = sys.stdout
    sys.stdout = sys.stderr  # user code's prints must not mix with the records
    out.write(READY_LINE + "\n")  # imports done: the parent's time limit starts now
    out.flush()

    def emit(rec: dict[str, Any]) -> None:
        out.write("\n" + json.dumps({**rec, "stage": stage_of(rec)}) + "\n")
        out.flush()

    final: dict[str, Any] | None = None
    try:
        final = run_file(args.file, args.seed, args.episodes, args.graph_out, emit=emit,
                         ravens=args.ravens, robot=args.robot)
    except Exception as exc:  # the last line of defence: always report, never hang the batch
        final = new_record(args.file)
        final["error"] = f"internal error: {type(exc).__name__}: {exc}"
    finally:
        sys.stdout = out
    out.write("\n" + json.dumps({**final, "stage": "done"}) + "\n")
    out.flush()
    return 0


def stage_of(rec: dict[str, Any]) -> str:
    """The last stage a partial record reached: loaded, imported or compiled."""
    if rec.get("compiled"):
        return "compiled"
    if rec.get("imported"):
        return "imported"
    return "loaded" if rec.get("loaded") else "started"


if __name__ == "__main__":
    raise SystemExit(main())
