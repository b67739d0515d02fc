"""Variables-first and subtasks-first in the grounded one-shot grammar's pieces
(factask.gen.grounded_steps; issue 34, part 4: the factorized approaches mean the
proposal where one-shot does)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from factask.gen import Generator, LLMClient, LLMConfig, Verifier
from factask.gen.answers.step_schemas import schema_problems
from factask.gen.compare import compare
from factask.gen.first_choice import FirstChoiceResponder
from factask.gen.grounded_steps import grounded_task
from factask.gen.loopback import LoopbackServer, ScriptedResponder
from factask.gen.reading import grounded
from factask.gen.reading.clauses import read_goals
from factask.gen.reading.mentions import mentions

PROPOSAL = "put the red block in the green bowl, then put the blue block on the red block"
INSIDE = {"type": "inside", "objects": ["red_block"], "container": "green_bowl"}
ON = {"type": "on", "objects": ["blue_block"], "support": "red_block"}
SET = Path(__file__).parent / "data" / "proposals.json"


class _SyntaxOnly(Verifier):
    """The ladder up to syntax: what the steps ask, without physics."""

    def check(self, graph, target="completion"):  # type: ignore[override]
        return super().check(graph, "syntax")


def _generate(responder, proposal: str, approach: str, verifier: Verifier | None = None):
    with LoopbackServer(responder) as server:
        client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                     num_retries=0, timeout=30,
                                     response_format="json_schema"))
        return Generator(client, verifier or Verifier(episodes=1), max_repairs=0,
                         grounded=True).generate(proposal, approach)


def test_the_stated_reading_is_one_shape_of_one_subtask_per_stated_goal() -> None:
    shaped = grounded_task(mentions(PROPOSAL), PROPOSAL)
    assert shaped is not None and shaped.stated and len(shaped.shapes) == 1
    shape = shaped.shapes[0]
    assert shape.names == ("inside_red_block", "on_blue_block")
    assert shape.objects == (("red_block", "green_bowl"), ("blue_block", "red_block"))
    goal = {"type": "object", "properties": {"goal": shape.goal_schemas[0]}}
    assert schema_problems({"goal": INSIDE}, goal) == []
    # Another relation, object or anchor than the words state is outside the grammar.
    for wrong in ({**INSIDE, "container": "red_block"}, {**INSIDE, "objects": ["blue_block"]},
                  {"type": "in_zone", "objects": ["red_block"], "zone": "green_bowl"}):
        assert schema_problems({"goal": wrong}, goal), wrong


def test_no_grounded_task_where_the_proposal_names_nothing_movable() -> None:
    assert grounded_task(mentions("build something nice"), "build something nice") is None


VARIABLES_FIRST = {
    "variables": [json.dumps({"variables": [
        {"name": "red_block", "initial": {"type": "table"}},
        {"name": "blue_block", "initial": {"type": "table"}}]})],
    "subtask_plan": [json.dumps({"subtasks": [
        {"name": "inside_red_block", "description": "the red block is in the green bowl",
         "variables": ["red_block", "green_bowl"]},
        {"name": "on_blue_block", "description": "the blue block is on the red block",
         "variables": ["blue_block", "red_block"]}]})],
    "subtask_goal:inside_red_block": [json.dumps({"goal": INSIDE, "description": "in"})],
    "subtask_goal:on_blue_block": [json.dumps({"goal": ON, "description": "on top"})],
}


def test_variables_first_asks_starts_plan_and_goals_and_keeps_the_words_steps() -> None:
    result = _generate(ScriptedResponder(VARIABLES_FIRST), PROPOSAL, "variables-first")
    assert result.level_reached == "completion", result.failure
    assert [s.step for s in result.steps] == [
        "variables", "subtask_plan", "subtask_goal:inside_red_block",
        "subtask_goal:on_blue_block", "assembly"]
    graph = result.graph
    assert [f.name for f in graph.factors] == ["inside_red_block", "on_blue_block"]
    assert graph.factors[1].after == ["inside_red_block"]  # "then"
    assert graph.factors[0].description == "the red block is in the green bowl"
    assert {(v.name, v.kind, v.color) for v in graph.variables} == {
        ("red_block", "block", "red"), ("blue_block", "block", "blue"),
        ("green_bowl", "bowl", "green")}


def test_a_plan_that_renames_or_regroups_a_stated_subtask_is_refused() -> None:
    plan = json.loads(VARIABLES_FIRST["subtask_plan"][0])
    plan["subtasks"][0]["name"] = "push_pile_into_zone"  # a library subtask's name
    result = _generate(ScriptedResponder({**VARIABLES_FIRST,
                                          "subtask_plan": [json.dumps(plan)]}),
                       PROPOSAL, "variables-first", _SyntaxOnly())
    assert result.level_reached == "none"
    assert result.failure.startswith("subtask_plan")
    assert "inside_red_block" in result.steps[-1].feedback


def test_subtasks_first_asks_an_outline_then_each_goal() -> None:
    script = {
        "subtask_outline": [json.dumps({"subtasks": [
            {"name": "inside_red_block", "description": "red in bowl"},
            {"name": "on_blue_block", "description": "blue on red"}]})],
        "subtask_design:inside_red_block": [json.dumps({"goal": INSIDE, "description": ""})],
        "subtask_design:on_blue_block": [json.dumps({"goal": ON, "description": ""})],
    }
    result = _generate(ScriptedResponder(script), PROPOSAL, "subtasks-first", _SyntaxOnly())
    assert result.level_reached == "syntax", result.failure
    assert [s.step for s in result.steps] == [
        "subtask_outline", "subtask_design:inside_red_block",
        "subtask_design:on_blue_block", "assembly"]
    assert [f.description for f in result.graph.factors] == ["red in bowl", "blue on red"]
    assert result.graph.factors[1].after == ["inside_red_block"]


def _shaped_proposals(limit: int, stated: bool) -> list[str]:
    # Chosen by the words alone (the layout checks behind grounded_task() run against
    # a clock: xdist's workers must collect the same list).
    out = []
    for task in json.loads(SET.read_text()):
        text = task["description"]
        found = mentions(f"{text} {task['name']}")
        if grounded.applies(found) and (read_goals(text, found) is not None) == stated:
            out.append(f"{task['name']}: {text}")
        if len(out) == limit:
            break
    return out


@pytest.mark.parametrize("proposal", _shaped_proposals(5, True) + _shaped_proposals(3, False))
def test_the_reader_writes_the_same_task_with_every_approach(proposal) -> None:
    """Piece by piece, the factorized approaches ask what one-shot asks at once."""
    graphs = {a: _generate(FirstChoiceResponder(), proposal, a, _SyntaxOnly()).graph
              for a in ("one-shot", "variables-first", "subtasks-first")}
    assert graphs["one-shot"] is not None
    for approach in ("variables-first", "subtasks-first"):
        assert graphs[approach] is not None, approach
        same = compare(graphs[approach], graphs["one-shot"])
        assert same.equivalent, (approach, same.differences)


def test_without_a_reading_the_plan_chooses_among_the_grammars_shapes() -> None:
    """No goal stated ("using" is no relation): the plan picks one of the one-shot
    grammar's shapes, and the goals follow the shape the plan chose."""
    proposal = "tidy up the yellow cylinder and the red block using the blue zone"
    shaped = grounded_task(mentions(proposal), proposal)
    assert shaped is not None and not shaped.stated and len(shaped.shapes) > 1
    one = next(s for s in shaped.shapes if len(s.names) == 1)
    assert one.names == ("in_zone_yellow_cylinder",)
    # One goal for both objects: the plan that lists one subtask closes the others.
    script = {
        "variables": [json.dumps({"variables": [
            {"name": "yellow_cylinder", "initial": {"type": "table"}},
            {"name": "red_block", "initial": {"type": "table"}}]})],
        "subtask_plan": [json.dumps({"subtasks": [
            {"name": "in_zone_yellow_cylinder", "description": "both in the zone",
             "variables": list(one.objects[0])}]})],
        "subtask_goal:in_zone_yellow_cylinder": [json.dumps({"goal": {
            "type": "in_zone", "objects": ["yellow_cylinder", "red_block"],
            "zone": "blue_zone"}, "description": ""})],
    }
    result = _generate(ScriptedResponder(script), proposal, "variables-first", _SyntaxOnly())
    assert result.level_reached == "syntax", result.failure
    assert [f.goal.objects for f in result.graph.factors] == [["yellow_cylinder", "red_block"]]
