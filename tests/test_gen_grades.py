"""Sizes that tell alike objects apart (factask.gen.reading.grades) and the meaning
metric's sizes (factask.gen.compare)."""

from __future__ import annotations

import copy

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.gen.compare import compare
from factask.gen.first_choice import first_choice
from factask.gen.reading import grounded
from factask.gen.reading.accounting import account
from factask.gen.reading.clauses import read_goals, still_objects
from factask.gen.reading.mentions import mentions
from factask.graph.taskgraph import parse_graph
from factask.vocabulary.kinds import kind_spec


def goals(proposal: str) -> list[tuple[str, tuple[str, ...], str | None]]:
    out = read_goals(proposal, mentions(proposal))
    assert out is not None, proposal
    return [(g.relation, g.objects, g.anchor) for g in out]


def graph_of(proposal: str) -> dict:
    found = mentions(proposal)
    schema = grounded.compact_graph_schema(found, proposal)
    return grounded.expand_graph(first_choice(schema), found, "graded", proposal)


@pytest.mark.parametrize(("proposal", "expected"), [
    ("Put the small ball in the small bowl and the large ball in the large bowl.",
     [("inside", ("small_ball",), "small_bowl"), ("inside", ("large_ball",), "large_bowl")]),
    ("Stand the tall cylinder in the container and the short cylinder on the pallet.",
     [("inside", ("tall_cylinder",), "container"), ("on", ("short_cylinder",), "pallet")]),
    ("Set the little red cube on top of the big red cube.",
     [("on", ("small_red_block",), "large_red_block")]),
    # a grade standing for its object ("a small one"), and "the other" of a graded pair
    ("There are two grey boxes, a small one and a large one. Put the small box inside the "
     "container and the other box on the pallet.",
     [("inside", ("small_gray_box",), "container"), ("on", ("large_gray_box",), "pallet")]),
])
def test_a_grade_picks_one_of_alike_objects(proposal: str, expected: list[tuple]) -> None:
    assert goals(proposal) == expected


def test_each_grade_has_its_size_from_the_kinds_default() -> None:
    found = {m.name: m for m in mentions(
        "Put the small ball in the small bowl and the large ball in the large bowl.")}
    ball = kind_spec("ball").default_size
    assert found["small_ball"].size == pytest.approx([0.75 * d for d in ball])
    assert found["large_ball"].size == pytest.approx([1.5 * d for d in ball])
    tall, short = (m.size for m in mentions("the tall cylinder and the short cylinder"))
    assert tall[2] > kind_spec("cylinder").default_size[2] > short[2]
    assert tall[:2] == short[:2]  # height only
    long_, short = (m.size for m in mentions("a long log and a short log"))
    assert long_[0] > short[0] and long_[2] == short[2]  # short against long: length


def test_the_grade_left_alone_stays_still() -> None:
    text = "Put only the large box on the pallet; do not move the small one."
    assert goals(text) == [("on", ("large_box",), "pallet")]
    assert still_objects(text, mentions(text)) == {"small_box"}


@pytest.mark.parametrize("proposal", [
    "Lay the long bar across the two short cylinders.",  # nothing contrasts
    "Put the small ball in the bowl.",
    "Put five small boxes and a large box on the pallet, then the large one in the zone.",
])
def test_a_grade_that_contrasts_with_nothing_splits_nothing(proposal: str) -> None:
    found = mentions(proposal)
    kinds = [m.kind for m in found]
    assert len(kinds) == len(set(kinds)) or all(m.grade for m in found if m.kind == "box")
    if "five small boxes" in proposal:
        boxes = [m for m in found if m.kind == "box"]
        assert sum(m.count for m in boxes) == 6 or len(boxes) == 1


def test_a_counted_group_shares_its_count_over_its_grades() -> None:
    found = {m.name: m for m in mentions(
        "Four red blocks lie on the table, two small ones and two large ones. Stack the "
        "large red blocks on the pallet.")}
    assert found["small_red_blocks"].count == found["large_red_blocks"].count == 2


def test_the_graded_graph_is_the_task_and_its_size_words_are_read() -> None:
    text = "Put the small ball in the small bowl and the large ball in the large bowl."
    graph = graph_of(text)
    sizes = {v["name"]: v["size"] for v in graph["variables"]}
    assert sizes["small_ball"][0] < sizes["large_ball"][0]
    assert not [w for w in account(text, parse_graph(graph)).unread
                if w.category == "size"]


def test_swapped_sizes_are_another_task() -> None:
    text = "Put the small ball in the small bowl and the large ball in the large bowl."
    graph = graph_of(text)
    assert compare(graph, graph, text).equivalent
    swapped = copy.deepcopy(graph)
    other = {"small_bowl": "large_bowl", "large_bowl": "small_bowl"}
    for factor in swapped["factors"]:  # the small ball into the large bowl, and back
        factor["goal"]["container"] = other[factor["goal"]["container"]]
        factor["scope"] = [other.get(n, n) for n in factor["scope"]]
    result = compare(swapped, graph, text)
    assert not result.equivalent
    same_size = copy.deepcopy(graph)
    for v in same_size["variables"]:
        if v["kind"] == "ball":
            v["size"] = None  # both the kind's default: two balls of one size
    assert not compare(same_size, graph, text).equivalent
    # without size words, sizes are details
    assert compare(same_size, graph, "put each ball in a bowl").equivalent


_WORDS = ["the", "a", "small", "large", "big", "little", "tall", "short", "long", "one",
          "ones", "other", "red", "two", "four", "ball", "balls", "bowl", "boxes", "box",
          "put", "in", "on", "and", ".", "pallet", "cylinder"]


@settings(max_examples=150, deadline=None)
@given(st.lists(st.sampled_from(_WORDS), max_size=25).map(" ".join))
def test_any_words_grade_alike_objects_or_leave_them_whole(text: str) -> None:
    found = mentions(text)
    assert len(found) <= 12
    names = [m.name for m in found]
    assert len(names) == len(set(names))
    for m in found:
        if m.grade is not None:
            assert m.size is not None and min(m.size) > 0
            alike = [g for g in found if g.kind == m.kind and g.color == m.color]
            assert len({g.grade for g in alike}) >= 2  # graded only against another
    read = read_goals(text, found)
    if read is not None:
        used = {n for g in read for n in (*g.objects, g.anchor) if n}
        assert used <= set(names)


@pytest.mark.parametrize(("proposal", "expected"), [
    ("Place the large box and the small box along the line, the large box first.",
     [("row", ("large_box", "small_box"), "line", True)]),
    # superlatives standing alone over a counted group: its ends, the third between
    ("Build a tower of three boxes from the largest at the bottom to the smallest on top.",
     [("stack", ("large_box", "medium_box", "small_box"), None, True)]),
    ("Build a tower of three boxes from the smallest at the bottom to the largest on top.",
     [("stack", ("small_box", "medium_box", "large_box"), None, True)]),
])
def test_the_words_order_alike_objects_by_size(proposal: str, expected: list) -> None:
    out = read_goals(proposal, mentions(proposal))
    assert out is not None
    assert [(g.relation, g.objects, g.anchor, g.ordered) for g in out] == expected
