"""The objects a proposal names (factask.gen.reading.mentions): a parser of outside
input, so property-based as well as by example."""

from __future__ import annotations

import json
import re

import pytest
from hypothesis import given
from hypothesis import strategies as st

from factask.gen.reading.mentions import MAX_SPLIT_MENTIONS, mentions, mentions_text
from factask.vocabulary.kinds import ASSET_KINDS
from factask.vocabulary.names import NAME_PATTERN
from factask.vocabulary.palette import COLOR_NAMES


def _names(text: str) -> list[tuple[str, str, str | None, int]]:
    return [(m.name, m.kind, m.color, m.count) for m in mentions(text)]


def test_colour_kind_and_count_are_read_from_the_words() -> None:
    assert _names("put the red block in the green zone") == [
        ("red_block", "block", "red", 1), ("green_zone", "zone", "green", 1)]
    assert _names("Place three red cubes and 2 blue cylinders in a brown bowl.") == [
        ("red_blocks", "block", "red", 3), ("blue_cylinders", "cylinder", "blue", 2),
        ("brown_bowl", "bowl", "brown", 1)]
    assert _names("six red and blue blocks around the zone") == [
        ("red_blocks", "block", "red", 3), ("blue_blocks", "block", "blue", 3),
        ("zone", "zone", None, 1)]
    assert _names("sort the spheres into the red and green zones") == [
        ("balls", "ball", None, 2), ("red_zone", "zone", "red", 1),
        ("green_zone", "zone", "green", 1)]


def test_a_proposal_naming_nothing_says_so() -> None:
    assert mentions("do something clever") == []
    assert "none recognised" in mentions_text("do something clever")


@given(st.text(max_size=300) | st.lists(st.sampled_from(
    [*ASSET_KINDS, *COLOR_NAMES, "and", "three", "12", "blocks", "the", "-", "_"]),
    max_size=60).map(" ".join))
def test_any_text_gives_valid_distinct_bounded_mentions(text: str) -> None:
    found = mentions(text)
    assert len(found) <= MAX_SPLIT_MENTIONS
    assert len({m.name for m in found}) == len(found)
    for m in found:
        assert re.fullmatch(NAME_PATTERN, m.name) and "__" not in m.name, m
        assert m.kind in ASSET_KINDS and (m.color is None or m.color in COLOR_NAMES)
        assert 1 <= m.count <= 16
    assert mentions_text(text).count("\n") == max(len(found) - 1, 0)


def test_a_coloured_object_of_the_proposal_must_be_a_variable() -> None:
    from factask.gen.reading.mentions import grounding_feedback, missing_mentions
    from factask.vocabulary.variables import StateVariable

    proposal = "put the yellow cylinder in the blue zone, next to a bowl"
    copied = [StateVariable(name="blue_cylinder", kind="cylinder", color="blue"),
              StateVariable(name="green_zone", kind="zone", color="green")]
    assert [m.name for m in missing_mentions(proposal, copied)] == [
        "yellow_cylinder", "blue_zone"]  # the uncoloured bowl is not required
    feedback = grounding_feedback(proposal, copied)
    assert feedback and "yellow_cylinder: kind cylinder, colour yellow" in feedback
    right = [StateVariable(name="cyl", kind="cylinder", color="yellow"),
             StateVariable(name="target", kind="zone", color="blue")]
    assert grounding_feedback(proposal, right) is None


def test_a_generated_graph_lacking_a_named_object_gets_that_feedback() -> None:
    from test_gen_strategies import _run

    from factask.gen.demo import DEMO_PROPOSAL, demo_graph

    wrong = demo_graph()
    wrong["variables"][0]["color"] = "orange"  # the proposal's red block is missing
    result, server = _run({"one_shot": [json.dumps(wrong), json.dumps(demo_graph())]},
                          "one-shot", max_repairs=1)
    assert "red_block: kind block, colour red" in result.steps[0].feedback
    assert result.level_reached == "completion" and "red" in DEMO_PROPOSAL
    assert any("red_block: kind block" in m["content"] for m in
               server.requests[-1]["messages"] if m["role"] == "user")


def test_a_later_phrase_naming_a_kind_again_refers_back() -> None:
    # The task name's words after the description, and "the sphere" after "a blue
    # sphere": the same object, not a second one every goal would have to use.
    assert _names("Pick up a blue sphere and place it into an open container. "
                  "insert sphere into container") == [
        ("blue_ball", "ball", "blue", 1), ("container", "container", None, 1)]
    # A coloured member of an uncoloured group named before it.
    assert _names("stack six blocks on the pallet; a red block at the bottom") == [
        ("blocks", "block", None, 6), ("pallet", "pallet", None, 1)]
    # Distinct colours of one kind stay distinct objects.
    assert _names("put the red block in the green zone, then the blue block on it") == [
        ("red_block", "block", "red", 1), ("green_zone", "zone", "green", 1),
        ("blue_block", "block", "blue", 1)]


def test_plural_names_follow_english_endings() -> None:
    assert _names("three boxes and two blocks") == [
        ("boxes", "box", None, 3), ("blocks", "block", None, 2)]


def test_everyday_words_for_the_kinds_are_read() -> None:
    assert _names("put the green puck in the basket") == [
        ("green_cylinder", "cylinder", "green", 1), ("container", "container", None, 1)]
    assert _names("stack the crates on the platform") == [
        ("boxes", "box", None, 2), ("pallet", "pallet", None, 1)]
    assert _names("put the orb in the dish") == [
        ("ball", "ball", None, 1), ("bowl", "bowl", None, 1)]
    # Objects of no stated shape are blocks; a board with silhouettes is a kit of holes.
    assert _names("pack the objects into the container") == [
        ("blocks", "block", None, 2), ("container", "container", None, 1)]
    assert _names("arrange the shapes on a board marked with silhouettes") == [
        ("blocks", "block", None, 2), ("kit", "kit", None, 1),
        ("fixtures", "fixture", None, 2)]


def test_an_l_shaped_piece_is_one_ell_and_a_pile_of_blocks_one_pile() -> None:
    assert _names("put the red L-shaped block into the hole") == [
        ("red_ell", "ell", "red", 1), ("fixture", "fixture", None, 1)]
    # GenSim's block-insertion: the hole keeps its own word.
    assert _names("put the L shape block in the L shape hole") == [
        ("ell", "ell", None, 1), ("fixture", "fixture", None, 1)]
    assert _names("put two L shapes in the L-shaped slots") == [
        ("ells", "ell", None, 2), ("fixtures", "fixture", None, 2)]
    assert _names("put three red L shaped blocks in the slots") == [
        ("red_ells", "ell", "red", 3), ("fixtures", "fixture", None, 2)]
    assert _names("push the pile of small red blocks into the green zone") == [
        ("red_pile", "pile", "red", 1), ("green_zone", "zone", "green", 1)]
    assert _names("sweep a heap of cubes onto the pad") == [
        ("pile", "pile", None, 1), ("zone", "zone", None, 1)]


def test_a_leading_task_name_adds_no_object_the_description_does_not_name() -> None:
    # The benchmark writes "name: description"; the description says what the
    # objects are (an L shape block is an ell: no block besides it).
    assert _names("block-insertion: put the L shape block in the L shape hole") == [
        ("ell", "ell", None, 1), ("fixture", "fixture", None, 1)]
    assert _names("build-block-tower-on-pallet: stack six blocks on the pallet") == [
        ("blocks", "block", None, 6), ("pallet", "pallet", None, 1)]
    # A description naming nothing leaves the name's words.
    assert _names("red-block-in-zone: do it") == [
        ("red_block", "block", "red", 1), ("zone", "zone", None, 1)]
    # The generator reads "description name": the same rule, and a name still adds
    # what the description only refers to ("them").
    assert _names("put the L shape block in the L shape hole block-insertion") == [
        ("ell", "ell", None, 1), ("fixture", "fixture", None, 1)]
    assert _names("stack them on the pallet stack-blocks-on-pallet") == [
        ("pallet", "pallet", None, 1), ("blocks", "block", None, 2)]


def test_an_everyday_word_accepts_every_kind_it_may_mean() -> None:
    from factask.gen.reading.mentions import ALSO_KINDS, missing_mentions
    from factask.gen.reading.words import KIND_WORDS
    from factask.vocabulary.kinds import KIND_NAMES
    from factask.vocabulary.variables import StateVariable

    assert set(ALSO_KINDS) <= set(KIND_WORDS)
    assert {k for kinds in ALSO_KINDS.values() for k in kinds} <= set(KIND_NAMES)
    proposal = "put the green puck in the red basket"
    as_bowl = [StateVariable(name="puck", kind="cylinder", color="green"),
               StateVariable(name="basket", kind="bowl", color="red")]
    assert missing_mentions(proposal, as_bowl) == []
    as_zone = [as_bowl[0], StateVariable(name="basket", kind="zone", color="red")]
    assert [m.name for m in missing_mentions(proposal, as_zone)] == ["red_container"]
    # A kind word is the reading's guess; the colour and the sort of object are not:
    # cylinders aligned with a hole may lie down (logs), a container with a slot on
    # top is a fixture.
    lying = [StateVariable(name="c", kind="log", color="red"),
             StateVariable(name="b", kind="fixture", color="blue")]
    assert missing_mentions("insert the red cylinder into the blue container",
                            lying) == []
    assert [m.name for m in missing_mentions("put the red ball in the blue bowl",
                                             lying)] == []  # a red mover, a blue holder
    assert [m.name for m in missing_mentions("put the green ball in the blue bowl",
                                             lying)] == ["green_ball"]


def test_counts_read_past_modifiers_and_from_a_list_of_colours() -> None:
    assert _names("Sort four differently colored blocks into four matching colored bowls") == [
        ("blocks", "block", None, 4), ("bowls", "bowl", None, 4)]
    assert _names("twelve blocks of four different colors and a pallet") == [
        ("blocks", "block", None, 12), ("pallet", "pallet", None, 1)]
    # A plural with no count is one object per colour of the list right after it...
    assert _names("stack the blocks (red, blue, green, and yellow) on the stand") == [
        ("red_block", "block", "red", 1), ("blue_block", "block", "blue", 1),
        ("green_block", "block", "green", 1), ("yellow_block", "block", "yellow", 1),
        ("stand", "stand", None, 1)]
    assert _names("cylinders of different colors: red, blue and green") == [
        ("red_cylinder", "cylinder", "red", 1), ("blue_cylinder", "cylinder", "blue", 1),
        ("green_cylinder", "cylinder", "green", 1)]
    assert _names("six blocks in two colours (three red and three blue)") == [
        ("red_blocks", "block", "red", 3), ("blue_blocks", "block", "blue", 3)]
    # ... not by colours that belong to the next noun.
    assert _names("put the blocks in the red and blue bowls") == [
        ("blocks", "block", None, 2), ("red_bowl", "bowl", "red", 1),
        ("blue_bowl", "bowl", "blue", 1)]


def test_ell_shaped_is_read_like_l_shaped() -> None:
    assert _names("three different colored ell-shaped fixtures") == [
        ("fixtures", "fixture", None, 3)]
    assert _names("put the ell-shaped block into the L-shaped hole") == [
        ("ell", "ell", None, 1), ("fixture", "fixture", None, 1)]


def test_a_noun_before_the_kind_word_does_not_hide_the_count() -> None:
    assert _names("insert three ell blocks into three insertion fixtures") == [
        ("ells", "ell", None, 3), ("fixtures", "fixture", None, 3)]
    assert _names("stack four kitting slots") == [("fixtures", "fixture", None, 4)]
    # A function word between them is no noun: the count is not the kind's.
    assert _names("three of the blocks") == [("blocks", "block", None, 2)]
    assert _names("put two in each bowl") == [("bowl", "bowl", None, 1)]


def test_a_matching_colour_phrase_splits_groups_into_one_object_per_colour() -> None:
    # The list of colours is both groups' when they are as large as it.
    # (A box something is put into is a container, every time the words name it.)
    assert _names("There are four spheres and four boxes of different colors (red, blue, "
                  "green, and yellow). Place each sphere in the box of the same color.") == [
        (f"{c}_{k}", kind, c, 1) for k, kind in (("ball", "ball"),
                                                  ("container", "container"))
        for c in ("red", "blue", "green", "yellow")]
    assert _names("stack the two boxes on the pallet")[0][1] == "box"
    # The phrase qualifies its own noun ("bowls of the same colour") with the colours
    # named for the others, one each when the words give fewer.
    assert _names("sort the red and blue blocks into the bowls of the same colour") == [
        ("red_block", "block", "red", 1), ("blue_block", "block", "blue", 1),
        ("red_bowl", "bowl", "red", 1), ("blue_bowl", "bowl", "blue", 1)]
    assert _names("put the red block in the bowl of the matching color") == [
        ("red_block", "block", "red", 1), ("red_bowl", "bowl", "red", 1)]
    # Counts per colour stay with their colour; other objects are left alone.
    assert _names("twelve blocks of three colors (four red, four green, four blue) go into "
                  "the zones of their colour on a pallet") == [
        ("red_blocks", "block", "red", 4), ("green_blocks", "block", "green", 4),
        ("blue_blocks", "block", "blue", 4), ("red_zone", "zone", "red", 1),
        ("green_zone", "zone", "green", 1), ("blue_zone", "zone", "blue", 1),
        ("pallet", "pallet", None, 1)]


def test_a_listed_group_is_one_object_per_colour_without_a_matching_phrase() -> None:
    assert _names("put the balls of different colors (red, blue, green) in the zone") == [
        ("red_ball", "ball", "red", 1), ("blue_ball", "ball", "blue", 1),
        ("green_ball", "ball", "green", 1), ("zone", "zone", None, 1)]
    from factask.gen.reading.mentions import colour_matched

    assert colour_matched("color-coordinated-ball-insertion")
    assert colour_matched("zones correspondingly colored")
    assert colour_matched("sort the blocks by colour")
    assert not colour_matched("put the red block on the blue colored pallet")


def test_each_colour_may_have_its_own_count_and_an_adjective_may_say_the_kind() -> None:
    assert _names("stack three red, three blue, and three green blocks on a pallet") == [
        ("red_blocks", "block", "red", 3), ("blue_blocks", "block", "blue", 3),
        ("green_blocks", "block", "green", 3), ("pallet", "pallet", None, 1)]
    assert _names("two red and three blue blocks") == [
        ("red_blocks", "block", "red", 2), ("blue_blocks", "block", "blue", 3)]
    assert [m.kind for m in mentions("pick up the cylindrical blocks and spherical objects")] \
        == ["cylinder", "ball"]


def test_a_cylinder_the_words_lay_on_its_side_is_a_log() -> None:
    assert _names("balance a green cylinder horizontally on top of the red blocks") == [
        ("green_log", "log", "green", 1), ("red_blocks", "block", "red", 2)]
    assert _names("put the horizontal cylinder in the zone")[0][:2] == ("log", "log")
    assert _names("put the horizontal green cylinder in the blue zone")[0] == (
        "green_log", "log", "green", 1)
    assert _names("the two red cylinders lying on their side")[0] == (
        "red_logs", "log", "red", 2)
    assert _names("put the red cylinder in the bowl")[0][1] == "cylinder"


def test_a_box_the_words_give_a_hole_is_a_holed_box_and_its_hole_no_object() -> None:
    # "with a hole": that box; "the boxes have a hole" (after they were named): all.
    assert _names("align the green cylinder with the hole of a yellow box with a small "
                  "hole on one side, and put the red block in the blue box") == [
        ("green_cylinder", "cylinder", "green", 1),
        ("yellow_holed_box", "holed_box", "yellow", 1),
        ("red_block", "block", "red", 1), ("blue_container", "container", "blue", 1)]
    assert [m.kind for m in mentions(
        "three cylinders (red, blue and green) and three boxes of the same colours. The "
        "boxes have a small hole on one of their sides. Align each cylinder with the hole "
        "in the box of its colour.")] == ["cylinder"] * 3 + ["holed_box"] * 3
    assert _names("put the red block in the box")[1][1] == "container"  # no hole: a box to fill
    assert _names("insert the peg into the hole")[1][1] == "fixture"


@given(st.lists(st.sampled_from([*COLOR_NAMES[:6], "and", "four", "two", "blocks", "bowls",
                                 "zones", "of", "the", "same", "colour", "matching",
                                 "(", ")", ","]), max_size=40).map(" ".join))
def test_splitting_by_colour_keeps_names_distinct_and_coloured(text: str) -> None:
    found = mentions(text)
    assert len(found) <= MAX_SPLIT_MENTIONS
    assert len({m.name for m in found}) == len(found)
    for m in found:
        assert m.name == (f"{m.color}_" if m.color else "") + m.name.split("_")[-1]
        assert 1 <= m.count <= 16


def test_under_a_matching_phrase_an_uncoloured_object_is_the_group_of_its_coloured_kin() -> None:
    assert _names("put each ball in the container of its colour: a red ball and a green "
                  "ball") == [("red_container", "container", "red", 1),
                              ("green_container", "container", "green", 1),
                              ("red_ball", "ball", "red", 1), ("green_ball", "ball", "green", 1)]


@pytest.mark.parametrize(("proposal", "expected"), [
    # a total stated after the group
    ("Move all the grey cylinders, four in total, into the container.",
     [("gray_cylinders", 4), ("container", 1)]),
    ("Put the blocks in the bowl, six in all.", [("blocks", 6), ("bowl", 1)]),
    # several shapes of one size each: a group per shape
    ("Build 2 towers of 3 cylinders each.", [("cylinders", 3), ("cylinders_2", 3)]),
    ("Make three columns of three cubes each.",
     [("blocks", 3), ("blocks_2", 3), ("blocks_3", 3)]),
    # colours listed on their own under a matching phrase: every uncoloured group's
    ("Fit every ell into the fixture of its color; the ells and the fixtures are red and "
     "blue.", [("red_ell", 1), ("blue_ell", 1), ("red_fixture", 1), ("blue_fixture", 1)]),
    # ... but not again where a group's own list gives them
    ("Stack blocks of three different colors (red, blue, green) on the pallet.",
     [("red_block", 1), ("blue_block", 1), ("green_block", 1), ("pallet", 1)]),
    # a colour list after an order word: the moved group's colours; "N of them"
    ("Put the balls in the container one at a time in this order: black, white, gold.",
     [("black_ball", 1), ("white_ball", 1), ("gold_ball", 1), ("container", 1)]),
    ("Move the two balls into the container and leave the cylinders where they are; "
     "there are three of them.", [("balls", 2), ("container", 1), ("cylinders", 3)]),
    # "that stands": a verb; a kitting plate: the kit
    ("Put the three boxes on the grey pallet that stands at the centre of the table.",
     [("boxes", 3), ("gray_pallet", 1)]),
    ("Set 5 violet blocks and 4 lime blocks down on the kitting plate.",
     [("violet_blocks", 5), ("lime_blocks", 4), ("kit", 1)]),
])
def test_counts_groups_and_compound_kinds_stated_around_a_group(proposal, expected) -> None:
    assert [(m.name, m.count) for m in mentions(proposal)] == expected


def test_an_uncoloured_object_never_takes_a_colour_the_words_give_another() -> None:
    from factask.gen.reading.mentions import NEUTRAL_COLOURS, unnamed_colour

    grey = mentions("move all the grey cylinders into the container")
    assert unnamed_colour(grey) == "white"
    container = next(m for m in grey if m.kind == "container")
    assert container.as_variable(unnamed=unnamed_colour(grey))["color"] == "white"
    assert unnamed_colour(mentions("put the red block in the bowl")) == "gray"
    # every neutral colour named: the first neutral one after all (no colour is free)
    crowded = mentions("put the gray block, the white block, the brown block and the "
                       "black block in the bowl")
    assert {m.color for m in crowded} >= set(NEUTRAL_COLOURS)
    assert unnamed_colour(crowded) == NEUTRAL_COLOURS[0]
