"""The oracle commands: run, eval-library and demo."""

from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

from factask.cli import app
from factask.library import get_task

runner = CliRunner()


def test_run_json_has_the_documented_shape() -> None:
    result = runner.invoke(app, ["run", "put-block-in-bowl", "--episodes", "2", "--seed", "3",
                                 "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["task"] == "put-block-in-bowl"
    assert [e["seed"] for e in data["episodes"]] == [3, 4]
    for e in data["episodes"]:
        assert set(e) >= {"seed", "reward", "success", "steps", "factors", "failure"}
        assert e["success"] is (e["reward"] >= 0.99)
        assert set(e["factors"]) == set(get_task("put-block-in-bowl").factor_names())
    assert data["success_rate"] == 1.0 and data["completed"] is True


def test_run_accepts_a_graph_file(tmp_path: Path) -> None:
    path = tmp_path / "task.json"
    path.write_text(get_task("stack-boxes-column").to_json())
    result = runner.invoke(app, ["run", str(path), "--json"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["task"] == "stack-boxes-column"


def test_run_unknown_task_and_invalid_file_exit_2(tmp_path: Path) -> None:
    result = runner.invoke(app, ["run", "stack-block-pyramidd"])
    assert result.exit_code == 2
    assert "stack-block-pyramid" in result.output  # a close name is suggested
    bad = tmp_path / "bad.json"
    bad.write_text('{"name": "x", "variables": [], "factors": [{"name": "f"}]}')
    result = runner.invoke(app, ["run", str(bad)])
    assert result.exit_code == 2
    assert "invalid" in result.output


def test_run_rejects_unknown_robot() -> None:
    result = runner.invoke(app, ["run", "put-block-in-bowl", "--robot", "hand"])
    assert result.exit_code == 2


def test_eval_library_summary_for_selected_tasks() -> None:
    result = runner.invoke(app, ["eval-library", "--episodes", "1", "--task", "block-insertion",
                                 "--task", "align-box-corner", "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["tasks_total"] == 2 and data["tasks_completed"] == 2
    assert data["episode_success_rate"] == 1.0
    assert [t["task"] for t in data["tasks"]] == ["block-insertion", "align-box-corner"]


def test_demo_writes_graph_picture_video_and_result(tmp_path: Path) -> None:
    result = runner.invoke(app, ["demo", "--task", "put-block-in-bowl", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert "total reward 1.00" in result.output
    assert (tmp_path / "put-block-in-bowl-graph.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (tmp_path / "put-block-in-bowl.gif").read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    episode = json.loads((tmp_path / "episode.json").read_text())
    assert episode["success"] is True


def test_run_ravens_scores_a_library_graph_and_a_task_file() -> None:
    hanoi = runner.invoke(app, ["run", "towers-of-hanoi", "-n", "1", "--json", "--ravens"])
    assert hanoi.exit_code == 0, hanoi.output
    data = json.loads(hanoi.stdout)
    (score,) = data["ravens"]
    assert score["goals"] == 7 and score["goals_done"] == 7 and score["success"]
    tasks = Path(__file__).parent / "cliport_tasks"
    seq = runner.invoke(app, ["run", f"{tasks / 'towers_of_hanoi_seq.py'}", "-n", "1",
                              "--json", "--ravens"])
    assert seq.exit_code == 0, seq.output
    (score,) = json.loads(seq.stdout)["ravens"]
    assert score["goals"] == 7 and score["success"]


def test_import_cliport_batch_ravens_reports_both_rates(tmp_path: Path) -> None:
    folder = tmp_path / "tasks"
    folder.mkdir()
    src = Path(__file__).parent / "cliport_tasks" / "place_red_in_green.py"
    (folder / src.name).write_text(src.read_text())
    out = tmp_path / "out.jsonl"
    for robot in ("floating", "arm"):
        result = runner.invoke(app, ["import-cliport-batch", str(folder), "-o", str(out),
                                     "--episodes", "1", "--ravens", "--robot", robot])
        assert result.exit_code == 0, result.output
        (rec,) = [json.loads(line) for line in out.read_text().splitlines()]
        assert rec["robot"] == robot
        assert rec["oracle_success_rate"] == 1.0 and rec["ravens_success_rate"] == 1.0
        (episode,) = rec["ravens"]
        assert episode["success"] and episode["ravens_success"]
    bad = runner.invoke(app, ["import-cliport-batch", str(folder), "-o", str(out),
                              "--robot", "no-such-robot"])
    assert bad.exit_code != 0 and "unknown robot" in bad.output


def test_graph_goal_queue_has_one_goal_per_factor_in_order() -> None:
    from factask.compat.cliport.scoring import graph_goal_queue
    from factask.sim.env import FactaskEnv

    graph = get_task("put-block-in-bowl")
    env = FactaskEnv(graph)
    try:
        env.reset(seed=0)
        queue = graph_goal_queue(graph, env.solved, env.objects, env.initial_layout)
    finally:
        env.close()
    order = graph.factor_order()
    assert [g.language for g in queue] == [graph.factor(n).description for n in order]
    assert abs(sum(g.max_reward for g in queue) - 1.0) < 1e-9
    for goal, name in zip(queue, order, strict=True):
        relation = graph.factor(name).goal.type
        assert goal.metric == ("zone" if relation in ("in_zone", "inside") else "pose")
        if goal.metric == "zone":
            (zone,) = goal.zones
            assert zone[4] > 0 and zone[5] > 0
        assert len(goal.matches) == len(goal.objects)
