"""The rest of a kind beside a coloured one (selectors.rest_of_kind): "the two other
cylinders", "the other two boxes, both red", "the yellow ball from among the four"."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.gen.reading.clauses import read_goals, still_objects
from factask.gen.reading.mentions import mentions


def groups(proposal: str) -> dict[str, tuple[str, str | None, int]]:
    return {m.name: (m.kind, m.color, m.count) for m in mentions(proposal)}


@pytest.mark.parametrize(("proposal", "others", "goals", "still"), [
    ("Move only the red cylinder into the zone; the two other cylinders stay put.",
     ("other_cylinders", ("cylinder", None, 2)),
     [("in_zone", ("red_cylinder",), "zone")], {"other_cylinders"}),
    ("Place the blue box in the zone and put the other two boxes, both red, on the pallet.",
     ("other_red_boxes", ("box", "red", 2)),
     [("in_zone", ("blue_box",), "zone"), ("on", ("other_red_boxes",), "pallet")], set()),
    # the four hold the yellow one: three others, left where they are
    ("Pick out the yellow ball from among the four balls and put it on the pallet.",
     ("other_balls", ("ball", None, 3)),
     [("on", ("yellow_ball",), "pallet")], {"other_balls"}),
])
def test_the_rest_of_a_kind_is_a_group_of_its_own(proposal: str, others: tuple,
                                                  goals: list, still: set) -> None:
    name, group = others
    assert groups(proposal)[name] == group
    found = mentions(proposal)
    read = read_goals(proposal, found)
    assert read is not None
    assert [(g.relation, g.objects, g.anchor) for g in read] == goals
    assert still_objects(proposal, found) == still


@pytest.mark.parametrize("proposal", [
    "Put the red block and two blocks on the pallet.",  # no "other", no "among"
    "Put the blocks in the bowl.",
])
def test_without_other_or_among_no_rest_is_read(proposal: str) -> None:
    assert not [n for n in groups(proposal) if n.startswith("other_")]


_WORDS = ["the", "red", "blue", "ball", "balls", "other", "two", "four", "among", "of",
          "from", "both", "put", "in", "on", "zone", "pallet", "and", ",", "stay", "."]


@settings(max_examples=150, deadline=None)
@given(st.lists(st.sampled_from(_WORDS), max_size=25).map(" ".join))
def test_any_words_give_a_rest_of_one_object_or_more(text: str) -> None:
    found = mentions(text)
    names = [m.name for m in found]
    assert len(names) == len(set(names))
    for m in found:
        if m.name.startswith("other_") and m.group:
            assert m.count >= 1
    read = read_goals(text, found)
    if read is not None:
        assert {n for g in read for n in (*g.objects, g.anchor) if n} <= set(names)
