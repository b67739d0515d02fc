"""A built wheel carries everything factask needs at run time (issue 12).

The wheel is built from this checkout and installed on its own into a folder
(its dependencies come from the test environment); from a folder outside the
repository, the installed package finds its prompts and its task list, and its
``factask generate`` writes a verified task talking to the loopback server:
nothing is read from the source tree.
"""

from __future__ import annotations

import os
import subprocess
import sys
import sysconfig
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
def test_the_wheel_ships_prompts_and_data_and_they_are_found_from_it(tmp_path: Path) -> None:
    dist = tmp_path / "dist"
    subprocess.run([sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps",
                    "--no-build-isolation", "-q", "-w", str(dist)], check=True, timeout=600,
                   capture_output=True)
    (wheel,) = dist.glob("factask-*.whl")
    names = set(zipfile.ZipFile(wheel).namelist())
    assert "factask/prompts/system.md" in names and "factask/data/gensim_tasks.json" in names
    assert {"factask/data/cliport_tasks/towers_of_hanoi.py",
            "factask/data/cliport_tasks/LICENSE"} <= names
    target = tmp_path / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "-q", "--target",
                    str(target), str(wheel)], check=True, timeout=600, capture_output=True)
    site = sysconfig.get_paths()["purelib"]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(target), site])}
    env.pop("FACTASK_PROMPTS", None)
    probe = ("import factask, factask.gen.prompts as p, factask.evaluation.benchmark as b;"
             "print(factask.__file__); print(p.prompts_dir());"
             "print(len(p.load_template('one_shot')));"
             "print(b.default_tasks_path())")
    out = subprocess.run([sys.executable, "-c", probe], cwd=tmp_path, env=env, check=True,
                         capture_output=True, text=True, timeout=300).stdout.splitlines()
    assert all(line.startswith(str(target)) for line in (out[0], out[1], out[3])), out
    assert int(out[2]) > 100

    from factask.gen.demo import DEMO_PROPOSAL, demo_responder
    from factask.gen.loopback import LoopbackServer

    graph = tmp_path / "generated.json"
    with LoopbackServer(demo_responder()) as server:
        run = subprocess.run([sys.executable, "-m", "factask", "generate", DEMO_PROPOSAL,
                              "-a", "one-shot", "--model", "openai/scripted", "--api-base",
                              server.url, "--episodes", "1", "--out", str(graph),
                              "--cache", str(tmp_path / "cache")],
                             cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    assert "level reached: completion" in run.stdout and graph.is_file()
