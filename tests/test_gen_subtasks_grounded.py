"""Subtasks-first grounded in the objects the proposal names (factask.gen.grounded_subtasks)."""

from __future__ import annotations

import json
import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_gen_cover import proposals, sample

from factask.gen import grounded_subtasks as gs
from factask.gen.answers.schemas import AnswerError
from factask.gen.answers.step_schemas import schema_problems
from factask.gen.reading import cover, grounded
from factask.gen.reading.mentions import mentions
from factask.vocabulary.palette import COLOR_NAMES

PROPOSAL = "put the yellow cylinder and the red block in the blue zone"
#: The same objects where the words state no goal ("using" is no relation): the
#: steps are the object outline's (where they state every goal the outline is the
#: reading.s: test_gen_grounded_steps.py).
UNSTATED = "tidy up the yellow cylinder and the red block using the blue zone"
FOUR = "put the red block, the green block, the blue block and the yellow block on the pallet"


def _item(obj: str, text: str = "it is placed") -> dict:
    return {"object": obj, "description": text}


def _design(goal: dict, text: str = "done") -> str:
    return json.dumps({"goal": goal, "description": text})


IN_ZONE = {"type": "in_zone", "zone": "blue_zone"}


def test_the_outline_has_each_movable_object_at_most_once_by_construction() -> None:
    found = mentions(PROPOSAL)
    assert gs.movers(found) == ["yellow_cylinder", "red_block"]  # the zone stays put
    schema = gs.outline_schema(found)
    for objects in (["yellow_cylinder", "red_block"], ["red_block", "yellow_cylinder"],
                    ["red_block"], ["yellow_cylinder"]):
        assert schema_problems({"subtasks": [_item(o) for o in objects]}, schema) == []
    for objects in (["red_block", "red_block"], ["blue_zone"], [], ["green_ball"],
                    ["red_block", "yellow_cylinder", "red_block"]):
        assert schema_problems({"subtasks": [_item(o) for o in objects]}, schema), objects
    # Every branch is a tuple of constants, no object twice.
    for branch in schema["properties"]["subtasks"]["anyOf"]:
        objects = [i["properties"]["object"]["const"] for i in branch["prefixItems"]]
        assert len(objects) == len(set(objects)) and branch["items"] is False
    # Bounded text: an answer cannot run to the token cap.
    assert branch["prefixItems"][0]["properties"]["description"]["maxLength"] <= 60


def test_many_movable_objects_get_a_bounded_enum_and_a_repeat_is_refused() -> None:
    found = mentions(FOUR)
    names = gs.movers(found)
    assert len(names) == 4
    subtasks = gs.outline_schema(found)["properties"]["subtasks"]
    assert subtasks["maxItems"] == 4 and subtasks["items"]["properties"]["object"]["enum"] == names
    with pytest.raises(AnswerError, match="more than once"):
        gs.read_outline({"subtasks": [_item(names[0]), _item(names[0])]}, found)


@settings(max_examples=80, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["red_block", "green_block", "blue_block",
                                           "yellow_block", "pallet", "ball"]),
                          st.text(max_size=20)), max_size=6))
def test_read_outline_names_subtasks_after_distinct_objects_or_refuses(items) -> None:
    found = mentions(FOUR)
    allowed = gs.movers(found)
    data = {"subtasks": [_item(o, t) for o, t in items]}
    objects = [o for o, _ in items]
    if objects and all(o in allowed for o in objects) and len(set(objects)) == len(objects):
        outline = gs.read_outline(data, found)
        names = [s.name for s in outline.subtasks]
        assert names == [gs.subtask_name(o) for o in objects]
        assert len(set(names)) == len(names)
        assert gs.outline_objects(outline, found) == dict(zip(names, objects, strict=True))
    else:
        with pytest.raises(AnswerError):
            gs.read_outline(data, found)


def test_the_design_has_the_named_objects_as_constants_and_its_object_first() -> None:
    found = mentions(PROPOSAL)
    variables = gs.named_variables(found)
    assert [(v.name, v.kind, v.color) for v in variables] == [
        ("yellow_cylinder", "cylinder", "yellow"), ("red_block", "block", "red"),
        ("blue_zone", "zone", "blue")]
    schema = gs.design_schema(variables, "red_block", PROPOSAL)
    assert set(schema["properties"]) == {"goal", "description"}  # no variables to re-declare
    goal = schema["properties"]["goal"]
    assert goal["properties"]["type"] == {"const": "in_zone"}  # the only relation named
    assert goal["properties"]["objects"]["items"]["enum"] == ["red_block", "yellow_cylinder"]
    good = {**IN_ZONE, "objects": ["red_block", "yellow_cylinder"]}
    assert schema_problems(json.loads(_design(good)), schema) == []
    for wrong in ({**IN_ZONE, "objects": ["blue_zone"]},            # a zone is not moved
                  {**IN_ZONE, "objects": ["green_block"]},          # not a named object
                  {"type": "on", "objects": ["red_block"], "support": "yellow_cylinder"},
                  {**IN_ZONE, "objects": ["red_block"], "zone": "red_zone"}):
        assert schema_problems(json.loads(_design(wrong)), schema), wrong


def test_a_design_must_use_its_subtask_object() -> None:
    found = mentions(PROPOSAL)
    assert gs.design_problems({**IN_ZONE, "objects": ["red_block"]}, "red_block", found) == []
    problems = gs.design_problems({**IN_ZONE, "objects": ["yellow_cylinder"]}, "red_block",
                                  found)
    assert len(problems) == 1 and "red_block" in problems[0]


def _run(script: dict, proposal: str = PROPOSAL):
    from factask.gen import Generator, LLMClient, LLMConfig, Verifier, grounded_steps
    from factask.gen.loopback import LoopbackServer, ScriptedResponder

    # The object outline is the fallback where the grounded one-shot grammar's goals
    # are a plain array (no shape fits the named objects: many of them, or large
    # ones); here it is forced on a small proposal, whose grammar has shapes
    # (those steps: test_gen_grounded_steps.py).
    with pytest.MonkeyPatch.context() as patch, \
            LoopbackServer(ScriptedResponder(script)) as server:
        patch.setattr(grounded_steps, "grounded_task", lambda found, proposal: None)
        client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                     num_retries=0, timeout=30))
        return Generator(client, Verifier(episodes=1), max_repairs=0,
                         grounded=True).generate(proposal, "subtasks-first")


GOOD = {
    "subtask_outline": [json.dumps({"subtasks": [_item("yellow_cylinder"),
                                                 _item("red_block")]})],
    "subtask_design:place_yellow_cylinder": [_design({**IN_ZONE,
                                                      "objects": ["yellow_cylinder"]})],
    "subtask_design:place_red_block": [_design({**IN_ZONE, "objects": ["red_block"]})],
}


def test_grounded_subtasks_first_through_the_pipeline_reaches_completion() -> None:
    result = _run(GOOD)
    assert result.level_reached == "completion", result.failure
    assert [s.step for s in result.steps] == [
        "subtask_outline", "subtask_design:place_yellow_cylinder",
        "subtask_design:place_red_block", "assembly"]
    graph = result.graph
    assert graph is not None
    assert [f.name for f in graph.factors] == ["place_yellow_cylinder", "place_red_block"]
    assert {(v.name, v.kind, v.color) for v in graph.variables} == {
        ("yellow_cylinder", "cylinder", "yellow"), ("red_block", "block", "red"),
        ("blue_zone", "zone", "blue")}


def test_an_outline_naming_an_object_twice_is_refused() -> None:
    script = dict(GOOD, subtask_outline=[json.dumps(
        {"subtasks": [_item("red_block"), _item("red_block")]})])
    result = _run(script)
    assert result.level_reached == "none"
    assert result.failure.startswith("subtask_outline")
    assert not result.steps[0].ok and len(result.steps) == 1


def test_a_design_whose_goal_leaves_out_its_object_is_refused() -> None:
    script = dict(GOOD, **{"subtask_design:place_red_block": [
        _design({**IN_ZONE, "objects": ["yellow_cylinder"]})]})
    result = _run(script)
    assert result.level_reached == "none"
    assert "place_red_block" in result.failure and "red_block" in result.steps[-1].feedback


def test_the_last_design_must_use_every_named_object_left() -> None:
    # One subtask for two movable objects and a zone: its goal must use all three.
    lone = {"type": "in_zone", "objects": ["yellow_cylinder"], "zone": "blue_zone"}
    script = {"subtask_outline": [json.dumps({"subtasks": [_item("yellow_cylinder")]})],
              "subtask_design:place_yellow_cylinder": [_design(lone)]}
    result = _run(script)
    assert result.level_reached == "none"  # refused by the design's schema
    assert result.steps[-1].step == "subtask_design:place_yellow_cylinder"
    both = {**lone, "objects": ["yellow_cylinder", "red_block"]}
    result = _run(dict(script, **{"subtask_design:place_yellow_cylinder": [_design(both)]}))
    assert result.level_reached == "completion", result.failure


def test_designs_leave_the_later_subtasks_able_to_use_every_named_object() -> None:
    proposal = "put the red block in the red bowl and the blue block in the blue bowl"
    found = mentions(proposal)
    variables = gs.named_variables(found)
    names = [m.name for m in found]

    def inside(obj: str, bowl: str) -> str:
        return _design({"type": "inside", "objects": [obj], "container": bowl})

    # Two subtasks, two bowls: no slack, so each design must take a bowl of its own.
    first = gs.design_schema(variables, "red_block", proposal,
                             [n for n in names if n != "blue_block"], 2)
    assert schema_problems(json.loads(inside("red_block", "red_bowl")), first) == []
    second = gs.design_schema(variables, "blue_block", proposal, ["blue_bowl"], 1)
    assert schema_problems(json.loads(inside("blue_block", "red_bowl")), second)
    assert schema_problems(json.loads(inside("blue_block", "blue_bowl")), second) == []
    # With slack (nothing left to use) the design is the plain one.
    assert gs.design_schema(variables, "blue_block", proposal, [], 1) == \
        gs.design_schema(variables, "blue_block", proposal, narrow=False)


def test_a_named_object_no_goal_uses_fails_the_assembly() -> None:
    from factask.graph.taskgraph import TaskGraph

    found = mentions(PROPOSAL)
    graph = TaskGraph.model_validate({
        "name": "t", "description": "d",
        "variables": [v.model_dump(mode="json") for v in gs.named_variables(found)],
        "factors": [{"name": "place_yellow_cylinder", "description": "d",
                     "goal": {**IN_ZONE, "objects": ["yellow_cylinder"]}}]})
    problem = gs.assembly_problem(graph, found)
    assert problem is not None and "red_block" in problem


def test_a_proposal_naming_nothing_movable_takes_the_ungrounded_path() -> None:
    result = _run({"subtask_outline": ['{"subtasks": []}']}, "build something nice")
    assert result.failure.startswith("subtask_outline")
    assert "object" not in (result.steps[0].feedback or "")


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(sorted(COLOR_NAMES)),
                          st.sampled_from(["block", "cylinder", "ball", "zone", "bowl"])),
                min_size=1, max_size=5))
def test_grounded_subtask_schemas_turn_into_a_llama_cpp_grammar(pairs) -> None:
    llama_grammar = pytest.importorskip("llama_cpp.llama_grammar")
    from factask.gen.reading import grounded

    proposal = " and ".join(f"the {c} {k}" for c, k in pairs) + " in a row"
    found = mentions(proposal)
    if not grounded.applies(found):
        return
    variables = gs.named_variables(found)
    schemas = [gs.outline_schema(found)] + [gs.design_schema(variables, o, proposal)
                                            for o in gs.movers(found)]
    for schema in schemas:
        gbnf = llama_grammar.json_schema_to_gbnf(json.dumps(schema))
        assert "root" in gbnf
        assert not re.search(r"::=[ \t]*$", gbnf, re.MULTILINE), gbnf


@settings(max_examples=100, deadline=None)
@given(proposals, st.data())
def test_designs_drawn_one_by_one_from_narrowed_schemas_use_every_named_object(
        proposal, data) -> None:
    found = mentions(proposal)
    if not grounded.applies(found):
        return
    variables = gs.named_variables(found)
    names = [m.name for m in found]
    outline = data.draw(st.permutations(gs.movers(found)))
    used: set[str] = set()
    slack = True
    for i, obj in enumerate(outline):
        unused = [n for n in names if n not in used and n not in outline[i + 1:]]
        remaining = len(outline) - i
        slack = slack and len([u for u in unused if u != obj]) <= remaining
        schema = gs.design_schema(variables, obj, proposal, unused, remaining)
        plain = gs.design_schema(variables, obj, proposal, narrow=False)
        if schema == plain and len([u for u in unused if u != obj]) >= remaining:
            return  # no branch can use what is left: the assembly check reports it
        goal = sample(schema["properties"]["goal"], data)
        assert schema_problems({"goal": goal, "description": "d"}, schema) == []
        if schema != plain:
            assert obj in cover.used_names(goal, names)
        used |= cover.used_names(goal, names) | {obj}
    if slack:
        assert used == set(names), (proposal, outline, used)
