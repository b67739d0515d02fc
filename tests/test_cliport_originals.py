"""The CLIPort original task files (code nobody here wrote), run through factask.

Runs ``benchmarks/cliport_corpus.py`` over the originals shipped in the package
(``factask/data/cliport_tasks/``) with the floating robot, 4 episodes per class. Every rigid
class (all but ropes, piles and Google scanned objects) must be completed in at
least 3 of its 4 episodes, under factask's checks and under Ravens' scoring of
the same episodes. (The arm's figures come from the same script with
``--robot arm``; see the closing note of issue 11.)
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import CLIPORT_ORIGINALS

ROOT = Path(__file__).resolve().parents[1]
CORPUS = CLIPORT_ORIGINALS
#: Classes outside the rigid scope (ropes, piles: issue 15; Google objects: no assets).
OUT_OF_SCOPE = ("rope", "piles", "google")
#: Episodes per class that must succeed, of the 4 run.
MIN_SUCCESSES = 3


# Session scope: xdist (loadgroup) interleaves other modules' tests on this worker, and a
# module-scoped fixture is torn down at each module change, so the corpus ran twice.
@pytest.fixture(scope="session")
def corpus_records(tmp_path_factory: pytest.TempPathFactory) -> dict[str, dict]:
    # Only the files whose classes are checked here: the rope, pile and Google classes
    # have tests of their own (test_compat_cliport_ropes, test_piles) and ran for nothing.
    folder = tmp_path_factory.mktemp("rigid")
    for path in CORPUS.glob("*.py"):
        if not any(s in path.stem.lower() for s in OUT_OF_SCOPE):
            (folder / path.name).symlink_to(path)
    out = tmp_path_factory.mktemp("corpus") / "results.jsonl"
    subprocess.run([sys.executable, str(ROOT / "benchmarks" / "cliport_corpus.py"), str(folder),
                    "--episodes", "4", "--timeout", "300", "--out", str(out)],
                   check=True, capture_output=True, text=True, timeout=1800, cwd=ROOT)
    return {r["class"]: r for r in map(json.loads, out.read_text().splitlines()) if r["class"]}


def _rigid_classes() -> list[str]:
    import ast

    names = []
    for path in sorted(CORPUS.glob("*.py")):
        for node in ast.parse(path.read_text()).body:
            if isinstance(node, ast.ClassDef) and not any(
                    s in f"{path.stem} {node.name}".lower() for s in OUT_OF_SCOPE):
                names.append(node.name)
    return names


@pytest.mark.slow
@pytest.mark.xdist_group("cliport_originals")  # one corpus run, on one worker
@pytest.mark.parametrize("cls", _rigid_classes())
def test_every_rigid_cliport_class_is_completed(cls: str, corpus_records: dict) -> None:
    rec = corpus_records[cls]
    assert rec["level"] == "completion", rec
    assert rec["successes"] >= MIN_SUCCESSES, rec
    assert rec["ravens_successes"] >= MIN_SUCCESSES, rec
