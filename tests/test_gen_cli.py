"""``factask generate`` against the loopback server (in-process CLI runner)."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from factask.cli import app
from factask.gen.demo import DEMO_PROPOSAL, demo_responder
from factask.gen.loopback import LoopbackServer, ScriptedResponder
from factask.model import parse_graph

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
    res = runner.invoke(app, ["generate", "x: y"])
    assert res.exit_code == 2 and "FACTASK_MODEL" in res.output
