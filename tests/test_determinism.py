"""Seeded oracle episodes are reproducible across processes.

Two processes with different ``PYTHONHASHSEED`` (so set and string-hash order
differ) record the same small library tasks with ``scripts/compare_episodes.py``;
the fingerprints (rewards after every action, the actions to full precision,
final factor progress, failures) must be identical.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

SCRIPT = Path(__file__).resolve().parent.parent / "scripts" / "compare_episodes.py"
#: Quick floating-robot tasks: a container goal, a row and a ring (set-heavy relations).
TASKS = ("place-red-in-green", "align-boxes-on-line", "put-blues-around-red")


def test_seeded_episodes_are_identical_across_processes(tmp_path: Path) -> None:
    runs = {}
    for hashseed in ("0", "4242"):
        out = tmp_path / f"hash{hashseed}.json"
        env = {**os.environ, "PYTHONHASHSEED": hashseed}
        cmd = [sys.executable, str(SCRIPT), "record", str(out), "--robots", "floating",
               "--episodes", "2", "--tasks", ",".join(TASKS), "--workers", "1", "--quiet"]
        runs[hashseed] = (out, subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE,
                                                stderr=subprocess.STDOUT, text=True))
    data = []
    for out, proc in runs.values():
        log, _ = proc.communicate(timeout=300)
        assert proc.returncode == 0, log[-3000:]
        data.append(json.loads(out.read_text()))
    a, b = data
    assert (a["meta"]["pythonhashseed"], b["meta"]["pythonhashseed"]) == ("0", "4242")
    assert sorted(a["tasks"]) == sorted(TASKS)
    for name in TASKS:
        run = a["tasks"][name]["floating"]
        assert "error" not in run, run["error"]
        assert [e["seed"] for e in run["episodes"]] == [0, 1]
        assert all(len(e["rewards"]) == e["steps"] > 0 for e in run["episodes"])
    a.pop("meta")
    b.pop("meta")
    assert a == b
