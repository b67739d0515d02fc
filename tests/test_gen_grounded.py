"""Step schemas grounded in the objects a proposal names (factask.gen.reading.grounded)."""

from __future__ import annotations

import json
import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.gen.answers.step_schemas import schema_problems
from factask.gen.first_choice import first_choice
from factask.gen.reading import grounded
from factask.gen.reading.mentions import mentions
from factask.graph.taskgraph import TaskGraph
from factask.vocabulary.palette import COLOR_NAMES

PROPOSAL = "put the yellow cylinder in the blue zone"


def _var(name: str, kind: str, color: str, count: int = 1,
         initial: dict | None = None) -> dict:
    return {"name": name, "description": "an object", "kind": kind, "size": None,
            "color": color, "count": count, "initial": initial or {"type": "table"}}


GOOD = {
    "name": "t", "description": "the task",
    "variables": [_var("yellow_cylinder", "cylinder", "yellow"),
                  _var("blue_zone", "zone", "blue")],
    "factors": [{"name": "place", "description": "d", "initial_setup": "",
                 "goal": {"type": "in_zone", "objects": ["yellow_cylinder"],
                          "zone": "blue_zone"},
                 "weight": 1.0, "after": [], "milestone": False}],
}


def test_a_graph_over_exactly_the_named_objects_validates_and_builds() -> None:
    schema = grounded.graph_schema("t", mentions(PROPOSAL))
    assert schema_problems(GOOD, schema) == []
    TaskGraph.model_validate(GOOD).ensure_valid()


@pytest.mark.parametrize("change", [
    lambda g: g["variables"][0].update(color="blue"),          # another object
    lambda g: g["variables"].pop(),                            # one missing
    lambda g: g["variables"].append(_var("red_block", "block", "red")),  # one added
    lambda g: g["variables"][0].update(size=[0.1, 0.1, 0.1]),  # size: the kind's default
    lambda g: g["factors"][0]["goal"].update(zone="yellow_cylinder"),  # not a region
    lambda g: g["factors"].append(dict(g["factors"][0], name="again")),  # 1 movable: 1 factor
    lambda g: g["factors"][0].update(after=["place"]),          # one factor: no order
])
def test_the_grounded_graph_schema_refuses(change) -> None:
    data = json.loads(json.dumps(GOOD))
    change(data)
    assert schema_problems(data, grounded.graph_schema("t", mentions(PROPOSAL)))


def test_variables_may_add_at_most_max_extra_objects() -> None:
    schema = grounded.variables_answer(mentions(PROPOSAL))
    base = [_var("yellow_cylinder", "cylinder", "yellow"), _var("blue_zone", "zone", "blue")]
    extra = _var("green_bowl", "bowl", "green")
    for k in range(grounded.MAX_EXTRA + 1):
        assert schema_problems({"variables": base + [extra] * k}, schema) == []
    assert schema_problems({"variables": base + [extra] * (grounded.MAX_EXTRA + 1)}, schema)
    assert schema_problems({"variables": base[::-1]}, schema)  # named objects first, in order


def test_initial_placement_only_on_a_kind_that_can_carry_it() -> None:
    found = mentions("put the red block on the blue pallet")
    schema = grounded.variables_answer(found, extra=0)
    on_pallet = _var("red_block", "block", "red", initial={"type": "on", "support": "blue_pallet"})
    pallet = _var("blue_pallet", "pallet", "blue")
    assert schema_problems({"variables": [on_pallet, pallet]}, schema) == []
    on_itself = dict(pallet, initial={"type": "on", "support": "blue_pallet"})
    assert schema_problems({"variables": [_var("red_block", "block", "red"), on_itself]},
                           schema)


def test_grounding_needs_a_movable_named_object() -> None:
    assert not grounded.applies(mentions("the green zone"))
    assert not grounded.applies(mentions("build something nice"))
    assert grounded.applies(mentions("place three blocks in a row"))


def test_grounding_needs_a_goal_over_the_named_objects() -> None:
    # One block and nothing to anchor it on: no relation fits (as the GenSim task
    # block-insertion was read before an L shape block was an ell and a hole a
    # fixture); its empty goal took llama.cpp's server down.
    found = mentions("block-lifting: lift the block high above the table")
    assert [m.name for m in found] == ["block"] and not grounded.applies(found)
    with pytest.raises(ValueError):
        grounded.compact_graph_schema(found)
    from factask.vocabulary.variables import StateVariable

    lone = grounded.goal_answer([StateVariable(name="block", kind="block")], "in the hole")
    assert lone["properties"]["goal"].get("anyOf")  # the ungrounded goal (coordinates)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(sorted(COLOR_NAMES)),
                          st.sampled_from(["block", "cylinder", "ball", "zone", "bowl"])),
                min_size=1, max_size=4))
def test_grounded_schemas_turn_into_a_llama_cpp_grammar(pairs) -> None:
    llama_grammar = pytest.importorskip("llama_cpp.llama_grammar")
    proposal = " and ".join(f"the {c} {k}" for c, k in pairs)
    found = mentions(proposal)
    from factask.gen.answers.step_schemas import empty_choices
    from factask.vocabulary.variables import StateVariable

    goal = grounded.goal_answer([StateVariable(name=m.name, kind=m.kind, count=m.count)
                                 for m in found], proposal)
    # Nothing movable: no goal is possible, and the step makes no call (see below).
    assert bool(empty_choices(goal)) == (not grounded.movable(found))
    schemas = [grounded.variables_answer(found)] + ([goal] if grounded.movable(found) else [])
    if grounded.applies(found):
        schemas += [grounded.compact_graph_schema(found, proposal),
                    grounded.graph_schema("t", found)]
    for schema in schemas:
        gbnf = llama_grammar.json_schema_to_gbnf(json.dumps(schema))
        assert "root" in gbnf
        # A rule with nothing on its right side: llama.cpp's parser rejects it.
        assert not re.search(r"::=[ \t]*$", gbnf, re.MULTILINE), gbnf


COMPACT = {"variables": [{"name": "yellow_cylinder", "initial": {"type": "table"}}],
           "factors": [{"goal": {"type": "in_zone",
                                                  "objects": ["yellow_cylinder"],
                                                  "zone": "blue_zone"}}]}


def test_a_compact_answer_expands_into_a_valid_graph_of_the_named_objects() -> None:
    found = mentions(PROPOSAL)
    assert schema_problems(COMPACT, grounded.compact_graph_schema(found)) == []
    data = grounded.expand_graph(COMPACT, found, "t", PROPOSAL)
    graph = TaskGraph.model_validate(data).ensure_valid()
    assert {(v.name, v.kind, v.color) for v in graph.variables} == {
        ("yellow_cylinder", "cylinder", "yellow"), ("blue_zone", "zone", "blue")}
    assert graph.factors[0].weight == 1.0


@pytest.mark.parametrize("goal", [
    {"type": "on", "objects": ["yellow_cylinder"], "support": "yellow_cylinder"},  # on itself
    {"type": "in_zone", "objects": ["blue_zone"], "zone": "blue_zone"},            # fixed kind
    {"type": "at_pose", "objects": ["yellow_cylinder"], "poses": [], "frame": None,
     "check_yaw": False},                                                          # coordinates
    {"type": "pile_in_zone", "objects": ["yellow_cylinder"], "zone": "blue_zone",
     "fraction": 0.5},                                                             # not a pile
])
def test_the_compact_schema_refuses_goals_that_cannot_be_meant(goal) -> None:
    data = json.loads(json.dumps(COMPACT))
    data["factors"][0]["goal"] = goal
    assert schema_problems(data, grounded.compact_graph_schema(mentions(PROPOSAL)))


def test_a_cylinder_lined_up_with_a_holed_box_takes_mode_hole_only() -> None:
    proposal = ("three cylinders (red, blue and green) and three boxes of the same colours. "
                "The boxes have a small hole on one of their sides. Align each cylinder "
                "with the hole in the box of its colour.")
    found = mentions(proposal)
    schema = grounded.compact_graph_schema(found, proposal)
    answer = {"variables": [{"name": f"{c}_cylinder", "initial": {"type": "table"}}
                            for c in ("red", "blue", "green")],
              "factors": [{"goal": {"type": "aligned", "objects": [f"{c}_cylinder"],
                                    "reference": f"{c}_holed_box", "mode": "hole"}}
                          for c in ("red", "blue", "green")]}
    assert schema_problems(answer, schema) == []
    centred = json.loads(json.dumps(answer))
    centred["factors"][0]["goal"]["mode"] = "center"  # on top of the box: no meaning
    assert schema_problems(centred, schema)
    graph = TaskGraph.model_validate(
        grounded.expand_graph(answer, found, "t", proposal)).ensure_valid()
    assert {v.kind for v in graph.variables} == {"cylinder", "holed_box"}
    # A fixture is still aligned by centre or corner, never by a hole.
    fixture = "insert the red ell into the green fixture"
    modes = re.findall(r'"mode": \{[^}]*\}', json.dumps(
        grounded.compact_graph_schema(mentions(fixture), fixture)))
    assert modes and all('"hole"' not in m for m in modes)


def test_a_fixed_object_starts_on_the_table() -> None:
    data = json.loads(json.dumps(COMPACT))  # a fixed object is no decision: not written
    data["variables"].append({"name": "blue_zone", "initial": {"type": "table"}})
    assert schema_problems(data, grounded.compact_graph_schema(mentions(PROPOSAL)))


def test_later_factors_moving_the_same_object_go_after_the_earlier_ones() -> None:
    found = mentions("put the red block in the green zone, then on the blue block")
    answer = {"variables": [{"name": m.name, "initial": {"type": "table"}} for m in found
                            if m.movable],
              "factors": [{"goal": {"type": "in_zone", "objects": ["red_block"],
                                    "zone": "green_zone"}},
                          {"goal": {"type": "on", "objects": ["red_block"],
                                    "support": "blue_block"}}]}
    assert schema_problems(answer, grounded.compact_graph_schema(found)) == []
    graph = TaskGraph.model_validate(grounded.expand_graph(answer, found, "t", "x"))
    graph.ensure_valid()
    first, second = graph.factors
    assert (first.name, second.name) == ("in_zone_red_block", "on_red_block")
    assert second.after == [first.name] and first.milestone


def test_compact_examples_are_library_tasks_written_as_compact_answers() -> None:
    text = grounded.compact_examples("cylinder zone", 1)
    payload = json.loads(text.split("```json\n", 1)[1].split("\n```", 1)[0])
    assert set(payload) == {"variables", "factors"}
    assert all(set(v) == {"name", "initial"} for v in payload["variables"])


def test_one_shot_grounded_through_the_pipeline_reaches_completion() -> None:
    from factask.gen import Generator, LLMClient, LLMConfig, Verifier
    from factask.gen.loopback import LoopbackServer, ScriptedResponder

    responder = ScriptedResponder({"one_shot": [json.dumps(COMPACT)]})
    with LoopbackServer(responder) as server:
        client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                     num_retries=0, timeout=30))
        result = Generator(client, Verifier(episodes=1), max_repairs=0,
                           grounded=True).generate(PROPOSAL, "one-shot")
    assert result.level_reached == "completion", result.failure
    assert result.graph is not None and result.graph.factors[0].name == "in_zone_yellow_cylinder"
    assert "one_shot_grounded" not in json.dumps(result.to_dict())  # the step keeps its name
    assert result.steps[0].step == "one_shot"


def goal_branches(schema: dict) -> list[dict]:
    """Every goal branch a compact schema's ``factors`` allows (in any shape)."""
    factors = schema["properties"]["factors"]
    items = [i for shape in factors.get("anyOf", [factors])
             for i in shape.get("prefixItems", [shape.get("items")])]
    goals = [i["properties"]["goal"] for i in items]
    return [b for g in goals for b in g.get("anyOf", [g])]


@pytest.mark.parametrize(("proposal", "relations"), [
    ("put the yellow cylinder in the blue zone", {"in_zone"}),
    ("place three blocks in a row", {"row"}),
    # The words state this goal (factask.gen.reading.clauses): a stack on the green block.
    ("stack the red block on the green block", {"stack"}),
    ("put the red ball into the green bowl", {"inside"}),
])
def test_the_relations_the_proposal_names_are_the_goals_allowed(proposal, relations) -> None:
    assert grounded.named_relations(proposal) >= relations
    types = {b["properties"]["type"]["const"] for b in goal_branches(
        grounded.compact_graph_schema(mentions(proposal), proposal))}
    assert types == relations


def test_no_named_relation_leaves_every_relation_that_fits() -> None:
    proposal = "move the yellow cylinder near the gold stand"
    assert grounded.named_relations(proposal) == set()
    types = {b["properties"]["type"]["const"] for b in goal_branches(
        grounded.compact_graph_schema(mentions(proposal), proposal))}
    assert len(types) > 1 and not types & {"row", "circle"}  # a row of one object: no task


def test_goal_problems_name_an_unused_object_and_a_trivial_group() -> None:
    found = mentions("stack the red block on the green block")
    lone = [{"type": "stack", "objects": ["red_block"], "base": None, "ordered": True}]
    problems = grounded.goal_problems(lone, found)
    assert any("stack of 1 object" in p for p in problems)
    assert any("green_block" in p for p in problems)
    good = [{"type": "on", "objects": ["red_block"], "support": "green_block"}]
    assert grounded.goal_problems(good, found) == []


@pytest.mark.parametrize("proposal", [
    "Place the white block between the two grey zones.",
    "Build a pyramid on the table: the three green blocks at the bottom, the two red "
    "blocks in the middle and the blue block on top.",
])
def test_the_check_takes_every_goal_the_stated_grammar_admits(proposal: str) -> None:
    # a row of one between a pair, or on the layer below: the grammar admits it, and
    # the one-shot check must too (it refused them: no graph at all)
    found = mentions(proposal)
    schema = grounded.compact_graph_schema(found, proposal)
    answer = first_choice(schema)
    goals = [f["goal"] for f in answer["factors"]]
    assert any(g["type"] == "row" and len(g["objects"]) == 1 for g in goals)
    assert grounded.goal_problems(goals, found) == []


def test_an_object_is_never_its_own_anchor() -> None:
    proposal = "stack the red block on the green block"
    schema = grounded.compact_graph_schema(mentions(proposal), proposal, stated=False)
    answer = {"variables": [{"name": n, "initial": {"type": "table"}}
                            for n in ("red_block", "green_block")],
              "factors": [{"goal": {"type": "on", "objects": ["red_block"],
                                    "support": "red_block"}}]}
    assert schema_problems(answer, schema)
    answer["factors"][0]["goal"]["support"] = "green_block"
    assert schema_problems(answer, schema) == []


def test_a_warm_request_to_llama_cpp_samples_from_every_grammar_valid_token() -> None:
    from factask.gen import LLMClient, LLMConfig
    from factask.gen.loopback import LoopbackServer, ScriptedResponder

    msgs = [{"role": "user", "content": "Step: one_shot\nhi"}]
    with LoopbackServer(ScriptedResponder({"one_shot": ["{}"]})) as server:
        client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                     num_retries=0, timeout=30, response_format="llama_cpp"))
        client.complete(msgs, schema={"type": "object"}, temperature=0.0)
        client.complete(msgs, schema={"type": "object"}, temperature=0.7)
        cold, warm = server.requests
    assert "min_p" not in cold and cold.get("top_p") in (None, 1.0)
    assert warm["top_p"] == 1.0 and warm["min_p"] == 0.0 and warm["top_k"] == 0


def test_a_grounded_subtask_goal_follows_the_words_and_has_no_coordinates() -> None:
    from factask.vocabulary.variables import StateVariable

    planned = [StateVariable(name="yellow_cylinder", kind="cylinder", color="yellow"),
               StateVariable(name="blue_zone", kind="zone", color="blue")]
    schema = grounded.goal_answer(planned, f"{PROPOSAL} move it into the zone")
    good = {"goal": {"type": "in_zone", "objects": ["yellow_cylinder"], "zone": "blue_zone"},
            "description": "d"}
    assert schema_problems(good, schema) == []
    posed = {"goal": {"type": "at_pose", "objects": ["yellow_cylinder"],
                      "poses": [{"x": 0.5, "y": 0.0, "z": None, "yaw_deg": 0}],
                      "frame": None, "check_yaw": False}, "description": "d"}
    assert schema_problems(posed, schema)


def test_a_step_whose_schema_admits_no_answer_makes_no_call() -> None:
    from factask.gen.answers import step_schemas as ss
    from factask.gen.answers.schemas import SubtaskPlan
    from factask.gen.fragments import plan_problems
    from factask.gen.steps import StepRunner
    from factask.vocabulary.variables import StateVariable

    only_a_zone = ss.goal_answer({"green_zone": "zone"})
    assert ss.empty_choices(only_a_zone) == ["$.properties.goal.anyOf"]
    assert ss.empty_choices(ss.goal_answer({"b": "block", "z": "zone"})) == []

    class NoCalls:
        def complete(self, *args, **kwargs):
            raise AssertionError("a schema with no possible answer was sent")

    runner = StepRunner(NoCalls(), max_repairs=2)  # type: ignore[arg-type]
    from factask.gen.results import GenerationResult

    runner._result = GenerationResult(approach="variables-first", proposal="p", task="t")
    out = runner.ask("subtask_goal:s", lambda lv: "p", only_a_zone, "goal_answer",
                     lambda text: (None, "none", "unused"))
    assert not out.ok and out.value is None and "nothing to choose" in out.feedback
    assert [r.step for r in runner._result.steps] == ["subtask_goal:s"]
    # The plan that would lead there is fed back instead.
    variables = [StateVariable(name="red_block", kind="block"),
                 StateVariable(name="green_zone", kind="zone")]
    plan = SubtaskPlan.model_validate({"subtasks": [
        {"name": "mark", "description": "d", "variables": ["green_zone"], "initial_setup": ""},
        {"name": "place", "description": "d", "variables": ["red_block", "green_zone"],
         "initial_setup": ""}]})
    assert [(p.node, p.field) for p in plan_problems(plan, variables)] == [("mark", "variables")]


def test_a_bowl_the_words_move_is_carried_and_one_they_do_not_stays_fixed() -> None:
    proposal = ("pick up the pink ball and drop it into the yellow bowl, then put the bowl "
                "in the green zone")
    found = mentions(proposal)
    assert [(m.name, m.moved) for m in found] == [
        ("pink_ball", False), ("yellow_bowl", True), ("green_zone", False)]
    assert [m.moved for m in mentions("put the red ball in the yellow bowl")] == [False, False]
    schema = grounded.compact_graph_schema(found, proposal)
    answer = {"variables": [{"name": m.name, "initial": {"type": "table"}} for m in found
                            if m.movable],
              "factors": [{"goal": {"type": "inside", "objects": ["pink_ball"],
                                    "container": "yellow_bowl"}},
                          {"goal": {"type": "in_zone", "objects": ["yellow_bowl"],
                                    "zone": "green_zone"}}]}
    assert schema_problems(answer, schema) == []
    graph = TaskGraph.model_validate(grounded.expand_graph(answer, found, "t", proposal))
    graph.ensure_valid()
    assert not graph.variable("yellow_bowl").is_fixed
    # Where the words do not move it, a bowl is never a goal's object.
    still = mentions("drop the pink ball into the yellow bowl in the green zone")
    answer["factors"][1]["goal"]["objects"] = ["yellow_bowl"]
    assert schema_problems(answer, grounded.compact_graph_schema(still, "drop ... zone"))


def test_capacity_pruning_skips_a_goal_the_whole_graph_check_refuses() -> None:
    """A rope_along with neither `along` nor `start`/`end` is no goal: the layout
    check must leave it (the syntax level's to report), not run its solver into an
    assertion. Found with the proposal below (it raised AssertionError before)."""
    proposal = "Lay the rope along the line on the table from one end to the other."
    schema = grounded.compact_graph_schema(mentions(proposal), proposal)
    assert schema is not None
    goals = schema["properties"]["factors"]["prefixItems"][0]["properties"]["goal"]["anyOf"]
    alongs = [g["properties"]["along"] for g in goals
              if g["properties"]["type"] == {"const": "rope_along"}]
    assert {"const": "line"} in alongs
