"""A bridge: one object laid across a pair the robot moves (goal_order.bridged), the
deck words (words.DECK_WORDS) and the joint layout check (capacity.prune)."""

from __future__ import annotations

import pytest

from factask.gen.first_choice import first_choice
from factask.gen.reading import grounded
from factask.gen.reading.clauses import read_goals
from factask.gen.reading.mentions import mentions
from factask.gen.reading.words import DECK_SIZE


@pytest.mark.parametrize("proposal", [
    "Stand the two red blocks apart, then lay the green log across them.",
    "Make a bridge: stand the two short cylinders apart first, then lay the long bar "
    "across them.",
    "Put the green log on top of the two red blocks.",
])
def test_the_pair_under_a_bridge_stands_in_a_row_first(proposal: str) -> None:
    found = mentions(proposal)
    read = read_goals(proposal, found)
    assert read is not None
    row, deck = read
    assert row.relation == "row" and deck.relation == "on"
    assert deck.anchor == row.objects[0] and row.step < deck.step
    graph = grounded.expand_graph(first_choice(grounded.compact_graph_schema(found, proposal)),
                                  found, "bridge", proposal)
    goals = [f["goal"] for f in graph["factors"]]
    assert [g["type"] for g in goals] == ["row", "on"]  # laid out together, not dropped
    assert goals[1]["support"] == goals[0]["objects"][0]


def test_a_bar_is_a_long_flat_box() -> None:
    (bar,) = [m for m in mentions("lay the plank across the two cylinders") if m.kind == "box"]
    assert bar.size == DECK_SIZE and DECK_SIZE[0] > 2 * DECK_SIZE[1]


def test_a_pair_already_arranged_gets_no_second_row() -> None:
    text = "Line up the two red blocks in a row, then put the green log on top of them."
    read = read_goals(text, mentions(text))
    assert read is not None
    assert sum(g.relation == "row" for g in read) == 1
