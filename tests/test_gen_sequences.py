"""Colour sequences that repeat colours (factask.gen.reading.sequences)."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.gen.reading.clauses import read_goals
from factask.gen.reading.mentions import mentions


def colours_of(proposal: str) -> list[tuple[str, bool]]:
    found = mentions(proposal)
    by_name = {m.name: m for m in found}
    out = read_goals(proposal, found)
    assert out is not None and len(out) == 1, out
    return [str(by_name[n].color) for n in out[0].objects], out[0].ordered


@pytest.mark.parametrize(("proposal", "expected"), [
    ("Pick up six blocks in two colors (three red and three blue) and stack them in "
     "alternating colors on the pallet. The tower should start with a red block at the "
     "bottom.", ["red", "blue"] * 3),
    ("Stack three blue and three yellow blocks into a tower, alternating the colours, with "
     "a yellow block at the bottom.", ["yellow", "blue"] * 3),
    ("Construct a tower using six blocks: two red, two blue, and two green. The tower "
     "should be built in the order of a red block at the base, followed by a blue, then "
     "green, then red, blue and green at the top.", ["red", "blue", "green"] * 2),
    # one more of the first colour: it starts and ends the row
    ("Line up three white and two black cylinders in a row, alternating colours.",
     ["white", "black", "white", "black", "white"]),
])
def test_a_repeating_sequence_orders_the_members(proposal: str, expected: list[str]) -> None:
    assert colours_of(proposal) == (expected, True)


@pytest.mark.parametrize("proposal", [
    "Stack the red blocks and the blue blocks on the pallet.",  # no sequence asked
    "Line up four white and one black cylinders in a row, alternating colours.",  # 4 vs 1
    "Stack two red and two blue blocks, in the order red, blue.",  # names fewer
])
def test_without_a_sequence_over_every_member_the_groups_stay_whole(proposal: str) -> None:
    assert all(m.group is None for m in mentions(proposal))


_WORDS = ["stack", "three", "two", "red", "blue", "green", "blocks", "block", "and",
          "alternating", "colours", "order", "then", "followed", "by", "bottom", "top", "a",
          "in", "row", "on", "the", "pallet", ",", "."]


@settings(max_examples=150, deadline=None)
@given(st.lists(st.sampled_from(_WORDS), max_size=30).map(" ".join))
def test_any_words_split_groups_into_all_their_members_or_none(text: str) -> None:
    found = mentions(text)
    assert len(found) <= 12
    groups: dict[str, list] = {}
    for m in found:
        if m.group is not None and m.name.rsplit("_", 1)[-1].isdigit():
            groups.setdefault(m.group, []).append(m)
    for members in groups.values():
        assert [m.rank for m in members] == list(range(len(members)))
        assert len({m.color for m in members}) == 1
    read = read_goals(text, found)
    if read is not None:
        names = {m.name for m in found}
        for g in read:
            assert set(g.objects) <= names
