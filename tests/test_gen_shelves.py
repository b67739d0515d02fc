"""The reading knows a stepped shelf's levels (issue 38, generation).

A shelf's levels are one entry of the reading's table of furniture parts
(:data:`~factask.gen.reading.articulated.SHELF_LEVELS`): proposals in varied words
("the top shelf", "the lower level of the shelf", "the upper one", "off the shelf")
are read with no model into graphs whose levels, starts and goals are the ones the
words mean; a level no shelf has is reported unread, not guessed.
"""

from __future__ import annotations

import pytest
from test_gen_drawers import goals, read

from factask.gen.compare import _seats
from factask.gen.reading.accounting import account
from factask.gen.reading.articulated import PART_KINDS
from factask.gen.reading.describe import describe
from factask.gen.reading.mentions import mentions
from factask.gen.reading.words import words_of
from factask.library.tasks import get_task
from factask.vocabulary.kinds import kind_spec, shelf_level_size

SHELF = kind_spec("shelf").default_size


def levels(graph) -> dict[str, tuple[str, int]]:
    """Level variable -> (shelf, level)."""
    return {v.name: (v.initial.cabinet, v.initial.level)
            for v in graph.variables if v.kind == "shelf_level"}


def start(graph, name: str) -> dict:
    return graph.variable(name).initial.model_dump(exclude_none=True, exclude={"yaw_deg"})


TWO = {"lower_shelf_level": ("shelf", 0), "upper_shelf_level": ("shelf", 1)}
THREE = {"lower_shelf_level": ("shelf", 0), "middle_shelf_level": ("shelf", 1),
         "upper_shelf_level": ("shelf", 2)}


@pytest.mark.parametrize(("words", "want_levels", "want_goals"), [
    ("put the red block on the top shelf", TWO,
     [("on", ("red_block",), ("upper_shelf_level",))]),
    ("set the ball on the upper step of the shelf", TWO,
     [("on", ("ball",), ("upper_shelf_level",))]),
    ("put the green block on the second level of the shelf", TWO,
     [("on", ("green_block",), ("upper_shelf_level",))]),
    ("put the red cube on the middle shelf and the blue cube on the bottom shelf", THREE,
     [("on", ("red_block",), ("middle_shelf_level",)),
      ("on", ("blue_block",), ("lower_shelf_level",))]),
])
def test_a_level_named_in_words_is_the_goal_support(words, want_levels, want_goals) -> None:
    g = read(words)
    assert levels(g) == want_levels
    assert goals(g) == want_goals
    assert account(words, g).complete, [str(w) for w in account(words, g).unread]


def test_a_coloured_shelf_and_its_bottom_level() -> None:
    words = "Place the blue bowl onto the bottom level of the brown shelf."
    g = read(words)
    assert levels(g) == {"lower_shelf_level": ("brown_shelf", 0),
                         "upper_shelf_level": ("brown_shelf", 1)}
    assert goals(g) == [("on", ("blue_bowl",), ("lower_shelf_level",))]
    assert account(words, g).complete


def test_a_shelf_with_three_levels_counted() -> None:
    words = "put the two blue blocks on the uppermost shelf of the gray shelf with three levels"
    g = read(words)
    assert len(levels(g)) == 3
    assert goals(g) == [("on", ("blue_blocks",), ("upper_shelf_level",))]
    assert account(words, g).complete


def test_moved_from_the_lower_shelf_to_the_upper_one_starts_on_it() -> None:
    words = "move the green block from the lower shelf to the upper one"
    g = read(words)
    assert levels(g) == TWO
    assert start(g, "green_block") == {"type": "on", "support": "lower_shelf_level"}
    assert goals(g) == [("on", ("green_block",), ("upper_shelf_level",))]
    assert account(words, g).complete


def test_taken_off_the_shelf_it_starts_on_its_level() -> None:
    words = "take the yellow block off the shelf and put it in the green zone"
    g = read(words)
    assert levels(g) == {"shelf_level": ("shelf", 0)}
    assert start(g, "yellow_block") == {"type": "on", "support": "shelf_level"}
    assert goals(g) == [("in_zone", ("yellow_block",), ("green_zone",))]
    g = read("take the blue block off the upper level of the shelf and put it into the box")
    assert start(g, "blue_block") == {"type": "on", "support": "upper_shelf_level"}


def test_levels_start_in_their_shelf_with_their_sizes() -> None:
    g = read("put the red cube on the middle shelf and the blue cube on the bottom shelf")
    for v in g.variables:
        if v.kind == "shelf_level":
            assert v.initial.type == "in_cabinet" and v.initial.opening == 0.0
            assert v.size == pytest.approx(shelf_level_size(SHELF, 3, v.initial.level))


def test_the_fourth_shelf_is_reported_unread() -> None:
    words = "put the block on the fourth shelf"
    assert "fourth" in account(words, read(words)).unread_words()


def test_a_level_word_with_no_shelf_is_no_shelf_level() -> None:
    # "the top level of the pyramid": no shelf is named, so no level is made.
    assert "shelflevel" not in words_of("build a pyramid and put the red block on the top level")
    assert not any(m.kind == "shelf_level" for m in mentions("put the block on the top level"))


def test_describe_tells_the_shelf_tasks_in_plain_words() -> None:
    assert describe(get_task("put-block-on-upper-shelf-level")) == \
        "put the red block onto the upper level of the brown shelf"
    assert describe(get_task("take-block-off-shelf-into-zone")) == \
        "take the blue block off the upper level of the brown shelf and put it into the " \
        "green zone"


def test_the_metric_labels_a_level_by_its_level() -> None:
    seats = _seats(get_task("put-blocks-on-two-shelf-levels"))
    assert seats == {"lower_level": "level 1 of 2", "upper_level": "level 2 of 2"}
    assert PART_KINDS["shelf_level"].host == "shelf"
