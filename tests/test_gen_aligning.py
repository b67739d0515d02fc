"""Into a fixture or a corner marker the words mean alignment, in the mode the
reference's kind asks, on the grammar's path as on the stated one."""

from __future__ import annotations

import pytest

from factask.gen.first_choice import first_choice
from factask.gen.reading import grounded
from factask.gen.reading.clauses import read_goals
from factask.gen.reading.mentions import mentions
from factask.relations.aligned import ALIGNING_KINDS, modes_for


def first_goals(proposal: str) -> list[dict]:
    found = mentions(proposal)
    schema = grounded.compact_graph_schema(found, proposal)
    graph = grounded.expand_graph(first_choice(schema), found, "aligning", proposal)
    return [f["goal"] for f in graph["factors"]]


def test_a_corner_marker_asks_corner_to_corner_first() -> None:
    assert modes_for("corner")[0] == "corner"
    assert modes_for("fixture")[0] == "center"
    assert modes_for("holed_box") == ("hole",)
    assert {"fixture", "corner", "kit", "holed_box"} == ALIGNING_KINDS


@pytest.mark.parametrize(("proposal", "mode"), [
    # the words state no goal the clause reading can place (a scene sentence between):
    # the grammar's first choice is the aligned goal, corner to corner into a corner
    ("Four blocks (red, blue, green, yellow) wait beside four corners of matching "
     "colours; each block belongs in its corner.",
     "corner"),
])
def test_the_grammar_offers_alignment_into_aligning_kinds_first(proposal: str,
                                                                mode: str) -> None:
    assert read_goals(proposal, mentions(proposal)) is None  # the grammar's path
    goals = first_goals(proposal)
    assert goals and all(g["type"] == "aligned" and g["mode"] == mode for g in goals)


def test_matching_words_between_a_preposition_and_its_kind_word() -> None:
    text = ("Pick up four blocks (red, blue, green, yellow) and insert them into four "
            "color-coded fixtures.")
    read = read_goals(text, mentions(text))
    assert read is not None
    assert [(g.relation, g.objects, g.anchor) for g in read] == [
        ("aligned", (f"{c}_block",), f"{c}_fixture") for c in ("red", "blue", "green",
                                                                 "yellow")]


@pytest.mark.parametrize(("proposal", "anchor"), [
    ("There are four balls and four corners of different colors (red, blue, green, and "
     "yellow). Place each ball in the corner of the same color.", "corner"),
])
def test_the_corner_of_a_colour_is_a_corner_marker(proposal: str, anchor: str) -> None:
    read = read_goals(proposal, mentions(proposal))
    assert read is not None and read
    assert all(g.relation == "aligned" and g.anchor and g.anchor.endswith(anchor)
               for g in read)
