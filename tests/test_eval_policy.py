"""factask eval-policy: reference policies, module:callable policies, 95 % intervals."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

import factask.sim  # noqa: F401  (headless GL backend before MuJoCo's GL loads)
from factask.cli import app
from factask.evaluation.policy import (
    PolicyError,
    evaluate_policy,
    load_policy,
    mean_interval,
    wilson_interval,
)

TASK = "place-red-in-green"


def test_wilson_interval_matches_known_values() -> None:
    assert wilson_interval(5, 10) == pytest.approx((0.2366, 0.7634), abs=1e-4)
    assert wilson_interval(0, 10) == pytest.approx((0.0, 0.2775), abs=1e-4)
    assert wilson_interval(10, 10) == pytest.approx((0.7225, 1.0), abs=1e-4)
    low, high = mean_interval([1.0, 0.0, 1.0, 0.0])
    assert low < 0.5 < high


def test_the_oracle_succeeds_and_episodes_are_json_lines(tmp_path: Path) -> None:
    out, chart, videos = tmp_path / "episodes.jsonl", tmp_path / "chart.png", tmp_path / "v"
    result = CliRunner().invoke(app, ["eval-policy", "oracle", TASK, "-n", "2",
                                      "--workers", "1", "--out", str(out), "--json",
                                      "--chart", str(chart), "--video-dir", str(videos)])
    assert result.exit_code == 0, result.output
    summary = json.loads(result.output)
    score = summary["tasks"][0]
    assert score["success_at_end"] == 1.0 and score["success_once"] == 1.0
    lines = [json.loads(x) for x in out.read_text().splitlines()]
    assert [x["seed"] for x in lines] == [10_001, 10_003]  # test seeds
    assert all(x["success_at_end"] for x in lines)
    assert chart.read_bytes().startswith(b"\x89PNG")
    assert [p.name for p in videos.iterdir()] == [f"{TASK}-seed10001.mp4"]  # --videos 1


def test_module_callable_and_object_policies() -> None:
    outcomes, scores = evaluate_policy("policies_for_tests:stop_at_once", [TASK], 1,
                                       workers=1)
    assert outcomes[0].actions == 0 and not outcomes[0].success_at_end
    assert scores[0].success_at_end == 0.0
    outcomes, _ = evaluate_policy("policies_for_tests:Counting", [TASK], 1, workers=1)
    assert outcomes[0].actions == 2


def test_random_reference_policy_runs() -> None:
    outcomes, scores = evaluate_policy("random", [TASK], 1, workers=1)
    assert len(outcomes) == 1 and 0.0 <= scores[0].mean_reward <= 1.0


def test_a_bad_policy_names_the_fix() -> None:
    with pytest.raises(PolicyError, match="module:callable"):
        load_policy("no-colon", None)
    with pytest.raises(PolicyError, match="cannot import"):
        load_policy("no_such_module_xyz:f", None)
    result = CliRunner().invoke(app, ["eval-policy", "nope:nothing", TASK, "--workers", "1"])
    assert result.exit_code == 2


@pytest.mark.slow
def test_eval_policy_on_ray_equals_in_process() -> None:
    ray = pytest.importorskip("ray", reason="Ray is optional: pip install 'factask[ray]'")
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        tasks = [TASK, "align-box-corner"]
        on_ray, _ = evaluate_policy("oracle", tasks, 2, ray_address="auto")
        here, _ = evaluate_policy("oracle", tasks, 2, workers=1)
        assert on_ray == here
    finally:
        ray.shutdown()
