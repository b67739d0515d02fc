"""benchmarks/bench_batch.py runs end to end on Warp's CPU device (a smoke run: one
task, small sizes) and writes its table's numbers and its plot."""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.xdist_group("warp")
if importlib.util.find_spec("mujoco_warp") is None:  # pragma: no cover - make test installs it
    pytest.skip("the gpu extra is not installed (make test installs it)",
                allow_module_level=True)
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import bench_batch  # noqa: E402


def test_the_batch_benchmark_measures_every_part_and_plots(tmp_path: Path) -> None:
    assert bench_batch.main(["--device", "cpu", "--quick", "--tasks", "put-block-in-bowl",
                             "--steps", "20", "--out", str(tmp_path)]) == 0
    result = json.loads((tmp_path / "batch-cpu-quick.json").read_text())
    physics, oracle, planning = result["physics"], result["oracle"], result["planning"]
    assert [r["num_envs"] for r in physics] == list(bench_batch.QUICK[0])
    assert [r["num_envs"] for r in oracle] == list(bench_batch.QUICK[1])
    assert [r["num_envs"] for r in planning] == list(bench_batch.QUICK[2])
    assert all(r["world_steps_per_s"] > 0 for r in physics)
    # One block into its bowl: every world succeeds in one lockstep action, planned
    # as array work.
    assert all(r["success"] == 1.0 and r["lockstep_actions"] == 1 for r in oracle)
    assert all(r["fallback_share"] == 0.0 for r in oracle + planning)
    single = result["single"][0]
    assert single["success"] == 1.0 and single["rollout_world_steps_per_s"] > 0
    assert (tmp_path / "img" / "batch-cpu-quick.png").stat().st_size > 10_000
