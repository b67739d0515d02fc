"""The goals a proposal's words state (factask.gen.reading.clauses) and their grammar."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.gen.compare import compare
from factask.gen.first_choice import first_choice
from factask.gen.reading import grounded
from factask.gen.reading.capacity import layout_problem
from factask.gen.reading.clauses import ReadGoal, parts_of, read_goals, still_objects
from factask.gen.reading.mentions import mentions
from factask.graph.taskgraph import parse_graph
from factask.vocabulary.kinds import kind_spec


def goals(proposal: str) -> list[tuple]:
    out = read_goals(proposal, mentions(proposal))
    assert out is not None, proposal
    return [(g.relation, g.objects, g.anchor, g.ordered, g.step) for g in out]


@pytest.mark.parametrize(("proposal", "expected"), [
    # one at a time onto one stand, the words saying what is at the bottom: one stack
    ("Put the green, red and blue cylinders on the stand one at a time: blue at the "
     "bottom, then red, and green at the top.",
     [("stack", ("blue_cylinder", "red_cylinder", "green_cylinder"), "stand", True, 0)]),
    # the order a later sentence gives
    ("Build a tower of the purple, orange and green blocks on the pallet. From bottom to "
     "top the colours go orange, green, purple.",
     [("stack", ("orange_block", "green_block", "purple_block"), "pallet", True, 0)]),
    # the scene in the passive: no goal ("the bowls are placed in a row")
    ("Put the red block in the red bowl and the blue block in the blue bowl. The bowls "
     "are placed in a row and the blocks are scattered on the table.",
     [("inside", ("red_block",), "red_bowl", False, 0),
      ("inside", ("blue_block",), "blue_bowl", False, 0)]),
    # between a pair of regions: a row from one to the other
    ("Set the cyan cylinder between the two white zones.",
     [("row", ("cyan_cylinder",), "white_zones", False, 0)]),
    # the rainbow's order
    ("Line up the blue, yellow and red blocks in rainbow order.",
     [("row", ("red_block", "yellow_block", "blue_block"), None, True, 0)]),
    # gapping: one verb, two goals
    ("Put the blue blocks in the blue bowl and the green blocks in the green bowl.",
     [("inside", ("blue_blocks",), "blue_bowl", False, 0),
      ("inside", ("green_blocks",), "green_bowl", False, 0)]),
    # "ones" is the kind named last (not the zone after "in")
    ("There are four red blocks and four blue blocks; put the red ones in the red zone "
     "and the blue ones in the blue zone.",
     [("in_zone", ("red_blocks",), "red_zone", False, 0),
      ("in_zone", ("blue_blocks",), "blue_zone", False, 0)]),
    # a count stated in another sentence, and "then" as a step
    ("First put the cyan blocks in the container, then stack the pink blocks on the pallet. "
     "There are two cyan blocks and three pink ones.",
     [("inside", ("cyan_blocks",), "container", False, 0),
      ("stack", ("pink_blocks",), "pallet", False, 1)]),
    # two shape words, each over the objects named after it
    ("Make a row from the red blocks and a circle from the blue blocks.",
     [("row", ("red_blocks",), None, False, 0), ("circle", ("blue_blocks",), None, False, 0)]),
    # one goal over objects the words put in one at a time, in a colour order
    ("Put the balls in the container one at a time in this order: black, white, gold.",
     [("inside", ("black_ball",), "container", False, 0),
      ("inside", ("white_ball",), "container", False, 1),
      ("inside", ("gold_ball",), "container", False, 2)]),
    # ... and one goal where no order is given
    ("Put the red, green and blue blocks in the bowl.",
     [("inside", ("red_block", "green_block", "blue_block"), "bowl", False, 0)]),
    # one shape word after each group: an arrangement each
    ("Put the five red blocks in a circle, and put the five blue blocks in a circle.",
     [("circle", ("red_blocks",), None, False, 0), ("circle", ("blue_blocks",), None, False, 0)]),
    # "align X with Y": Y is the anchor
    ("Align the red ell with the red fixture, then align the blue ell with the blue fixture.",
     [("aligned", ("red_ell",), "red_fixture", False, 0),
      ("aligned", ("blue_ell",), "blue_fixture", False, 1)]),
    # into a corner marker: corner to corner; along it: a row
    ("Put the brown box into the green corner.",
     [("aligned", ("brown_box",), "green_corner", False, 0)]),
    ("Put the red block and the blue block in a row along the corner.",
     [("row", ("red_block", "blue_block"), "corner", False, 0)]),
    # six pairs: twelve objects named
    ("Put the red ball into the red zone, the blue ball into the blue zone, the green ball "
     "into the green zone, the yellow ball into the yellow zone, the orange ball into the "
     "orange zone and the purple ball into the purple zone.",
     [("in_zone", (f"{c}_ball",), f"{c}_zone", False, 0)
      for c in ("red", "blue", "green", "yellow", "orange", "purple")]),
    # "two towers": one per group
    ("Make two towers, one from three maroon blocks and the other from three navy blocks.",
     [("stack", ("maroon_blocks",), None, False, 0),
      ("stack", ("navy_blocks",), None, False, 0)]),
    # around X: X is the centre
    ("Place the five yellow balls in a circle around the purple block.",
     [("circle", ("yellow_balls",), "purple_block", False, 0)]),
    # the order of a stack from the places the words give each colour
    ("Build one tower: 2 purple blocks at the bottom and 3 yellow cylinders stacked on top.",
     [("stack", ("purple_blocks", "yellow_cylinders"), None, True, 0)]),
    # the order from a list after "the bottom", read again from a second sentence
    ("Stack the red, blue and green cylinders on the stand. The bottom of the stack is the "
     "blue cylinder, followed by the green one, then the red one.",
     [("stack", ("blue_cylinder", "green_cylinder", "red_cylinder"), "stand", True, 0)]),
    # "in that order" points back at the colours named before it
    ("Stack the red, green and blue blocks into a tower in that order.",
     [("stack", ("red_block", "green_block", "blue_block"), None, True, 0)]),
    # ordinals after an anchored goal: the same goal, one step each
    ("First put the orange block on the pallet, second the purple block, and third the "
     "pink block.",
     [("on", ("orange_block",), "pallet", False, 0), ("on", ("purple_block",), "pallet", False, 1),
      ("on", ("pink_block",), "pallet", False, 2)]),
    # anchors paired with their objects by colour
    ("There are two balls (red, blue) and two cylinders of matching colours. Put each "
     "ball on the cylinder of the same colour.",
     [("on", ("red_ball",), "red_cylinder", False, 0),
      ("on", ("blue_ball",), "blue_cylinder", False, 0)]),
    # goals in a colour sequence
    ("Put the blocks (red, green, blue) in the bowls of matching colour, in the sequence "
     "blue, red, green.",
     [("inside", ("red_block",), "red_bowl", False, 1),
      ("inside", ("green_block",), "green_bowl", False, 2),
      ("inside", ("blue_block",), "blue_bowl", False, 0)]),
    # "fill X with Y": Y goes into X
    ("Fill the green bowl with three red balls and a single yellow ball.",
     [("inside", ("red_balls", "yellow_ball"), "green_bowl", False, 0)]),
    # a fixture takes its object aligned; a pile is swept
    ("insert the red ell into the red fixture", [("aligned", ("red_ell",), "red_fixture", False,
                                                  0)]),
    ("sweep the pile of small blocks into the green zone",
     [("pile_in_zone", ("pile",), "green_zone", False, 0)]),
])
def test_the_goals_the_words_state(proposal: str, expected: list[tuple]) -> None:
    assert goals(proposal) == expected


@pytest.mark.parametrize(("proposal", "expected", "still"), [
    ("Put the red block in the bowl and leave the blue block alone.",
     [("inside", ("red_block",), "bowl", False, 0)], {"blue_block"}),
    ("Place the cyan block in the blue zone, not in the green zone.",
     [("in_zone", ("cyan_block",), "blue_zone", False, 0)], {"green_zone"}),
    ("Stack the two white boxes, but do not move the black box.",
     [("stack", ("white_boxes",), None, False, 0)], {"black_box"}),
    ("Put the green box on the pallet; the red and yellow boxes around it are not part of "
     "the task.", [("on", ("green_box",), "pallet", False, 0)], {"red_box", "yellow_box"}),
    ("Take the blue ball out of the bowl and put it on the stand.",
     [("on", ("blue_ball",), "stand", False, 0)], {"bowl"}),
    ("Without moving the red block, put the green block on the pallet.",
     [("on", ("green_block",), "pallet", False, 0)], {"red_block"}),
])
def test_objects_the_words_keep_still_have_no_goal(proposal: str, expected: list[tuple],
                                                    still: set[str]) -> None:
    assert goals(proposal) == expected
    assert still_objects(proposal, mentions(proposal)) == still


@pytest.mark.parametrize("proposal", [
    # nothing moves
    "The zone is green.",
    # "the other" names no kind the words named before: the green block has no anchor
    "Put the red block on the bowl and the green block on the other.",
])
def test_no_reading_where_the_words_leave_an_object_without_a_goal(proposal: str) -> None:
    assert read_goals(proposal, mentions(proposal)) is None


def test_a_list_after_then_goes_on_and_a_new_action_is_a_step() -> None:
    assert [s for _, s in parts_of("stack red, then blue, then green")] == [0]
    assert [s for _, s in parts_of("put the block in the bowl, then put the ball on it")] \
        == [0, 1]
    assert [s for _, s in parts_of("make a row of four blocks and after that a second row")] \
        == [0, 1]


def test_a_stated_goal_grows_its_anchor_to_fit() -> None:
    proposal = "put the five blocks in the zone"
    found = mentions(proposal)
    goal = {"type": "in_zone", "objects": ["blocks"], "zone": "zone"}
    assert layout_problem(goal, found) is not None  # the default zone is too small
    sized = grounded.graph_mentions(found, proposal)
    zone = next(m for m in sized if m.name == "zone")
    assert zone.size is not None and zone.size[0] > kind_spec("zone").default_size[0]
    assert layout_problem(goal, sized) is None
    schema = grounded.compact_graph_schema(found, proposal)
    graph = parse_graph(grounded.expand_graph(first_choice(schema), found, "t", proposal))
    assert list(graph.variable("zone").size) == list(zone.size)


def test_goals_that_share_an_anchor_grow_it_for_all_they_put_there() -> None:
    proposal = "First put the red block in the bowl, then the blue block."
    found = mentions(proposal)
    both = {"type": "inside", "objects": ["red_block", "blue_block"], "container": "bowl"}
    assert layout_problem(both, found) is not None  # a default bowl holds one block
    sized = grounded.graph_mentions(found, proposal)
    assert layout_problem(both, sized) is None


def test_the_words_steps_become_the_factors_order() -> None:
    proposal = "First put the cyan block in the container, then put the pink block on the pallet."
    found = mentions(proposal)
    schema = grounded.compact_graph_schema(found, proposal)
    graph = parse_graph(grounded.expand_graph(first_choice(schema), found, "t", proposal))
    first, second = graph.factors
    assert first.goal.objects == ["cyan_block"] and second.after == [first.name]


def test_steps_that_contradict_the_anchors_are_left_to_the_anchors() -> None:
    # The ball goes in the bowl first, but the bowl's own goal is the anchor's: no cycle.
    proposal = "drop the pink ball into the yellow bowl, then put the bowl in the green zone"
    found = mentions(proposal)
    schema = grounded.compact_graph_schema(found, proposal)
    graph = parse_graph(grounded.expand_graph(first_choice(schema), found, "t", proposal))
    graph.ensure_valid()


def test_the_reading_only_graph_means_the_proposal() -> None:
    proposal = "Put two blue blocks and three green ones into the brown container."
    reference = {
        "name": "r", "description": proposal,
        "variables": [
            {"name": "b", "description": "d", "kind": "block", "color": "blue", "count": 2},
            {"name": "g", "description": "d", "kind": "block", "color": "green", "count": 3},
            {"name": "c", "description": "d", "kind": "container", "color": "brown",
             "size": [0.2, 0.2, 0.05]}],
        "factors": [{"name": "f", "description": "d", "weight": 1.0,
                     "goal": {"type": "inside", "objects": ["b", "g"], "container": "c"}}]}
    found = mentions(proposal)
    schema = grounded.compact_graph_schema(found, proposal)
    graph = parse_graph(grounded.expand_graph(first_choice(schema), found, "t", proposal))
    assert compare(graph, reference, proposal).equivalent


_WORDS = ["put", "the", "red", "blue", "green", "block", "blocks", "ball", "bowl", "zone",
          "in", "on", "into", "then", "and", "stack", "tower", "row", "circle", "around",
          "pallet", "two", "three", "ones", "of", "each", ".", ",", "first", "bottom", "top",
          "them", "it", "pile", "line", "along", "fixture", "insert", "another", "order"]


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from(_WORDS), max_size=30).map(" ".join) | st.text(max_size=200))
def test_any_text_gives_goals_over_its_own_objects_or_none(text: str) -> None:
    found = mentions(text)
    out = read_goals(text, found)
    if out is None:
        return
    names = {m.name for m in found}
    assert all(isinstance(g, ReadGoal) and g.objects and g.step >= 0 for g in out)
    used = {n for g in out for n in (*g.objects, g.anchor) if n}
    still = still_objects(text, found)
    assert used | still == names and not used & still  # every named object, once
    assert all(g.anchor not in g.objects for g in out)


def test_a_fixed_object_of_a_kind_that_moves_is_a_fixed_variable() -> None:
    proposal = "Put the red ball in the red zone; leave the three fixed gray boxes where they are."
    found = mentions(proposal)
    boxes = next(m for m in found if m.kind == "box")
    assert boxes.pinned and not boxes.movable and boxes.as_variable()["fixed"] is True
    assert still_objects(proposal, found) == {"gray_boxes"}
    loose = next(m for m in mentions("Put the red ball in the red zone; leave the gray box.")
                 if m.kind == "box")
    assert not loose.pinned and loose.movable
