"""The three strategies end to end: litellm -> loopback server -> verification ladder
(the real MuJoCo backend, floating robot) -> feedback -> repair."""

from __future__ import annotations

import json
from types import SimpleNamespace

import pytest

from factask.gen.conversation import REMOTE_ANSWER_TOKENS, RETRY_TEMPERATURES, answer_tokens
from factask.gen.demo import DEMO_PROPOSAL, demo_answers, demo_graph, demo_responder
from factask.gen.llm import LLMClient, LLMConfig, ResponseCache
from factask.gen.loopback import LoopbackServer, ScriptedResponder
from factask.gen.memory import SubtaskMemory
from factask.gen.results import APPROACHES, GenerationResult
from factask.gen.strategies import Generator, UnknownApproachError, split_proposal
from factask.gen.verify import Verifier
from factask.graph import parse_graph

EPISODES = 1  # the multi-episode rule is tested with scripted episodes below


def _client(server: LoopbackServer, cache=None) -> LLMClient:
    return LLMClient(LLMConfig(model="openai/scripted", api_base=server.url, num_retries=0,
                               timeout=30), ResponseCache(cache) if cache else None)


def _run(script, approach: str, max_repairs: int = 3, memory=None, cache=None,
         verifier=None, port: int = 0) -> tuple[GenerationResult, LoopbackServer]:
    responder = script if callable(script) else ScriptedResponder(script)
    with LoopbackServer(responder, port=port) as server:
        gen = Generator(_client(server, cache), verifier or Verifier(episodes=EPISODES),
                        memory=memory, max_repairs=max_repairs)
        result = gen.generate(DEMO_PROPOSAL, approach)
    return result, server


def _feedback_was_sent(server: LoopbackServer, result: GenerationResult) -> bool:
    """Every failed attempt but the last of its step reached the model as a user message."""
    sent = [m["content"] for r in server.requests for m in r["messages"] if m["role"] == "user"]
    failed = [s for s in result.steps if not s.ok and s.step != "assembly" and s.feedback]
    return all(any(s.feedback in text for text in sent) for s in failed[:1])


def test_split_proposal() -> None:
    assert split_proposal("build-a-bridge: two pillars and a deck") == (
        "build-a-bridge", "two pillars and a deck")
    name, desc = split_proposal("Put the red block in the bowl!")
    assert name == "put-red-block-in-bowl" and desc.startswith("Put")
    # whole words: never cut mid-phrase after "in the" (issue 37, item 15)
    assert split_proposal("put the small yellow cylinder and the blue ball in the green "
                          "bowl")[0] == "put-small-yellow-cylinder-and-blue-ball"
    assert split_proposal("place the blue ball into the second red zone")[0] == (
        "place-blue-ball-into-second-red-zone")
    assert split_proposal("stack-the-blocks: three high")[0] == "stack-the-blocks"  # given


@pytest.mark.parametrize("approach", APPROACHES)
def test_each_approach_recovers_from_a_broken_answer_and_completes(approach, tmp_path) -> None:
    memory = SubtaskMemory(tmp_path / "memory")
    result, server = _run(demo_responder(broken=True), approach, memory=memory)
    assert result.level_reached == "completion", result.failure
    assert result.failure is None and result.completed
    graph = parse_graph(result.graph.to_dict())  # valid as a whole
    assert graph.name == "stack-blue-on-red-in-zone"
    assert {f.goal.type for f in graph.factors} == {"in_zone", "on"}
    assert graph.factor_order() == ["place_red_in_zone", "stack_blue_on_red"]
    # At least one answer failed and a later attempt of the same step succeeded.
    failed_steps = {s.step for s in result.steps if not s.ok}
    assert failed_steps
    assert any(s.ok and s.attempt > 0 and s.step in failed_steps for s in result.steps)
    assert result.repairs >= 1
    assert _feedback_was_sent(server, result)
    assert result.usage.calls == len(server.requests) and result.usage.prompt_tokens > 0
    llm_steps = [s for s in result.steps if not (s.step == "assembly" and s.attempt == 0)]
    assert all(s.tokens > 0 for s in llm_steps)  # usage recorded per call
    assert sum(s.tokens for s in result.steps) == result.usage.total_tokens
    # Verified subtasks were remembered, and later prompts can retrieve them.
    assert {e["name"] for e in memory.entries()} == {"place_red_in_zone", "stack_blue_on_red"}
    # The result survives a JSON round trip (a benchmark line).
    again = GenerationResult.from_dict(json.loads(json.dumps(result.to_dict())))
    assert again.level_reached == "completion" and again.graph == result.graph


def test_repairs_that_never_succeed_are_bounded_and_reported() -> None:
    result, server = _run({"one_shot": ["still thinking...", "hmm, thinking", "no idea",
                                        "fourth"]}, "one-shot", max_repairs=2)
    assert len(server.requests) == 3  # first answer + 2 repairs, no more
    assert [s.attempt for s in result.steps] == [0, 1, 2]
    assert not any(s.ok for s in result.steps)
    assert result.level_reached == "none" and result.graph is None
    assert "one_shot" in result.failure and "JSON" in result.failure
    # The conversation grew by the answer and the feedback at each repair.
    assert [len(r["messages"]) for r in server.requests] == [2, 4, 6]
    # Each retry samples differently: another seed, a warmer temperature.
    seeds = [r["seed"] for r in server.requests]
    temps = [r["temperature"] for r in server.requests]
    assert len(set(seeds)) == 3 and temps[0] == 0 and temps[1] > 0 and temps[2] > temps[1]
    # A remote model's bound is generous (a capable model's whole graph is longer
    # than the local model's budget); the local model's is sized per step.
    assert all(r["max_tokens"] == REMOTE_ANSWER_TOKENS for r in server.requests)
    assert answer_tokens("one_shot") == 1200 < answer_tokens("one_shot", local=False)


def test_a_repeated_answer_stops_the_step_early() -> None:
    result, server = _run({"one_shot": ["still thinking..."]}, "one-shot", max_repairs=5)
    # The second answer repeats the first: the third try samples at the warmest
    # temperature; it repeats again: stop (3 of the 6 allowed attempts).
    assert len(server.requests) == 3
    temps = [r["temperature"] for r in server.requests]
    assert temps[2] == max(RETRY_TEMPERATURES) > temps[1]
    assert len({r["seed"] for r in server.requests}) == 3
    assert "repeats an earlier one" in result.steps[1].feedback
    assert "repeated an earlier answer twice" in result.steps[-1].feedback
    assert result.level_reached == "none"
    # The try after a repeat does not show the model its answers (a small model
    # copies what it sees); the feedback is in the one user message.
    roles = [m["role"] for m in server.requests[2]["messages"]]
    assert roles == ["system", "user"]
    assert "repeats an earlier one" in server.requests[2]["messages"][1]["content"]


def test_infeasible_layout_gets_runtime_feedback_then_repair() -> None:
    crowded = demo_graph()
    crowded["variables"][0]["count"] = 40  # 40 blocks cannot fit in one zone
    result, server = _run({"one_shot": [json.dumps(crowded), json.dumps(demo_graph())]},
                          "one-shot")
    first = result.steps[0]
    assert not first.ok and first.level == "syntax"
    assert "Level 2 (runtime)" in first.feedback and "place_red_in_zone" in first.feedback
    assert result.level_reached == "completion"
    assert first.feedback in server.requests[1]["messages"][-1]["content"]


def test_best_graph_is_kept_when_repairs_run_out() -> None:
    crowded = demo_graph()
    crowded["variables"][0]["count"] = 40
    result, _ = _run({"one_shot": [json.dumps(crowded), "junk"]}, "one-shot", max_repairs=1)
    assert result.level_reached == "syntax"  # the valid-but-infeasible graph is kept
    assert result.graph is not None and result.graph.variables[0].count == 40
    assert result.failure and not result.completed


def test_missing_variables_and_wrong_schema_are_repaired() -> None:
    good = demo_answers()
    plan = json.loads(good["subtask_plan"])
    plan["subtasks"][1]["variables"] = ["blue_block", "purple_block"]
    script = dict(good, subtask_plan=[json.dumps(plan), good["subtask_plan"]],
                  variables=[json.dumps({"objects": ["red"]}), good["variables"]])
    result, _ = _run(script, "variables-first")
    fb = {s.step: s.feedback for s in result.steps if not s.ok}
    assert "does not follow the schema" in fb["variables"]
    assert "'variables' is a required property" in fb["variables"]
    # An unknown variable in the plan: the plan's check names it and the declared ones
    # (a plan the schema refuses but the plan model takes reaches that check).
    assert "unknown variable 'purple_block'" in fb["subtask_plan"]
    assert "['red_block', 'blue_block', 'green_zone']" in fb["subtask_plan"]
    assert result.level_reached == "completion"


def test_subtasks_first_may_leave_out_earlier_variables() -> None:
    good = demo_answers()
    design = {"variables": [json.loads(good["subtask_design:stack_blue_on_red"])
                            ["variables"][0]],
              "goal": {"type": "on", "objects": ["blue_block"], "support": "red_block"},
              "description": ""}
    script = dict(good, **{"subtask_design:stack_blue_on_red": json.dumps(design)})
    result, _ = _run(script, "subtasks-first")
    assert result.level_reached == "completion"
    assert sorted(v.name for v in result.graph.variables) == [
        "blue_block", "green_zone", "red_block"]


def test_a_planning_step_that_never_parses_stops_with_a_structured_failure() -> None:
    result, server = _run({"subtask_outline": ['{"subtasks": []}']}, "subtasks-first",
                          max_repairs=1)
    assert len(server.requests) == 2
    assert result.level_reached == "none" and result.graph is None
    assert result.failure.startswith("subtask_outline")


def test_rerun_from_the_cache_is_free_and_identical(tmp_path) -> None:
    first, s1 = _run(demo_responder(broken=True), "one-shot", cache=tmp_path)
    # The same endpoint (the API base is part of the cache key).
    second, s2 = _run(ScriptedResponder({}), "one-shot", cache=tmp_path, port=s1.port)
    assert len(s2.requests) == 0
    assert second.usage.cached_calls == second.usage.calls == first.usage.calls
    assert second.usage.total_tokens == 0
    assert second.graph == first.graph
    assert [(s.step, s.attempt, s.ok) for s in second.steps] == [
        (s.step, s.attempt, s.ok) for s in first.steps]


def test_unknown_approach_is_a_typed_error() -> None:
    with LoopbackServer(ScriptedResponder({})) as server, pytest.raises(UnknownApproachError):
        Generator(_client(server)).generate("x: y", "bottom-up")


class _ScriptedEpisodes(Verifier):
    """The real completion logic over scripted episode outcomes."""

    def __init__(self, outcomes: list[bool]) -> None:
        super().__init__(episodes=len(outcomes))
        self.outcomes = outcomes

    def _backend(self):  # type: ignore[override]
        def check_runtime(graph, seed=0, robot="floating"):
            return None

        def run_episode(graph, seed, robot="floating"):
            i = self.seeds.index(seed) if seed in self.seeds else len(self.seeds)
            self.seeds.append(seed)
            ok = self.outcomes[i % len(self.outcomes)]
            return SimpleNamespace(
                seed=seed, reward=1.0 if ok else 0.5, success=ok, steps=3,
                failure=None if ok else "stack_blue_on_red: no free spot on red_block",
                factors={"place_red_in_zone": 1.0, "stack_blue_on_red": 1.0 if ok else 0.0},
                details={"stack_blue_on_red": "blue_block is 3 cm off the red block"})
        self.seeds: list[int] = []
        return check_runtime, run_episode


def test_completion_needs_half_the_episodes_with_distinct_seeds() -> None:
    graph = parse_graph(demo_graph())
    v = _ScriptedEpisodes([True, False, False])
    outcome = v.check(graph)
    assert outcome.level == "runtime" and not outcome.ok
    assert len(set(v.seeds)) == 3
    assert "1 of 3 episodes" in outcome.feedback
    assert "factor 'stack_blue_on_red' progress 0.00" in outcome.feedback
    assert "3 cm off" in outcome.feedback and "no free spot" in outcome.feedback
    assert _ScriptedEpisodes([True, False]).check(graph).level == "completion"


# ------------------------------------------------ review fixes (fake clients)
class _FakeClient:
    """Answers from a list (the last repeats); an exception in it is raised."""

    def __init__(self, answers) -> None:
        self.answers = list(answers)
        self.prompts: list[list[dict]] = []

    def complete(self, messages, schema=None, schema_name="answer", **sampling):
        from factask.gen.llm import LLMReply, Usage

        self.prompts.append([dict(m) for m in messages])
        item = self.answers[min(len(self.prompts) - 1, len(self.answers) - 1)]
        if isinstance(item, BaseException):
            raise item
        return LLMReply(text=item, usage=Usage(calls=1, prompt_tokens=1), cached=False,
                        key="k")


class _StubVerifier(Verifier):
    """Levels 2 and 3 scripted: ``syntax`` with feedback, or ``completion``."""

    def __init__(self, level: str = "completion", error: Exception | None = None) -> None:
        super().__init__(episodes=1)
        self.level, self.error = level, error

    def check(self, graph, target="completion"):
        from factask.gen.verify import VerifyOutcome

        if self.error is not None:
            raise self.error
        if self.level == "completion":
            return VerifyOutcome("completion")
        return VerifyOutcome(self.level, f"Level 2 (runtime) failed: {graph.variables[0].count}"
                             " blocks do not fit")


def _crowded() -> str:
    g = demo_graph()
    g["variables"][0]["count"] = 40
    return json.dumps(g)


def test_transient_request_and_auth_errors_are_told_apart() -> None:
    from factask.gen.llm import LLMAuthError, LLMRequestError, LLMTransientError

    gen = Generator(_FakeClient([LLMTransientError("connection refused")]), _StubVerifier())
    result = gen.generate(DEMO_PROPOSAL, "one-shot")
    assert result.llm_error and "connection refused" in result.failure
    # A rejected request is the model's failure (counted in the rates), not an outage.
    gen = Generator(_FakeClient([LLMRequestError("ContextWindowExceededError: too long")]),
                    _StubVerifier())
    result = gen.generate(DEMO_PROPOSAL, "variables-first")
    assert not result.llm_error and result.level_reached == "none"
    assert "rejected" in result.failure and "ContextWindow" in result.failure
    with pytest.raises(LLMAuthError):
        Generator(_FakeClient([LLMAuthError("bad key")]), _StubVerifier()).generate(
            DEMO_PROPOSAL, "subtasks-first")


def test_a_rejected_repair_keeps_the_best_graph_and_its_level() -> None:
    from factask.gen.llm import LLMRequestError

    client = _FakeClient([_crowded(), LLMRequestError("ContextWindowExceededError")])
    result = Generator(client, _StubVerifier("syntax"), max_repairs=3).generate(
        DEMO_PROPOSAL, "one-shot")
    assert not result.llm_error and result.level_reached == "syntax"
    assert result.graph is not None and result.graph.variables[0].count == 40
    assert "40 blocks do not fit" in result.failure and "rejected" in result.failure


def test_failure_is_the_feedback_of_the_best_attempt_not_the_last() -> None:
    client = _FakeClient([_crowded(), "junk"])
    result = Generator(client, _StubVerifier("syntax"), max_repairs=2).generate(
        DEMO_PROPOSAL, "one-shot")
    assert result.level_reached == "syntax"
    assert "40 blocks do not fit" in result.failure and "JSON" not in result.failure


def test_long_task_names_are_cut_and_the_final_graph_is_valid() -> None:
    long = "-".join(["stack"] * 40)  # 239 characters
    assert len(split_proposal(f"{long}: d")[0]) <= 100
    assert len(split_proposal(" ".join(["word"] * 30))[0]) <= 100
    result = Generator(_FakeClient([json.dumps(demo_graph())]), _StubVerifier()).generate(
        "stack them", "one-shot", name=long)
    assert result.level_reached == "completion", result.failure
    assert len(result.task) <= 100 and result.graph.name == result.task
    parse_graph(result.graph.to_dict())


def test_an_unexpected_error_while_checking_is_feedback_not_a_crash() -> None:
    client = _FakeClient([json.dumps(demo_graph())])
    result = Generator(client, _StubVerifier(error=ZeroDivisionError("boom")),
                       max_repairs=1).generate(DEMO_PROPOSAL, "one-shot")
    assert len(client.prompts) == 2 and result.level_reached == "none"
    assert "ZeroDivisionError: boom" in result.steps[0].feedback
    assert "ZeroDivisionError: boom" in client.prompts[1][-1]["content"]


def test_prompts_never_show_the_task_itself(tmp_path) -> None:
    pytest.importorskip("factask.library")
    from factask.library import get_task

    library = get_task("build-bridge")
    memory = SubtaskMemory(tmp_path / "mem")
    graph = parse_graph(demo_graph())
    memory.save(_one_factor(graph, 0), task="build-bridge", approach="one-shot")
    memory.save(_one_factor(graph, 1), task="another-task", approach="one-shot")
    for approach in ("one-shot", "variables-first"):
        client = _FakeClient(["junk"])
        Generator(client, _StubVerifier(), memory=memory, max_repairs=0).generate(
            f"build-bridge: {library.description}", approach)
        prompt = client.prompts[0][1]["content"]
        assert "(library-task) `build-bridge`" not in prompt
        assert "verified in task build-bridge" not in prompt
        assert "verified in task another-task" in prompt
        # Without the exclusion the same query would show it.
        other = _FakeClient(["junk"])
        Generator(other, _StubVerifier(), max_repairs=0).generate(
            f"bridge-task-x: {library.description}", approach)
        assert "(library-task) `build-bridge`" in other.prompts[0][1]["content"]


def _one_factor(graph, i):
    from factask.graph import extract_fragment

    return extract_fragment(graph, graph.factors[i].name)


@pytest.mark.parametrize("approach", ["variables-first", "subtasks-first"])
def test_subtasks_moving_one_object_are_sequenced_in_the_plans_order(approach: str) -> None:
    # The red block goes to the zone, then onto... the zone again is pointless, so:
    # first into the zone (a milestone), then stacked on the blue block (final).
    from factask.gen.demo import BLUE, RED, ZONE

    on_blue = {"type": "on", "objects": ["red_block"], "support": "blue_block"}
    in_zone = {"type": "in_zone", "objects": ["red_block"], "zone": "green_zone"}
    script = dict(demo_answers())
    script["subtask_plan"] = json.dumps({"subtasks": [
        {"name": "red_to_zone", "description": "put the red block in the zone",
         "variables": ["red_block", "green_zone"], "initial_setup": ""},
        {"name": "red_on_blue", "description": "then put the red block on the blue block",
         "variables": ["red_block", "blue_block"], "initial_setup": ""}]})
    script["subtask_goal:red_to_zone"] = json.dumps({"goal": in_zone, "description": ""})
    script["subtask_goal:red_on_blue"] = json.dumps({"goal": on_blue, "description": ""})
    script["subtask_outline"] = json.dumps({"subtasks": [
        {"name": "red_to_zone", "description": "the red block is in the zone"},
        {"name": "red_on_blue", "description": "the red block is on the blue block"}]})
    script["subtask_design:red_to_zone"] = json.dumps(
        {"variables": [RED, ZONE], "goal": in_zone, "description": ""})
    script["subtask_design:red_on_blue"] = json.dumps(
        {"variables": [RED, BLUE], "goal": on_blue, "description": ""})
    result, _ = _run(script, approach, max_repairs=0)
    assert result.graph is not None, result.failure
    by_name = {f.name.split("__")[-1]: f for f in result.graph.factors}
    first, second = (next(f for n, f in by_name.items() if n.endswith(k))
                     for k in ("red_to_zone", "red_on_blue"))
    assert first.milestone and not second.milestone and first.name in second.after
    assert result.graph.problems() == []
