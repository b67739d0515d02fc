"""Goals whose layout fits, by construction (factask.gen.reading.capacity)."""

from __future__ import annotations

import json

from hypothesis import given, settings
from hypothesis import strategies as st
from test_gen_cover import proposals, sample, schema_of

from factask.gen.answers.step_schemas import schema_problems
from factask.gen.reading import capacity, grounded
from factask.gen.reading.mentions import Mention, mentions
from factask.vocabulary.palette import COLOR_NAMES


def goals_of(schema: dict) -> list[dict]:
    """Every goal branch (an object with a relation ``type`` const) in ``schema``."""
    props = schema.get("properties")
    if isinstance(props, dict) and "const" in props.get("type", {}):
        return [schema]
    out: list[dict] = []
    for child in [*schema.get("anyOf", []), *schema.get("prefixItems", []),
                  *([schema["items"]] if isinstance(schema.get("items"), dict) else []),
                  *([props["goal"]] if isinstance(props, dict) and "goal" in props else [])]:
        out.extend(goals_of(child))
    return out


def test_a_zone_too_small_for_the_blocks_is_not_offered() -> None:
    found = mentions("put the five blocks in the zone")
    assert [(m.name, m.count) for m in found] == [("blocks", 5), ("zone", 1)]
    problem = capacity.layout_problem({"type": "in_zone", "objects": ["blocks"],
                                       "zone": "zone"}, found)
    assert problem is not None and "do not fit" in problem
    # (The shapes the grammar offers where the words state no goal; where they do, the
    # zone is made larger instead: test_a_stated_goal_grows_its_anchor_to_fit.)
    schema = grounded.compact_graph_schema(found, "put the five blocks in the zone",
                                           stated=False)
    kinds = {g["properties"]["type"]["const"] for g in goals_of(schema["properties"]["factors"])}
    assert "in_zone" not in kinds
    few = mentions("put the four blocks in the zone")
    assert capacity.layout_problem({"type": "in_zone", "objects": ["blocks"],
                                    "zone": "zone"}, few) is None


def test_a_stack_above_the_workspace_ceiling_is_not_offered() -> None:
    # fifteen 4 cm blocks on a 3.75 cm pallet: 0.64 m, above the 0.6 m the arm allows
    found = [Mention("blocks", "block", None, 15), Mention("pallet", "pallet", None, 1)]
    goal = {"type": "stack", "objects": ["blocks"], "base": "pallet", "ordered": True}
    assert "above the workspace" in (capacity.layout_problem(goal, found) or "")
    assert capacity.layout_problem(goal, [Mention("blocks", "block", None, 3), found[1]]) is None
    schema = grounded.compact_graph_schema(found, "stack the fifteen blocks on the pallet")
    assert all(g["properties"]["type"]["const"] != "stack"
               for g in goals_of(schema["properties"]["factors"]))


def test_a_row_offers_only_the_spacings_that_fit_its_line() -> None:
    found = [Mention("blocks", "block", None, 4), Mention("line", "line", None, 1)]
    schema = grounded.compact_graph_schema(found, "put the four blocks in a row on the line")
    rows = [g for g in goals_of(schema["properties"]["factors"])
            if g["properties"]["type"]["const"] == "row"]
    assert rows
    for row in rows:
        spacing = row["properties"]["spacing"]
        offered = [v for o in spacing.get("anyOf", [spacing]) for v in o.get("enum", [])]
        assert 0.5 not in offered and offered and max(offered) <= 0.1
        for s in offered:
            goal = {"type": "row", "objects": ["blocks"], "spacing": s, "along": "line",
                    "on": None, "ordered": False}
            assert capacity.layout_problem(goal, found) is None


def test_a_schema_nothing_fits_is_kept_as_it_was() -> None:
    found = [Mention("blocks", "block", None, 12), Mention("zone", "zone", None, 1)]
    goal = grounded.relation_over("in_zone", {"blocks": "block", "zone": "zone"},
                                  {"blocks": 12, "zone": 1})
    assert goal is not None
    pinned = {**goal, "properties": {**goal["properties"],
                                     "objects": {"type": "array",
                                                 "prefixItems": [{"const": "blocks"}],
                                                 "items": False, "minItems": 1,
                                                 "maxItems": 1}}}
    assert capacity.prune(pinned, found) is None
    assert capacity.prune(goal, found) is None  # its only answer moves all 12 blocks
    either = grounded.relation_over("in_zone", {"blocks": "block", "balls": "ball",
                                                "zone": "zone"}, {"blocks": 12, "zone": 1})
    assert either is not None
    unpinned = {"type": "array", "items": {"type": "object", "properties": {"goal": either},
                                           "required": ["goal"]}, "minItems": 1}
    assert capacity.prune(unpinned, found) == unpinned  # objects not pinned: unchanged


@settings(max_examples=40, deadline=None)
@given(proposals, st.data())
def test_every_pinned_goal_the_pruned_schema_allows_can_be_laid_out(proposal, data) -> None:
    found = mentions(proposal)
    if not grounded.applies(found):
        return
    schema = schema_of(proposal)
    answer = sample(schema, data)
    assert schema_problems(answer, schema) == []
    factors = schema["properties"]["factors"]
    if "items" in factors and factors["items"] is not False:
        return  # the plain list: objects not pinned (checked at runtime)
    sized = grounded.graph_mentions(found, proposal)  # the anchors stated goals fill, grown
    goals = [f["goal"] for f in answer["factors"]]
    for k, goal in enumerate(goals):
        problem = capacity.layout_problem(goal, sized)
        earlier = capacity.moving_anchors(goal, goals[:k])
        if problem is not None and earlier:  # laid out after what moves its anchors
            problem = capacity.goals_problem([*earlier, goal], sized)
        assert problem is None or "budget" in problem, (proposal, goal, problem)


@settings(max_examples=25, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["block", "ball", "ell", "box", "cylinder", "zone",
                                           "bowl", "pallet", "line", "fixture", "container"]),
                          st.integers(1, 10), st.sampled_from(sorted(COLOR_NAMES))),
                min_size=1, max_size=4, unique_by=lambda t: t[0]),
       st.sampled_from(["in", "stack", "row", "on", "inside", "circle", "align"]))
def test_prune_over_any_counts_keeps_a_schema_or_the_original(objects, word) -> None:
    found = [Mention(f"{c}_{k}s", k, c, n) for k, n, c in objects]
    if not grounded.applies(found):
        return
    proposal = f"{word} the objects"
    schema = grounded.compact_graph_schema(found, proposal)
    factors = schema["properties"]["factors"]
    assert goals_of(factors), "an empty anyOf is no grammar"
    for goal in goals_of(factors):
        for field in goal["properties"].values():
            assert field.get("anyOf", [None]) != []
            assert field.get("enum", [None]) != []


def test_a_circle_offers_only_the_radii_that_fit_the_workspace() -> None:
    found = [Mention("blocks", "block", None, 2), Mention("ells", "ell", None, 1)]
    schema = grounded.compact_graph_schema(found, "put the blocks and the ell in a circle")
    circles = [g for g in goals_of(schema["properties"]["factors"])
               if g["properties"]["type"]["const"] == "circle"]
    assert circles
    for circle in circles:
        radius = circle["properties"]["radius"]
        offered = [v for o in radius.get("anyOf", [radius]) for v in o.get("enum", [])]
        assert offered and max(offered) < 0.25  # 0.527 m across at 0.2 m: wider than 0.50 m


def test_a_search_budget_can_count_cpu_time_so_a_busy_machine_does_not_spend_it() -> None:
    import time

    import pytest

    from factask.scene.collision import Deadline, LayoutError

    now = [0.0]
    deadline = Deadline.after(0.25, clock=lambda: now[0])
    deadline.check("a row")  # nothing spent yet
    now[0] = 0.3
    assert deadline.passed
    with pytest.raises(LayoutError, match=r"0\.25 s budget"):
        deadline.check("a row")
    cpu = Deadline.after(0.25, clock=time.thread_time)
    time.sleep(0.3)  # waiting (a preempted search) spends no CPU time
    assert not cpu.passed
    assert Deadline.after(0.0).clock is time.monotonic  # wall time by default


def shapes_of(schema: dict) -> list[list[list[dict]]]:
    """The factors' shapes: per shape, per goal position, its goal variants."""
    factors = schema["properties"]["factors"]
    out = []
    for shape in factors.get("anyOf", [factors]):
        if "prefixItems" in shape:
            out.append([goals_of(item) for item in shape["prefixItems"]])
    return out


def names(variant: dict) -> set[str]:
    """The names a goal variant's anchor fields allow."""
    from factask.gen.reading.cover import names_of
    from factask.relations import RELATION_TYPES
    props = variant["properties"]
    return {n for f in RELATION_TYPES[props["type"]["const"]].anchor_fields if f in props
            for n in names_of(props[f])}


def test_goals_that_fit_alone_but_not_on_one_anchor_are_not_offered_together() -> None:
    proposal = ("align the red cylinder, the blue cylinder and the green cylinder "
                "with the fixture")
    found = mentions(proposal)
    assert [m.name for m in found][-1] == "fixture"
    alone = [{"type": "aligned", "objects": [c], "reference": "fixture", "mode": "center"}
             for c in ("red_cylinder", "blue_cylinder")]
    assert all(capacity.layout_problem(g, found) is None for g in alone)
    assert capacity.goals_problem(alone, found) is not None  # one fixture, two cylinders
    shapes = shapes_of(grounded.compact_graph_schema(found, proposal))
    assert shapes
    for shape in shapes:  # one goal per cylinder: only one of them may use the fixture
        assert sum(any("fixture" in names(v) for v in goals) for goals in shape) <= 1


def test_an_anchor_that_holds_every_goal_stays_shared() -> None:
    proposal = "put the red block in the zone and the blue block in the zone"
    found = mentions(proposal)
    both = [{"type": "in_zone", "objects": [b], "zone": "zone"}
            for b in ("red_block", "blue_block")]
    assert capacity.goals_problem(both, found) is None
    each = [s for s in shapes_of(grounded.compact_graph_schema(found, proposal))
            if len(s) == 2]
    assert each and any(all(any("zone" in names(v) for v in goals) for goals in s)
                        for s in each)


def test_two_goals_pinned_to_an_anchor_that_cannot_hold_both_drop_their_shape() -> None:
    found = [Mention("red_ell", "ell", "red", 1), Mention("blue_ell", "ell", "blue", 1),
             Mention("fixture", "fixture", None, 1)]
    item = {"type": "object", "required": ["goal"], "properties": {"goal": {
        "type": "object", "properties": {
            "type": {"const": "aligned"},
            "objects": {"type": "array", "prefixItems": [{"const": "red_ell"}],
                        "items": False, "minItems": 1, "maxItems": 1},
            "reference": {"const": "fixture"}, "mode": {"const": "center"}}}}}
    other = json.loads(json.dumps(item).replace("red_ell", "blue_ell"))
    assert capacity.share_anchors([item, other], found) is None
    assert capacity.share_anchors([item], found) == [item]


def _sampled_goals(proposal: str, data: st.DataObject) -> tuple[list, list[dict]] | None:
    """(mentions, the goals of one answer the proposal's grounded schema allows), or
    None where grounding does not apply or only the plain list is offered (its
    objects are not pinned: checked at runtime)."""
    found = mentions(proposal)
    if not grounded.applies(found):
        return None
    schema = schema_of(proposal)
    factors = schema["properties"]["factors"]
    if "items" in factors and factors["items"] is not False:
        return None
    return found, [f["goal"] for f in sample(schema, data)["factors"]]


@settings(max_examples=30, deadline=None)
@given(proposals, st.data())
def test_goals_an_answer_puts_on_one_fixed_anchor_fit_together(proposal, data) -> None:
    sampled = _sampled_goals(proposal, data)
    if sampled is None:
        return
    found, goals = sampled
    fixed = {m.name for m in found if not m.movable}
    for anchor in fixed:
        on = [g for g in goals if anchor in {v for k, v in g.items()
                                             if k not in ("type", "objects")}]
        if len(on) > 1:
            problem = capacity.goals_problem(on, found)
            assert problem is None or "budget" in problem, (proposal, on, problem)


def _goal_item(mover: str, anchors: list[str]) -> dict:
    return {"type": "object", "required": ["goal"], "properties": {"goal": {
        "type": "object", "properties": {
            "type": {"const": "on"},
            "objects": {"type": "array", "prefixItems": [{"const": mover}],
                        "items": False, "minItems": 1, "maxItems": 1},
            "support": {"type": "string", "enum": anchors}}}}}


def test_goals_that_could_anchor_on_each_other_build_only_on_earlier_objects() -> None:
    # The blue box on the green one, the green box on the blue one: "factor order has
    # a cycle" (the graph invalid). In the order green, blue, red, a goal builds on
    # another goal's object only when that object comes before its own.
    blue = _goal_item("blue_box", ["green_box", "pallet"])
    green = _goal_item("green_box", ["blue_box", "pallet"])
    red = _goal_item("red_box", ["blue_box", "green_box", "pallet"])
    order = ["pallet", "green_box", "blue_box", "red_box"]
    first, second, third = capacity.acyclic_anchors([blue, green, red], order)
    assert names(goals_of(first)[0]) == {"green_box", "pallet"}
    assert names(goals_of(second)[0]) == {"pallet"}
    assert third == red  # both boxes come before it
    # A goal left with nothing but a later object: no answer of the shape is a task.
    only = _goal_item("green_box", ["blue_box"])
    assert capacity.acyclic_anchors([blue, only], order) is None
    # An anchor no other goal moves is never restricted.
    assert capacity.acyclic_anchors([only], order) == [only]


@settings(max_examples=30, deadline=None)
@given(proposals, st.data())
def test_an_answer_never_anchors_its_goals_in_a_circle(proposal, data) -> None:
    import networkx as nx

    sampled = _sampled_goals(proposal, data)
    if sampled is None:
        return
    _, goals = sampled
    order = nx.DiGraph()
    for i, g in enumerate(goals):
        named = {v for k, v in g.items() if k not in ("type", "objects") and isinstance(v, str)}
        order.add_edges_from((i, k) for k, h in enumerate(goals)
                             if k != i and named & set(h["objects"]))
    assert nx.is_directed_acyclic_graph(order), (proposal, goals)


def test_the_words_bases_come_first() -> None:
    from factask.gen.reading.bases import base_order

    def order(proposal: str) -> list[str]:
        return base_order(mentions(proposal), proposal)

    assert order("put the red block on the blue block and the blue block on the green "
                 "block") == ["green_block", "blue_block", "red_block"]
    assert order("stack a red, a blue and a green block") == [
        "red_block", "blue_block", "green_block"]
    assert order("place the blue box on top of the green box, then put the green box into "
                 "the brown container") == ["brown_container", "green_box", "blue_box"]
    # Placings in a circle say nothing: the order of mention.
    assert order("put the red block on the blue block and the blue block on the red "
                 "block") == ["red_block", "blue_block"]


@settings(max_examples=50, deadline=None)
@given(st.lists(st.sampled_from(
    ["red", "blue", "block", "box", "on", "into", "the", "top", "of", "bowl", "zone", "and",
     "put", "green", "blocks", "x", ",", "onto", "three"]), max_size=24))
def test_base_order_names_every_mention_once(words: list[str]) -> None:
    from factask.gen.reading.bases import base_order

    proposal = " ".join(words)
    found = mentions(proposal)
    assert sorted(base_order(found, proposal)) == sorted(m.name for m in found)
