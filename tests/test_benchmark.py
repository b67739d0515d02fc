"""The generation benchmark: expressibility, rates, files, and resume after SIGKILL."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from helpers import GENSIM_TASKS as GENSIM
from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

from factask.cli import app
from factask.evaluation.benchmark import (
    RESEARCH_RATES,
    BenchmarkError,
    BenchTask,
    load_tasks,
    meaning_of,
    non_rigid_reason,
    not_expressible_reason,
    read_results,
    reference_graph,
    research_sample,
    run_benchmark,
    summarize,
    summary_table,
)
from factask.gen.demo import demo_responder
from factask.gen.llm import LLMClient, LLMConfig
from factask.gen.loopback import LoopbackServer
from factask.gen.strategies import Generator
from factask.gen.verify import Verifier
from factask.library.tasks import get_task

TASKS = [
    {"name": "red-in-zone-then-blue-on-red", "description": "put the red block in the zone, "
     "then the blue block on it", "assets": ["block/block.urdf", "zone/zone.urdf"]},
    {"name": "fold-the-cloth", "description": "fold the cloth in half",
     "assets": ["cloth/cloth.urdf"]},
    {"name": "blue-on-red-in-green-zone", "description": "red block in the green zone, blue "
     "block on top", "assets": ["block/block.urdf"]},
]


@pytest.mark.skipif(not GENSIM.exists(), reason="gensim_tasks.json not available")
def test_rope_and_pile_tasks_go_to_the_model_and_stay_out_of_the_rigid_sample() -> None:
    tasks = load_tasks(GENSIM)
    assert len(tasks) == 192
    assert not [t.name for t in tasks if not_expressible_reason(t)]  # no cloth, no bag
    non_rigid = {t.name for t in tasks if non_rigid_reason(t)}
    assert {"sweeping-piles", "manipulating-rope", "align-rope", "separating-piles",
            "connect-boxes-with-rope", "push-piles-into-letter", "mix-piles",
            "sweep-and-sort-blocks"} <= non_rigid
    assert not non_rigid & {"place-red-in-green", "align-box-corner", "stack-block-pyramid",
                            "towers-of-hanoi", "assembling-kits"}
    assert len(non_rigid) < 20
    assert not {t.name for t in research_sample(tasks)} & non_rigid


def test_not_expressible_reason_reads_assets_and_words() -> None:
    pushed = BenchTask("x", "push the small blocks into the zone", ["block/small.urdf"])
    assert not_expressible_reason(pushed) is None and non_rigid_reason(pushed)
    rope = BenchTask("x", "lay the rope along the line", ["square/square-template.urdf"])
    assert not_expressible_reason(rope) is None and "rope" in non_rigid_reason(rope)
    assert "cloth" in not_expressible_reason(BenchTask("x", "fold it", ["cloth/cloth.urdf"]))
    assert "bag" in not_expressible_reason(BenchTask("x", "put the block in the bag", []))
    stack = BenchTask("stack-blocks", "stack three blocks", ["block/block.urdf"])
    assert not_expressible_reason(stack) is None and non_rigid_reason(stack) is None


@given(st.text(max_size=200), st.lists(st.text(max_size=40), max_size=5))
def test_expressibility_reads_any_text_without_error(text: str, assets: list[str]) -> None:
    task = BenchTask("t", text, assets)
    for reason in (not_expressible_reason(task), non_rigid_reason(task)):
        assert reason is None or (isinstance(reason, str) and "\n" not in reason)
    if not_expressible_reason(task):
        assert non_rigid_reason(task)  # what no world holds is not rigid either


def test_summary_last_line_wins_and_errors_are_separate() -> None:
    lines = [
        {"approach": "one-shot", "task": "a", "status": "llm_error", "level_reached": "none"},
        {"approach": "one-shot", "task": "a", "status": "done", "level_reached": "runtime",
         "usage": {"total_tokens": 10, "cost_usd": 0.5}},
        {"approach": "one-shot", "task": "b", "status": "done", "level_reached": "completion"},
        {"approach": "one-shot", "task": "c", "status": "not_expressible"},
        {"approach": "one-shot", "task": "d", "status": "llm_error", "level_reached": "none"},
    ]
    s = summarize(lines, ["one-shot"])
    row = s["approaches"]["one-shot"]
    assert row["tasks"] == 2 and row["llm_errors"] == 1 and row["not_expressible"] == 1
    assert (row["syntax"], row["runtime"], row["completion"]) == (1.0, 1.0, 0.5)
    assert row["tokens"] == 10
    table = summary_table(s)
    assert "| one-shot | 2 | 100.0 | 100.0 | 50.0 | - | 1 | 1 |" in table
    assert "95.0 / 53.3 / 16.7" in table


def test_faithful_is_judged_against_the_reference_and_summarised() -> None:
    wanted = get_task("stack-block-pyramid")
    task = BenchTask("stack-block-pyramid", "stack the blocks into a pyramid")
    assert reference_graph(task) == wanted  # the library's graph of the same name
    assert meaning_of(wanted, task)["faithful"] is True
    other = meaning_of(get_task("build-house"), task)
    assert other["faithful"] is False
    assert any(d.startswith("missing goal") for d in other["meaning"]["differences"])
    assert meaning_of(None, task) == {"faithful": False, "meaning": {
        "reference": "stack-block-pyramid", "differences": ["no graph"]}}
    own = BenchTask("my-task", "words", reference="build-house")
    assert meaning_of(get_task("build-house"), own)["faithful"] is True
    assert meaning_of(wanted, BenchTask("not-in-the-library", "words"))["faithful"] is None
    with pytest.raises(BenchmarkError, match="reference"):
        reference_graph(BenchTask("x", "y", reference={"name": "x", "variables": "none"}))
    lines = [{"approach": "one-shot", "task": n, "status": "done",
              "level_reached": "completion", "faithful": f}
             for n, f in (("a", True), ("b", False), ("c", None))]
    row = summarize(lines, ["one-shot"])["approaches"]["one-shot"]
    assert row["faithful"] == 0.5 and row["counts"]["with_reference"] == 2
    assert "| 50.0 (of 2) |" in summary_table(summarize(lines, ["one-shot"]))


def _generator(server: LoopbackServer) -> Generator:
    client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url, num_retries=0))
    return Generator(client, Verifier(episodes=1), max_repairs=1)


def test_run_writes_jsonl_summary_table_chart_and_skips_finished_pairs(tmp_path) -> None:
    tasks = [BenchTask(**t) for t in TASKS[:2]]
    # Two approaches keep the test fast; every approach runs end to end in
    # test_gen_strategies.py.
    approaches = ["one-shot", "subtasks-first"]
    seen: list[dict] = []
    with LoopbackServer(demo_responder(broken=False)) as server:
        summary = run_benchmark(tasks, approaches, _generator(server), tmp_path,
                                on_result=seen.append)
        served = server.served
        again = run_benchmark(tasks, approaches, _generator(server), tmp_path)
        assert server.served == served  # nothing re-ran
    lines = read_results(tmp_path / "results.jsonl")
    assert len(lines) == len(seen) == 4
    for a in approaches:
        row = summary["approaches"][a]
        assert row["tasks"] == 1 and row["not_expressible"] == 1
        assert row["completion"] == 1.0
    assert again["approaches"] == summary["approaches"]
    cloth = [r for r in lines if r["task"] == "fold-the-cloth"]
    assert {r["status"] for r in cloth} == {"not_expressible"} and "cloth" in cloth[0]["reason"]
    saved = json.loads((tmp_path / "summary.json").read_text())
    assert saved["research"]["subtasks-first"] == list(RESEARCH_RATES["subtasks-first"])
    assert "| subtasks-first | 1 | 100.0 | 100.0 | 100.0 | - | 1 |" in (
        tmp_path / "summary.md").read_text()
    done = [r for r in lines if r["status"] == "done"]
    assert {r["faithful"] for r in done} == {None}  # no library task of that name
    assert {r["meaning"]["reference"] for r in done} == {None}
    assert (tmp_path / "rates.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


class _Gate:
    """Answers the first request at once; later ones wait until opened."""

    def __init__(self) -> None:
        self.inner = demo_responder(broken=False)
        self.opened = threading.Event()
        self.count = 0

    def __call__(self, request: dict) -> str:
        self.count += 1
        if self.count > 1:
            self.opened.wait(timeout=300)
        return self.inner(request)


def _bench_cmd(url: str, tasks: Path, out: Path) -> list[str]:
    return [sys.executable, "-m", "factask", "benchmark", "--approach", "one-shot",
            "--model", "openai/scripted", "--api-base", url, "--tasks", str(tasks),
            "--out", str(out), "--episodes", "1", "--max-repairs", "1"]


def test_killed_run_resumes_without_losing_or_repeating_a_task(tmp_path) -> None:
    tasks_file = tmp_path / "tasks.json"
    tasks_file.write_text(json.dumps(TASKS))
    run = tmp_path / "run"
    results = run / "results.jsonl"
    env = {**os.environ, "LITELLM_LOCAL_MODEL_COST_MAP": "True",
           "MUJOCO_GL": os.environ.get("MUJOCO_GL", "egl"), "FACTASK_CACHE": ""}
    gate = _Gate()
    with LoopbackServer(gate) as server:
        log = (tmp_path / "first.log").open("w")
        child = subprocess.Popen(_bench_cmd(server.url, tasks_file, run), env=env,
                                 stdout=log, stderr=subprocess.STDOUT, cwd=tmp_path)
        try:
            # Wait (polling, bounded) for the first finished line, then kill -9.
            for _ in range(1200):
                if results.exists() and results.read_text().count("\n") >= 1:
                    break
                if child.poll() is not None:
                    pytest.fail("benchmark exited early:\n" + (tmp_path / "first.log")
                                .read_text())
                time.sleep(0.25)
            else:
                pytest.fail("no result line appeared")
            child.send_signal(signal.SIGKILL)
            child.wait()
        finally:
            if child.poll() is None:
                child.kill()
            log.close()
        before = results.read_text()
        first = before.splitlines()[0]
        assert child.returncode == -signal.SIGKILL
        assert json.loads(first)["task"] == TASKS[0]["name"]
        assert not (run / "summary.json").exists()  # it really stopped midway

        gate.opened.set()
        # Resume with the same command line, in-process (saves a second interpreter start).
        done = CliRunner().invoke(app, _bench_cmd(server.url, tasks_file, run)[3:])
    assert done.exit_code == 0, done.output
    assert "resuming" in done.output
    after = results.read_text()
    assert after.startswith(before)  # nothing lost or rewritten
    lines = [json.loads(x) for x in after.splitlines()]
    pairs = [(r["approach"], r["task"]) for r in lines]
    assert len(pairs) == len(set(pairs)) == len(TASKS)  # every task once
    assert {r["task"] for r in lines} == {t["name"] for t in TASKS}
    summary = json.loads((run / "summary.json").read_text())
    row = summary["approaches"]["one-shot"]
    assert row["tasks"] == 2 and row["not_expressible"] == 1 and row["completion"] == 1.0
    assert (run / "summary.md").exists() and (run / "rates.png").exists()
    assert "one-shot" in done.output and "16.7" in done.output


# ------------------------------------------------------------- review fixes
class _Flaky(Generator):
    """Crashes on one task; records which memory each pair was given."""

    def __init__(self, crash_on: str, error: Exception | None = None, memory=None) -> None:
        super().__init__(LLMClient(LLMConfig(model="openai/none")), Verifier(episodes=1),
                         memory=memory)
        self.crash_on, self.error, self.seen = crash_on, error, []

    def generate(self, proposal, approach="variables-first", name=None, description=None):
        from factask.gen.results import GenerationResult

        where = self.memory.directory if self.memory is not None else None
        self.seen.append((approach, name, where))
        if name == self.crash_on:
            raise self.error or KeyError("boom")
        return GenerationResult(approach=approach, proposal=proposal, task=name,
                                level_reached="runtime", failure="stopped at runtime")


def test_an_unexpected_error_is_a_recorded_failure_and_the_run_goes_on(tmp_path) -> None:
    tasks = [BenchTask(**TASKS[0]), BenchTask(**TASKS[2])]
    gen = _Flaky(crash_on=TASKS[0]["name"])
    summary = run_benchmark(tasks, ["one-shot"], gen, tmp_path)
    lines = read_results(tmp_path / "results.jsonl")
    assert [r["status"] for r in lines] == ["error", "done"]
    assert "KeyError" in lines[0]["error"] and lines[0]["level_reached"] == "none"
    row = summary["approaches"]["one-shot"]
    assert row["tasks"] == 2 and row["errors"] == 1 and row["runtime"] == 0.5
    run_benchmark(tasks, ["one-shot"], gen, tmp_path)
    assert len(gen.seen) == 2  # an error line is finished, not retried forever


def test_auth_error_stops_the_run(tmp_path) -> None:
    from factask.gen.llm import LLMAuthError

    gen = _Flaky(crash_on=TASKS[0]["name"], error=LLMAuthError("bad key"))
    with pytest.raises(LLMAuthError):
        run_benchmark([BenchTask(**TASKS[0])], ["one-shot"], gen, tmp_path)
    assert read_results(tmp_path / "results.jsonl") == []


def test_each_approach_has_its_own_memory_and_summary_says_examples_exclude_the_task(
        tmp_path) -> None:
    from factask.gen.memory import SubtaskMemory

    gen = _Flaky(crash_on="", memory=SubtaskMemory(tmp_path / "mem"))
    run_benchmark([BenchTask(**TASKS[0])], ["one-shot", "subtasks-first"], gen,
                  tmp_path / "run")
    assert [d for _, _, d in gen.seen] == [tmp_path / "mem" / "one-shot",
                                           tmp_path / "mem" / "subtasks-first"]
    assert gen.memory.directory == tmp_path / "mem"  # restored
    saved = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert saved["examples"]["exclude_task_itself"] is True
    assert saved["examples"]["memory"] == "per approach"


def test_benchmark_honours_factask_cache(tmp_path, monkeypatch) -> None:
    import factask.cli.gen_cmds as cmds

    tasks_file = tmp_path / "tasks.json"
    tasks_file.write_text(json.dumps(TASKS))
    given = []

    def fake(model, api_base, cache, *args, **kwargs):
        given.append(cache)
        raise SystemExit(0)

    monkeypatch.setattr(cmds, "_session", fake)
    args = ["benchmark", "-a", "one-shot", "--model", "m", "--tasks", str(tasks_file),
            "--out", str(tmp_path / "run")]
    monkeypatch.setenv("FACTASK_CACHE", str(tmp_path / "shared-cache"))
    CliRunner().invoke(app, args)
    monkeypatch.setenv("FACTASK_CACHE", "")
    CliRunner().invoke(app, args)
    CliRunner().invoke(app, [*args, "--cache", str(tmp_path / "c")])
    assert given == [tmp_path / "shared-cache", tmp_path / "run" / "cache", tmp_path / "c"]


def test_the_default_task_list_ships_with_the_package() -> None:
    from factask.evaluation.benchmark import default_tasks_path

    path = default_tasks_path()
    assert path.is_file() and "factask" in path.parts
    assert len(load_tasks(path)) == 192
