"""Members picked out of a group of alike objects (factask.gen.reading.selectors)."""

from __future__ import annotations

import itertools

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.gen.first_choice import first_choice
from factask.gen.reading import grounded
from factask.gen.reading.accounting import account
from factask.gen.reading.clauses import read_goals, still_objects
from factask.gen.reading.mentions import mentions
from factask.gen.reading.selectors import spell_out
from factask.graph.taskgraph import parse_graph
from factask.vocabulary.kinds import kind_spec


def goals(proposal: str) -> list[tuple[str, tuple[str, ...], str | None]]:
    out = read_goals(proposal, mentions(proposal))
    assert out is not None, proposal
    return [(g.relation, g.objects, g.anchor) for g in out]


@pytest.mark.parametrize(("proposal", "expected"), [
    ("Three zones lie in a row from left to right. Put the green block in the second zone "
     "from the left.", [("in_zone", ("green_block",), "second_zone")]),
    ("Three bowls stand in a row. Put the red ball in the first bowl and the blue ball in "
     "the third bowl; the second bowl stays empty.",
     [("inside", ("red_ball",), "first_bowl"), ("inside", ("blue_ball",), "third_bowl")]),
    # "the second" alone: the kind named last that has a second
    ("Two containers sit on the table. Drop the yellow ball into the first container and "
     "the green ball into the second.",
     [("inside", ("yellow_ball",), "first_container"),
      ("inside", ("green_ball",), "second_container")]),
    ("Four containers stand in a row; put the white block into the fourth one.",
     [("inside", ("white_block",), "fourth_container")]),
    ("Two zones are marked on the table. Put the white box in the near zone.",
     [("in_zone", ("white_box",), "near_zone")]),
    ("Two cylinders stand on the table. Put the red block on one cylinder and the green "
     "block on the other.",
     [("on", ("red_block",), "one_cylinder"), ("on", ("green_block",), "other_cylinder")]),
    ("Rest the black ball on one of the two tall cylinders; the other cylinder should stay "
     "bare.", [("on", ("black_ball",), "one_cylinder")]),
])
def test_a_picked_member_is_the_goals_anchor(proposal: str, expected: list[tuple]) -> None:
    assert goals(proposal) == expected


def test_the_members_nobody_picks_stay_where_they_are() -> None:
    text = "Three zones lie on the table. Put the green block in the third zone."
    assert still_objects(text, mentions(text)) == {"first_zone", "second_zone"}


def test_a_fixed_row_stands_left_to_right_and_near_to_far() -> None:
    row = {m.name: m.place for m in mentions(
        "Three bowls stand in a row. Put the ball in the left bowl.")}
    assert row["left_bowl"] is not None and row["right_bowl"] is not None
    assert row["left_bowl"][1] > row["middle_bowl"][1] > row["right_bowl"][1]  # left: +y
    assert row["left_bowl"][0] == row["right_bowl"][0]
    near = {m.name: m.place for m in mentions("Put the box in the far zone of the two zones.")}
    assert near["near_zone"][0] < near["far_zone"][0]  # near the robot: smaller x


def test_members_are_spaced_by_their_size_and_never_overlap() -> None:
    found = mentions("Four containers stand in a row; put the white block into the fourth one.")
    row = sorted(m.place[1] for m in found if m.place)
    width = kind_spec("container").default_size[1]
    assert len(row) == 4
    assert all(b - a > width for a, b in itertools.pairwise(row))
    assert max(abs(y) for y in row) + width / 2 <= 0.5  # on the table


def test_a_movable_group_is_picked_from_only_by_one_and_the_other() -> None:
    # "the second block" of what the robot moves is a place in a tower, not a member
    assert all(m.group is None for m in mentions(
        "Put the first block on the pallet and the second block in the bowl."))
    found = mentions("Put one cyan cylinder on the left pallet and the other cyan "
                     "cylinder on the right pallet.")
    cylinders = [m for m in found if m.kind == "cylinder"]
    assert [m.name for m in cylinders] == ["one_cyan_cylinder", "other_cyan_cylinder"]
    assert all(m.place is None for m in cylinders)
    assert goals("Put one cyan cylinder on the left pallet and the other cyan cylinder "
                 "on the right pallet.") == [
        ("on", ("one_cyan_cylinder",), "left_pallet"),
        ("on", ("other_cyan_cylinder",), "right_pallet")]


@pytest.mark.parametrize("proposal", [
    "Put one block in the bowl.",                       # "one" alone counts, picks nothing
    "Put the block in the center of the zone.",         # the centre of a zone is no member
    "First put the red block in the bowl, then the blue block.",  # a sequence word
    "Put the ball in the fourth of the three bowls.",   # a count the words give holds
    "Put the ball in the zone in the back-left corner.",  # a corner of the table
    "The first level is red, the second is blue; put the blocks in the zones.",
])
def test_words_that_pick_no_member_leave_the_group_whole(proposal: str) -> None:
    assert all(m.group is None for m in mentions(proposal))


def test_spell_out_adds_the_kind_only_where_a_group_is_large_enough() -> None:
    text = "two bowls and a block. put the block in the second."
    assert spell_out(text, mentions(text)).endswith("in the second bowl.")
    text = "a bowl and a block. put the block in the second."
    assert spell_out(text, mentions(text)) == text  # no group has a second


def test_the_reading_only_graph_places_the_row_and_reads_the_words() -> None:
    text = ("Three zones lie in a row from left to right. Put the green block in the "
            "second zone from the left.")
    found = mentions(text)
    graph = parse_graph(grounded.expand_graph(
        first_choice(grounded.compact_graph_schema(found, text)), found, "t", text))
    zones = {v.name: v for v in graph.variables if v.kind == "zone"}
    assert zones["second_zone"].initial.type == "pose"
    assert zones["first_zone"].initial.y > zones["second_zone"].initial.y \
        > zones["third_zone"].initial.y
    (factor,) = graph.factors
    assert factor.goal.anchors() == ["second_zone"]
    unread = account(text, graph).unread_words()
    assert not {"second", "left", "right"} & set(unread), unread


_WORDS = ["the", "first", "second", "third", "last", "left", "right", "middle", "near",
          "far", "one", "other", "of", "two", "three", "bowl", "bowls", "zone", "zones",
          "block", "blocks", "red", "put", "in", "on", "and", ".", "each", "every",
          "different", "evenly", "over", "cylinders", "twelve"]


@settings(max_examples=150, deadline=None)
@given(st.lists(st.sampled_from(_WORDS), max_size=25).map(" ".join))
def test_any_words_pick_members_of_a_group_or_none(text: str) -> None:
    found = mentions(text)
    assert len(found) <= 12
    names = [m.name for m in found]
    assert len(names) == len(set(names))
    for m in found:
        if m.group is not None:
            assert m.count >= 1
            group = [g for g in found if g.group == m.group]
            assert len(group) >= 2  # a group splits into two members or more
        if m.place is not None:
            assert m.group is not None and not m.movable
            assert 0.25 <= m.place[0] <= 0.75 and -0.5 <= m.place[1] <= 0.5
    read = read_goals(text, found)
    if read is not None:
        used = {n for g in read for n in (*g.objects, g.anchor) if n}
        assert used <= set(names)


@pytest.mark.parametrize(("proposal", "expected"), [
    ("Please put each of the three cylinders in a different one of the three zones.",
     [("in_zone", ("cylinder_1",), "zone_1"), ("in_zone", ("cylinder_2",), "zone_2"),
      ("in_zone", ("cylinder_3",), "zone_3")]),
    ("Split 12 blocks evenly over the 3 zones, 4 blocks in each zone.",
     [("in_zone", ("blocks_1",), "zone_1"), ("in_zone", ("blocks_2",), "zone_2"),
      ("in_zone", ("blocks_3",), "zone_3")]),
])
def test_each_member_of_a_shared_anchor_takes_its_share(proposal: str,
                                                        expected: list[tuple]) -> None:
    assert goals(proposal) == expected
    shares = [m.count for m in mentions(proposal) if m.movable]
    assert len(set(shares)) == 1  # an even split


@pytest.mark.parametrize("proposal", [
    "Put each block in the zone.",                   # one zone: nothing to share
    "Put the red and blue blocks in the zones, one in each zone.",  # coloured: the colours pair
    "Put each of the three cylinders in the bowl.",  # "each" of the movers, not the anchor
])
def test_no_share_without_one_group_that_divides_another(proposal: str) -> None:
    assert not any(m.group for m in mentions(proposal))


@pytest.mark.parametrize(("proposal", "expected"), [
    ("Put a brown box on the pallet and another brown box on top of it.",
     [("on", ("one_brown_box",), "pallet"), ("on", ("another_brown_box",), "one_brown_box")]),
    ("Place one yellow ball in the bowl and another yellow ball in the container.",
     [("inside", ("one_yellow_ball",), "bowl"),
      ("inside", ("another_yellow_ball",), "container")]),
])
def test_another_names_one_more_of_the_same(proposal: str, expected: list[tuple]) -> None:
    assert goals(proposal) == expected


def test_another_of_no_colour_is_no_member_of_a_coloured_group() -> None:
    assert all(m.group is None for m in mentions(
        "Put the red block in the bowl and another block in the zone."))
