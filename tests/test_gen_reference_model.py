"""The reference models (issue 34, part 5): a capable model's answers, from reference
graphs, through litellm and the loopback server on the ungrounded path remote models
take; the perfect one means the reference with every approach, the noisy one's errors
are caught and repaired."""

from __future__ import annotations

import json
import re
from collections import Counter

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.gen.answers import step_schemas as ss
from factask.gen.compare import compare
from factask.gen.llm import LLMConfig
from factask.gen.reference_model import (
    ERROR_KINDS,
    NOISY_REFERENCE_MODEL,
    REFERENCE_MODEL,
    ReferenceModelError,
    ReferenceResponder,
    fit,
    in_step_names,
    noise_of,
    planned_error,
    reference_answer,
    repair_table,
    spoil,
)
from factask.gen.results import APPROACHES
from factask.gen.session import open_client
from factask.gen.strategies import Generator
from factask.gen.verify import Verifier
from factask.graph import parse_graph
from factask.graph.factors import SubtaskFactor
from factask.graph.taskgraph import TaskGraph
from factask.library import get_task, task_names
from factask.relations import InZone, On
from factask.vocabulary.variables import StateVariable

#: Small tasks whose references order subtasks between different objects (``after``),
#: move one object twice (milestones), fix an object of a movable kind, or name
#: factors the steps' pattern refuses.
TASKS = ("towers-of-hanoi-seq", "place-red-in-green", "stack-block-pyramid")


def _generate(model: str, task: str, approach: str, max_repairs: int = 2):
    graph = get_task(task)
    with open_client(LLMConfig(model=model, num_retries=0, timeout=30),
                     references={task: graph}) as client:
        assert not client.config.is_local  # the remote path, not the grounded one
        gen = Generator(client, Verifier(episodes=1), max_repairs=max_repairs)
        return gen.generate(f"{task}: {graph.description}", approach), graph


@pytest.mark.parametrize("approach", APPROACHES)
@pytest.mark.parametrize("task", TASKS)
def test_the_perfect_reference_means_its_task_with_every_approach(task, approach) -> None:
    result, reference = _generate(REFERENCE_MODEL, task, approach)
    assert result.graph is not None, result.failure
    judged = compare(result.graph, reference)
    assert judged.equivalent, judged.differences
    assert not any(not s.ok for s in result.steps), [s.feedback for s in result.steps]


@pytest.mark.parametrize("approach", APPROACHES)
def test_every_error_of_the_noisy_reference_is_caught_and_repaired(approach) -> None:
    task = "towers-of-hanoi-seq"  # seven subtasks: many steps to spoil
    result, reference = _generate(f"{NOISY_REFERENCE_MODEL}:1.0", task, approach)
    assert result.graph is not None, result.failure
    assert compare(result.graph, reference).equivalent
    record = {"task": task, "faithful": True, "steps": [s.to_dict() for s in result.steps]}
    table = repair_table([record], 1.0)
    made = sum(row["made"] for row in table.values())
    asked = {s.step for s in result.steps if not (s.step == "assembly" and s.attempt == 0)}
    assert made == len(asked)
    for kind, row in table.items():  # every first answer was spoiled, refused, repaired
        assert row["caught"] == row["repaired"] == row["made"], (kind, row)


def test_the_plan_orders_subtasks_on_different_objects_with_after() -> None:
    variables = [StateVariable(name=n, kind="block", color=c)
                 for n, c in (("red_block", "red"), ("blue_block", "blue"),
                              ("green_block", "green"))]
    variables.append(StateVariable(name="zone", kind="zone", color="gray"))
    first = SubtaskFactor(name="blue_on_red", weight=0.5, goal=On(objects=["blue_block"],
                                                      support="red_block"))
    # different objects, no shared anchor: only `after` orders the two
    then = SubtaskFactor(name="green_in_zone", weight=0.5, goal=InZone(objects=["green_block"],
                                                           zone="zone"),
                         after=["blue_on_red"])
    graph = parse_graph(TaskGraph(name="two-steps", description="first blue on red, then "
                                  "green into the zone", variables=variables,
                                  factors=[first, then]).to_dict())
    plan = reference_answer(graph, "subtask_plan", None)
    assert [s["after"] for s in plan["subtasks"]] == [[], ["blue_on_red"]]
    for approach in ("variables-first", "subtasks-first"):
        with open_client(LLMConfig(model=REFERENCE_MODEL, num_retries=0, timeout=30),
                         references={"two-steps": graph}) as client:
            gen = Generator(client, Verifier(episodes=1), max_repairs=1)
            result = gen.generate(f"two-steps: {graph.description}", approach)
        assert result.graph is not None, result.failure
        by_name = {f.name: f for f in result.graph.factors}
        assert by_name["green_in_zone"].after == ["blue_on_red"], approach
        assert compare(result.graph, graph).equivalent


def test_a_plan_whose_after_names_a_later_or_unknown_subtask_is_sent_back() -> None:
    from factask.gen.answers.schemas import SubtaskOutline
    from factask.gen.fragments import order_problems, relabelled

    outline = SubtaskOutline.model_validate({"subtasks": [
        {"name": "a", "description": "x", "after": ["b"]},
        {"name": "b", "description": "y", "after": ["c"]}]})
    problems = order_problems(outline.subtasks)
    assert [(p.node, p.field) for p in problems] == [("a", "after"), ("b", "after")]
    assert "not a subtask listed before it" in problems[0].message
    # a repeated name made distinct keeps the after pointing at its first holder
    again = SubtaskOutline.model_validate({"subtasks": [
        {"name": "a", "description": "x"}, {"name": "a", "description": "y", "after": ["a"]}]})
    assert [(s.name, s.after) for s in relabelled(again.subtasks)] == [("a", []),
                                                                      ("a_2", ["a"])]


def test_every_library_graph_has_names_the_steps_take_and_answers_in_step_form() -> None:
    pattern = re.compile(ss.NAME_REGEX)
    for name in task_names():
        graph = in_step_names(get_task(name))
        names = [v.name for v in graph.variables] + [f.name for f in graph.factors]
        assert all(pattern.match(n) for n in names), name
        assert len(set(names)) == len(names), name
        scope = {v.name: v.kind for v in graph.variables}
        plan = fit(reference_answer(graph, "subtask_plan", None),
                   ss.subtask_plan(list(scope), 16))
        assert not [p for p in ss.schema_problems(plan, ss.subtask_plan(list(scope), 16))
                    if "maxItems" not in p and "too long" not in p], name
        outline = fit(reference_answer(graph, "subtask_outline", None), ss.subtask_outline())
        assert all(len(s["description"]) <= ss.MAX_TEXT for s in outline["subtasks"])


def test_noise_rates_and_planned_errors() -> None:
    assert noise_of(REFERENCE_MODEL) == 0.0
    assert noise_of(NOISY_REFERENCE_MODEL) == pytest.approx(0.3)
    assert noise_of(f"{NOISY_REFERENCE_MODEL}:0.75") == 0.75
    for bad in ("x", "1.5", "-0.1", "nan"):
        with pytest.raises(ReferenceModelError, match="noise rate"):
            noise_of(f"{NOISY_REFERENCE_MODEL}:{bad}")
    steps = [f"subtask_goal:s{i}" for i in range(400)]
    assert all(planned_error("t", s, 0.0) is None for s in steps)
    kinds = Counter(planned_error("t", s, 1.0) for s in steps)
    assert set(kinds) == {"unknown_name", "missing_field", "goal_on_itself", "cut_off"}
    half = sum(planned_error("t", s, 0.5) is not None for s in steps)
    assert 150 < half < 250  # about the rate asked for
    assert [planned_error("t", s, 0.5) for s in steps] == \
        [planned_error("t", s, 0.5) for s in steps]  # the same run, the same errors
    assert planned_error("t", "one_shot", 1.0, seed=0) in ERROR_KINDS


@pytest.mark.parametrize("kind", ERROR_KINDS)
def test_each_spoiled_one_shot_answer_is_refused(kind) -> None:
    from factask.gen.answers.schemas import AnswerError
    from factask.gen.steps import read_graph_answer
    from factask.vocabulary.errors import GraphValidationError

    graph = in_step_names(get_task("place-red-in-green"))
    schema = ss.graph_schema(graph.name)
    good = fit(reference_answer(graph, "one_shot", None), schema)
    assert read_graph_answer(json.dumps(good), schema)
    bad = spoil(good, kind)
    text = bad if isinstance(bad, str) else json.dumps(bad)
    # refused by the step's schema, or (names, a goal on itself) by the graph's check
    with pytest.raises((AnswerError, GraphValidationError)):
        parse_graph(read_graph_answer(text, schema))


def test_a_reply_is_cut_at_the_requests_max_tokens() -> None:
    graph = get_task("place-red-in-green")
    responder = ReferenceResponder({graph.name: graph})
    request = {"messages": [{"role": "user", "content":
                             f"Step: one_shot\nTask `{graph.name}`: {graph.description}"}],
               "max_tokens": 50}
    reply = responder(request)
    assert len(reply) == 150 and type(reply).__name__ == "CutReply"
    unknown = responder({"messages": [{"role": "user",
                                       "content": "Step: one_shot\nTask `nope`: x"}]})
    assert "no reference graph" in unknown


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(sorted(task_names())), st.data())
def test_empty_fields_may_be_left_out_but_nothing_else(name, data) -> None:
    """A strict answer with a nullable or may-be-empty field left out is filled back to
    the same answer; with a field that has no empty value left out it still breaks
    the schema."""
    graph = in_step_names(get_task(name))
    schema = ss.variables_answer(64)
    answer = fit(reference_answer(graph, "variables", None), schema)
    assert not [p for p in ss.schema_problems(answer, schema) if "maxItems" not in p]
    i = data.draw(st.integers(0, len(answer["variables"]) - 1))
    field = data.draw(st.sampled_from(["size", "fixed", "kind", "name", "count"]))
    cut = json.loads(json.dumps(answer))
    del cut["variables"][i][field]
    filled = ss.with_empty_fields(cut, schema)
    if field in ("size", "fixed"):
        assert filled["variables"][i][field] is None
        assert not [p for p in ss.schema_problems(filled, schema) if "maxItems" not in p]
    else:
        assert field not in filled["variables"][i]
        assert any(f"'{field}' is a required property" in p
                   for p in ss.schema_problems(filled, schema))


@pytest.mark.parametrize("approach", ["variables-first", "subtasks-first"])
def test_a_valid_goal_beyond_the_step_grammar_is_taken_on_the_remote_path(approach) -> None:
    """A row between two bowls (``along`` a list of two): the per-subtask grammar
    names one anchor, the relation takes two; a capable model's valid goal is taken,
    not refused for the grammar's sake."""
    from pathlib import Path

    from factask.evaluation.benchmark import load_tasks, reference_graph

    tasks = load_tasks(Path(__file__).parent / "data" / "proposals.json")
    task = next(t for t in tasks if t.name == "block-between-red-bowl-and-blue-bowl")
    reference = reference_graph(task)
    assert any(isinstance(f.goal.model_dump().get("along"), list) for f in reference.factors)
    with open_client(LLMConfig(model=REFERENCE_MODEL, num_retries=0, timeout=30),
                     references={task.name: reference}) as client:
        result = Generator(client, Verifier(episodes=1), max_repairs=1).generate(
            task.proposal, approach)
    assert result.graph is not None, result.failure
    assert compare(result.graph, reference).equivalent
