"""``factask generate`` against the loopback server (in-process CLI runner)."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from factask.cli import app
from factask.gen.demo import DEMO_PROPOSAL, demo_responder
from factask.gen.loopback import LoopbackServer, ScriptedResponder
from factask.graph import parse_graph

runner = CliRunner()


def test_generate_prints_steps_writes_the_graph_and_exits_0(tmp_path) -> None:
    out = tmp_path / "task.json"
    with LoopbackServer(demo_responder(broken=True)) as server:
        res = runner.invoke(app, ["generate", DEMO_PROPOSAL, "--approach", "one-shot",
                                  "--model", "openai/scripted", "--api-base", server.url,
                                  "--out", str(out), "--episodes", "1",
                                  "--cache", str(tmp_path / "cache")])
    assert res.exit_code == 0, res.output
    assert "one_shot attempt 0: failed" in res.output
    assert "one_shot attempt 2: ok" in res.output
    assert "level reached: completion" in res.output
    graph = parse_graph(json.loads(out.read_text()))
    assert graph.name == "stack-blue-on-red-in-zone"


def test_generate_exits_1_when_completion_is_not_reached(tmp_path) -> None:
    with LoopbackServer(ScriptedResponder({"one_shot": ["no"]})) as server:
        res = runner.invoke(app, ["generate", "a-task: anything", "-a", "one-shot",
                                  "--model", "openai/scripted", "--api-base", server.url,
                                  "--max-repairs", "1", "--out", str(tmp_path / "g.json")])
    assert res.exit_code == 1, res.output
    assert "level reached: none" in res.output
    assert not (tmp_path / "g.json").exists()


def test_generate_rejects_bad_options(monkeypatch) -> None:
    monkeypatch.delenv("FACTASK_MODEL", raising=False)
    res = runner.invoke(app, ["generate", "x: y", "--approach", "bottom-up", "--model", "m"])
    assert res.exit_code == 2
    res = runner.invoke(app, ["generate", "x: y", "--model", "local/no-such-model"])
    assert res.exit_code == 2 and "unknown local model" in res.output
    res = runner.invoke(app, ["generate", "x: y", "--response-format", "xml"])
    assert res.exit_code == 2 and "response_format" in res.output


def test_a_missing_key_is_one_line_and_exit_2_with_no_call(monkeypatch) -> None:
    for var in ("OPENAI_API_KEY", "ANTHROPIC_API_KEY", "FACTASK_API_KEY", "FACTASK_MODEL"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.delenv("FACTASK_API_BASE", raising=False)
    res = runner.invoke(app, ["generate", "x: y", "--model", "openai/gpt-4o-mini"])
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and "OPENAI_API_KEY" in lines[0] and "fix:" in lines[0]
    assert "Traceback" not in res.output
    res = runner.invoke(app, ["benchmark", "--model", "anthropic/claude-3-5-haiku-latest",
                              "--limit", "1", "--out", "/tmp/factask-never"])
    assert res.exit_code == 2 and "ANTHROPIC_API_KEY" in res.output


def test_no_successful_call_exits_3(tmp_path) -> None:
    from factask.gen.loopback import LoopbackServer, ScriptedResponder

    with LoopbackServer(ScriptedResponder({})) as server:  # every call: 500
        env = {"FACTASK_RETRIES": "0"}
        res = runner.invoke(app, ["benchmark", "-a", "one-shot", "--model", "openai/scripted",
                                  "--api-base", server.url, "--limit", "2", "--out",
                                  str(tmp_path / "run")], env=env)
    assert res.exit_code == 3, res.output
    assert "no LLM call succeeded" in res.output


def test_generate_json_is_one_object_on_stdout_with_the_steps_on_stderr(tmp_path) -> None:
    out = tmp_path / "task.json"
    with LoopbackServer(demo_responder(broken=True)) as server:
        res = runner.invoke(
            app, ["generate", DEMO_PROPOSAL, "-a", "one-shot", "--model", "openai/scripted",
                  "--api-base", server.url, "--out", str(out), "--episodes", "1", "--json"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["level_reached"] == "completion" and data["exit_code"] == 0
    assert data["graph_file"] == str(out) and out.exists()
    assert "one_shot attempt 0: failed" in res.stderr


def test_benchmark_takes_comma_lists_and_prints_json(tmp_path) -> None:
    tasks = tmp_path / "tasks.json"
    tasks.write_text(json.dumps([{"name": "stack-blue-on-red-in-zone",
                                  "description": "put the red block in the zone, "
                                                      "then the blue block on it"}]))
    with LoopbackServer(demo_responder()) as server:
        res = runner.invoke(
            app, ["benchmark", "-a", "one-shot,one-shot", "--tasks", str(tasks),
                  "--model", "openai/scripted", "--api-base", server.url, "--episodes", "1",
                  "-o", str(tmp_path / "run"), "--json"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["exit_code"] == 0 and list(data["approaches"]) == ["one-shot"]
    bad = runner.invoke(app, ["benchmark", "-a", "one-shot,[bold]x[/bold]",
                              "-o", str(tmp_path / "b")])
    assert bad.exit_code == 2 and "[bold]x[/bold]" in bad.output


def test_generate_help_names_the_default_approach_it_takes() -> None:
    from factask.cli import gen_cmds
    from factask.gen.results import DEFAULT_APPROACH

    assert gen_cmds._DEFAULT_APPROACH_HELP.startswith(f"default {DEFAULT_APPROACH}:")
    res = runner.invoke(app, ["generate", "--help"])
    assert f"default {DEFAULT_APPROACH}" in " ".join(res.output.split())


def test_the_reference_models_from_the_command_line(tmp_path) -> None:
    from factask.gen.compare import compare
    from factask.library import get_task

    out = tmp_path / "g.json"
    result = runner.invoke(app, ["generate", "--model", "local/reference", "--episodes", "1",
                                 "-o", str(out),
                                 "place-red-in-green: put the red blocks in the green bowls"])
    assert result.exit_code == 0, result.output
    graph = parse_graph(json.loads(out.read_text()))
    assert compare(graph, get_task("place-red-in-green")).equivalent
    bad = runner.invoke(app, ["generate", "--model", "local/noisy-reference:abc", "x"])
    assert bad.exit_code == 2 and "noise rate" in bad.output and "Traceback" not in bad.output
    # a benchmark answers each task from its own reference (the list's)
    tasks = tmp_path / "tasks.json"
    tasks.write_text(json.dumps([{"name": "place-red-in-green",
                                  "description": "put the red blocks in the green bowls"}]))
    run = runner.invoke(app, ["benchmark", "--model", "local/noisy-reference:1", "-a",
                              "one-shot", "--episodes", "1", "--tasks", str(tasks),
                              "-o", str(tmp_path / "run"), "--json"])
    assert run.exit_code == 0, run.output
    line = json.loads((tmp_path / "run" / "results.jsonl").read_text().splitlines()[0])
    assert line["faithful"] is True and line["repairs"] >= 1  # spoiled, then repaired
