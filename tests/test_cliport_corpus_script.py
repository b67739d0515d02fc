"""benchmarks/cliport_corpus.py: every class of a folder through factask, one table."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "benchmarks" / "cliport_corpus.py"
TASKS = Path(__file__).parent / "cliport_tasks"


def test_the_corpus_table_has_a_level_for_every_class(tmp_path: Path) -> None:
    shutil.copy(TASKS / "place_red_in_green.py", tmp_path)
    (tmp_path / "broken.py").write_text("class Broken(Task:\n    pass\n")
    (tmp_path / "leaves.py").write_text(
        "import sys\nfrom cliport.tasks.task import Task\n"
        "class Leaves(Task):\n    def reset(self, env):\n        sys.exit(0)\n")
    out = tmp_path / "results.jsonl"
    done = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path), "--episodes", "1",
                           "--timeout", "120", "--out", str(out)],
                          capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    records = {r["file"]: r for r in map(json.loads, out.read_text().splitlines())}
    assert records["place_red_in_green.py"]["level"] == "completion"
    assert records["broken.py"]["level"] == "none" and "SyntaxError" in records["broken.py"][
        "error"]
    assert records["leaves.py"]["level"] in ("none", "syntax")
    assert records["leaves.py"]["successes"] == 0
    assert "completion 1/3" in done.stdout
    # stderr is a pipe here: progress is one line per class, not a live bar that shows
    # nothing until the end (issue 37, item 14)
    progress = [line for line in done.stderr.splitlines() if line.startswith("[")]
    assert len(progress) == 3 and progress[-1].startswith("[3/3] ")
    assert "listing the task classes of 3 file(s)" in done.stderr
