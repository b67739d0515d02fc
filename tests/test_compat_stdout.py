"""A task file's own prints never reach a command's stdout (issue 35, item 6): under
``--json`` stdout is one JSON value, however much the task code prints."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TASK = ROOT / "tests" / "cliport_tasks" / "place_red_in_green.py"
#: 10 MB of prints: at module level, in ``__init__`` and in ``reset``.
CHATTY = ("\nprint('len of languages: 2 obj:20')\n", "        print('x' * 10_000_000)\n")


def _chatty_task(tmp_path: Path) -> Path:
    source = TASK.read_text() + CHATTY[0]
    source = source.replace("    def reset(self, env):\n",
                            "    def reset(self, env):\n" + CHATTY[1], 1)
    assert CHATTY[1] in source
    path = tmp_path / "chatty.py"
    path.write_text(source)
    return path


@pytest.mark.parametrize("command", [["run", "{file}", "-n", "1", "--json"],
                                     ["import-cliport", "{file}", "-o", "{tmp}/g.json",
                                      "--json"]])
def test_a_task_that_prints_leaves_the_json_on_stdout_alone(command: list[str],
                                                            tmp_path: Path) -> None:
    file = _chatty_task(tmp_path)
    args = [a.replace("{file}", str(file)).replace("{tmp}", str(tmp_path)) for a in command]
    done = subprocess.run([sys.executable, "-m", "factask", *args], capture_output=True,
                          text=True, timeout=300, cwd=tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    data = json.loads(done.stdout)  # one JSON value, nothing else
    assert isinstance(data, dict)
    assert "len of languages" in done.stderr and len(done.stderr) > 10_000_000
