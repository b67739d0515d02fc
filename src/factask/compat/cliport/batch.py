"""Import a folder of CLIPort task files, each in its own child process.

Every file **is executed** (it is Python). Each runs in a fresh
``python -m factask.compat.cliport.worker`` process, in its own process group,
with a wall-clock time limit (the only limit a hanging user file respects); one
JSON line per file is written as soon as that file is done, so a crash, a hang
or a bad file never stops the batch and a partial results file is still useful.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import IO, Any

#: Default time limit per file, seconds (a reset alone takes 2-4 s in PyBullet).
DEFAULT_TIMEOUT_S = 120.0
#: Seconds a worker may take to start (import factask and MuJoCo) before the time
#: limit for the task file itself begins.
STARTUP_TIMEOUT_S = 300.0

#: The line a worker prints once it has started (its imports are done).
READY_LINE = '{"worker": "ready"}'

#: Characters of a crashed child's stderr kept in its error message.
STDERR_TAIL = 600


def task_files(folder: str | Path) -> list[Path]:
    """The ``.py`` files of ``folder`` (not recursive, no ``__init__.py``), sorted."""
    return sorted(p for p in Path(folder).glob("*.py")
                  if p.is_file() and p.name != "__init__.py")


def _failed(path: Path, error: str) -> dict[str, Any]:
    return {"file": str(path), "class": None, "task": None, "loaded": False,
            "imported": False, "compiled": None, "oracle_success_rate": None,
            "warnings": [], "error": error}


def _kill_group(proc: subprocess.Popen[str]) -> None:
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        proc.kill()


def _worker_command(path: Path, seed: int, episodes: int,
                    graph_out: str | Path | None, ravens: bool = False,
                    robot: str = "floating") -> list[str]:
    cmd = [sys.executable, "-m", "factask.compat.cliport.worker", str(path),
           "--seed", str(seed), "--episodes", str(episodes), "--robot", robot]
    if ravens:
        cmd.append("--ravens")
    if graph_out is not None:
        cmd += ["--graph-out", str(graph_out)]
    return cmd


#: What the child was doing when it stopped, by the last stage it reported.
_NEXT_STEP = {
    None: "while loading the file",
    "started": "while loading the file",
    "loaded": "while running reset and building the graph",
    "imported": "while compiling the graph",
    "compiled": "during the oracle episodes",
}


def _last_record(out: str) -> tuple[dict[str, Any] | None, str | None]:
    """The last record line the worker printed, and its stage (popped from it)."""
    for line in reversed(out.splitlines()):
        line = line.strip()
        if not line.startswith("{"):
            continue
        try:
            rec = json.loads(line)
        except json.JSONDecodeError:
            continue
        if isinstance(rec, dict) and "loaded" in rec:
            stage = rec.pop("stage", "done")
            return rec, stage if isinstance(stage, str) else None
    return None, None


def run_one(path: str | Path, timeout: float = DEFAULT_TIMEOUT_S, seed: int = 0,
            episodes: int = 0, graph_out: str | Path | None = None,
            ravens: bool = False, robot: str = "floating") -> dict[str, Any]:
    """Import one file in a child process; always return a result record.

    The child reports each stage it finishes (loaded, imported, compiled) as it
    goes; if it is killed for the time limit or dies, the stages it reported stay
    true and ``error`` says what it was doing.

    Args:
        path: The task file.
        timeout: Seconds the task file may take in the child, counted from the
            worker's start (it and its children are killed after).
        seed: Import seed.
        episodes: Oracle episodes per file (0: none).
        graph_out: Where the child writes the graph JSON, if given.
        ravens: Also score every episode as Ravens does.
        robot: The robot of the oracle episodes (a name of the registry).

    Returns:
        The worker's record, or one saying why the child did not finish.
    """
    p = Path(path)
    proc = subprocess.Popen(_worker_command(p, seed, episodes, graph_out, ravens, robot),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    child = _ChildOutput(proc)
    # The limit is for the task file: it starts once the worker has imported factask
    # and MuJoCo (seconds on a busy machine, and no business of the file's).
    started = child.ready.wait(STARTUP_TIMEOUT_S)
    timed_out = False
    try:
        proc.wait(timeout=timeout if started else 0)
    except subprocess.TimeoutExpired:
        timed_out = True
        _kill_group(proc)
        proc.wait()
    out, err = child.collect()  # what the child printed, up to its exit or the kill
    rec, stage = _last_record(out)
    if rec is not None and stage == "done":
        return rec
    rec = rec if rec is not None else _failed(p, "")
    when = _NEXT_STEP.get(stage, f"after stage {stage!r}")
    if timed_out and not started:
        rec["error"] = (f"the worker did not start within {STARTUP_TIMEOUT_S:g} s "
                        "(importing factask and MuJoCo); is the machine overloaded?")
    elif timed_out:
        rec["error"] = f"timed out after {timeout:g} s (wall clock) {when}"
    else:
        tail = err.strip()[-STDERR_TAIL:]
        rec["error"] = (f"child process exited with code {proc.returncode} {when} "
                        "without a result" + (f": {tail}" if tail else ""))
    return rec


class _ChildOutput:
    """Reads a child's stdout and stderr on threads (so neither pipe fills up) and
    signals ``ready`` when the worker's ready line arrives or stdout closes."""

    def __init__(self, proc: subprocess.Popen[str]) -> None:
        self.ready = threading.Event()
        self._out: list[str] = []
        self._err: list[str] = []
        self._threads = [threading.Thread(target=self._read_out, args=(proc.stdout,), daemon=True),
                         threading.Thread(target=self._read_err, args=(proc.stderr,), daemon=True)]
        for t in self._threads:
            t.start()

    def _read_out(self, stream: IO[str]) -> None:
        for line in stream:
            self._out.append(line)
            if line.strip() == READY_LINE:
                self.ready.set()
        self.ready.set()  # the child exited (or closed stdout): nothing more to wait for

    def _read_err(self, stream: IO[str]) -> None:
        self._err.append(stream.read())

    def collect(self) -> tuple[str, str]:
        """Everything printed, once the child has exited."""
        for t in self._threads:
            t.join()
        return "".join(self._out), "".join(self._err)


def run_batch(folder: str | Path, out: IO[str], timeout: float = DEFAULT_TIMEOUT_S,
              seed: int = 0, episodes: int = 0, graphs_dir: str | Path | None = None,
              on_result: Callable[[dict[str, Any]], None] | None = None,
              ravens: bool = False, robot: str = "floating") -> list[dict[str, Any]]:
    """Import every task file of ``folder``; write one JSON line per file to ``out``.

    Args:
        folder: Folder of task files.
        out: Text stream of the JSONL results (flushed after every line).
        timeout: Seconds per file.
        seed: Import seed.
        episodes: Oracle episodes per file (0: none).
        graphs_dir: If given, each imported graph is written there as ``<stem>.json``.
        on_result: Called with each record as it is written (progress display).
        ravens: Also score every episode as Ravens does.
        robot: The robot of the oracle episodes (a name of the registry).

    Returns:
        Every record, in file order.
    """
    records = []
    for rec in iter_batch(folder, timeout, seed, episodes, graphs_dir, ravens, robot):
        out.write(json.dumps(rec) + "\n")
        out.flush()
        if on_result is not None:
            on_result(rec)
        records.append(rec)
    return records


def iter_batch(folder: str | Path, timeout: float = DEFAULT_TIMEOUT_S, seed: int = 0,
               episodes: int = 0, graphs_dir: str | Path | None = None,
               ravens: bool = False, robot: str = "floating") -> Iterator[dict[str, Any]]:
    """Records of :func:`run_one` for each file of ``folder``, one at a time."""
    gdir = Path(graphs_dir) if graphs_dir is not None else None
    if gdir is not None:
        gdir.mkdir(parents=True, exist_ok=True)
    for path in task_files(folder):
        graph_out = gdir / f"{path.stem}.json" if gdir is not None else None
        yield run_one(path, timeout, seed, episodes, graph_out, ravens, robot)
