"""The example scripts run end to end with plain ``python`` and write their outputs.

Each example runs in a subprocess (``sys.executable``) with a temporary
directory as its working directory, so its ``out/examples/`` files land there.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

#: Example script -> files it must write under ``out/examples/``.
EXPECTED: dict[str, tuple[str, ...]] = {
    "01_build_task_from_templates.py": ("01_task.json", "01_task_graph.png"),
    "02_compose_tasks.py": ("02_composed.json", "02_composed_graph.png"),
    "03_run_oracle_and_rewards.py": ("03_rewards.json",),
    "04_render_scene.py": ("04_rgb_front.png", "04_rgb_top.png", "04_depth_top.png",
                           "04_segmentation_top.png", "04_episode.gif"),
    "05_import_cliport_task.py": ("05_stack_boxes_column.py", "05_imported.json"),
    "06_generate_with_loopback.py": ("06_generated.json", "06_results.json"),
    "07_milestones_and_ravens_scoring.py": ("07_block_tour.py", "07_scores.json"),
    "08_collect_dataset.py": ("08_cameras.png", "08_summary.json",
                              "08_dataset/meta/info.json"),
    "09_piles_and_ropes.py": ("09_piles_and_ropes.png", "09_results.json"),
    "10_batched.py": ("10_batched.json",),
    "11_does_it_mean_the_proposal.py": ("11_meaning.json",),
    "12_reader_only.py": ("12_reader.json",),
    "13_reference_model.py": ("13_reference.json",),
    "14_libero_task.py": ("14_libero.json", "14_libero_scene.png"),
    "15_drawers.py": ("15_drawers.json", "15_drawer_shut.png", "15_drawer_open.png"),
    "16_switches.py": ("16_switches.json", "16_switch_off.png", "16_switch_on.png"),
    "17_doors.py": ("17_doors.json", "17_door_shut.png", "17_door_open.png"),
    "18_shelves.py": ("18_shelves.json", "18_shelf_start.png", "18_shelf_done.png"),
}
#: Examples that compile MuJoCo Warp's kernels: with the batched env's tests in one
#: xdist group, so one worker compiles them (once per machine, then cached).
WARP = {"10_batched.py"}
SIGNATURES = {".png": b"\x89PNG\r\n\x1a\n", ".gif": b"GIF8"}


def test_every_example_is_covered() -> None:
    assert sorted(p.name for p in EXAMPLES.glob("[0-9]*.py")) == sorted(EXPECTED)


@pytest.mark.parametrize("script", [
    pytest.param(s, marks=pytest.mark.xdist_group("warp")) if s in WARP else s
    for s in sorted(EXPECTED)])
def test_example_runs(script: str, tmp_path: Path) -> None:
    env = {**os.environ, "MUJOCO_GL": os.environ.get("MUJOCO_GL", "egl"),
           "MPLBACKEND": "Agg", "PYTHONHASHSEED": "0"}
    proc = subprocess.run([sys.executable, str(EXAMPLES / script)], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=300, check=False)
    assert proc.returncode == 0, f"{script} failed:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    out = tmp_path / "out" / "examples"
    for name in EXPECTED[script]:
        path = out / name
        assert path.is_file(), f"{script} did not write {path}"
        if path.suffix == ".json":
            json.loads(path.read_text())
        elif path.suffix == ".py":
            compile(path.read_text(), str(path), "exec")  # written source parses
        else:
            assert path.read_bytes().startswith(SIGNATURES[path.suffix]), \
                f"{path} is not a {path.suffix} file"
