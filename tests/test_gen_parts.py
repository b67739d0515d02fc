"""The reading knows microwaves (hinged doors) and stoves / lamps (switches) (issue 38,
generation), as entries of the one table of articulated kinds
(:data:`factask.gen.reading.articulated.PART_KINDS`).

Proposals written here in varied words are read with no model (the mentions, the
clause reading, the grounded one-shot grammar's first choice) into graphs whose
parts, starts, goals and order are the ones the words mean; a word the reading
cannot place is reported unread, not guessed.
"""

from __future__ import annotations

import networkx as nx
import pytest

from factask.gen.compare import _seats, compare
from factask.gen.first_choice import first_choice
from factask.gen.reading import grounded
from factask.gen.reading.accounting import account
from factask.gen.reading.describe import describe
from factask.gen.reading.mentions import mentions
from factask.graph import InCabinet, MountedOn, TaskGraph, parse_graph
from factask.library.tasks import get_task
from factask.vocabulary.kinds import door_size, kind_spec, switch_size


def read(words: str) -> TaskGraph:
    """The graph the reading makes of ``words`` (no model)."""
    found = mentions(words)
    assert grounded.applies(found), words
    schema = grounded.compact_graph_schema(found, words)
    return parse_graph(grounded.expand_graph(first_choice(schema), found, "t", words))


def goals(graph: TaskGraph) -> list[tuple[str, tuple[str, ...], tuple[str, ...]]]:
    """(type, objects, anchors) of each goal, in the graph's order."""
    return [(f.goal.type, tuple(f.goal.objects), tuple(f.goal.anchors()))
            for f in (graph.factor(n) for n in graph.factor_order())]


def before(graph: TaskGraph, a: str, b: str) -> bool:
    """Whether the goal of type ``a`` comes before the goal of type ``b``."""
    names = {graph.factor(n).goal.type: n for n in graph.factor_order()}
    return nx.has_path(graph.dependency_graph(), names[a], names[b])


def door(graph: TaskGraph) -> tuple[str, float]:
    """(microwave, opening) of the graph's one door."""
    (v,) = [v for v in graph.variables if v.kind == "door"]
    assert isinstance(v.initial, InCabinet) and v.initial.level == 0
    return v.initial.cabinet, v.initial.opening


def switches(graph: TaskGraph) -> dict[str, tuple[str, bool]]:
    """Switch -> (its host, whether it starts on)."""
    return {v.name: (v.initial.host, v.initial.on) for v in graph.variables
            if isinstance(v.initial, MountedOn)}


@pytest.mark.parametrize("words", ["open the microwave", "Open the microwave door.",
                                   "swing the microwave's door open"])
def test_opening_a_microwave_makes_its_door_shut_at_the_start(words: str) -> None:
    g = read(words)
    assert door(g) == ("microwave", 0.0)
    assert goals(g) == [("open", ("door",), ())]
    size = g.variable("microwave").size or kind_spec("microwave").default_size
    assert tuple(g.variable("door").size) == pytest.approx(door_size(tuple(size)))
    assert account(words, g).complete


@pytest.mark.parametrize("words", ["Shut the microwave.", "close the microwave door"])
def test_closing_a_microwave_starts_its_door_open(words: str) -> None:
    g = read(words)
    assert door(g) == ("microwave", 1.0)
    assert goals(g) == [("closed", ("door",), ())]


def test_put_the_mug_into_the_microwave_and_close_it_opens_it_first() -> None:
    words = "put the mug into the microwave and close it"
    g = read(words)
    assert door(g) == ("microwave", 0.0)
    assert goals(g) == [("open", ("door",), ()), ("inside", ("cylinder",), ("microwave",)),
                        ("closed", ("door",), ())]
    assert before(g, "open", "inside") and before(g, "inside", "closed")
    assert account(words, g).complete


def test_a_microwave_said_open_is_not_opened_again() -> None:
    g = read("The white microwave is open; put the red bowl inside it and shut it.")
    assert door(g) == ("white_microwave", 1.0)
    assert goals(g) == [("inside", ("red_bowl",), ("white_microwave",)),
                        ("closed", ("door",), ())]
    assert before(g, "inside", "closed")
    assert g.variable("white_microwave").color == "white"


def test_open_the_microwave_and_put_the_bowl_inside_puts_it_in_the_microwave() -> None:
    g = read("open the gray microwave and put the blue bowl inside")
    assert goals(g) == [("open", ("door",), ()), ("inside", ("blue_bowl",), ("gray_microwave",))]


@pytest.mark.parametrize("words", ["turn on the stove", "Switch on the stove burner.",
                                   "turn the stove on", "press the stove's switch"])
def test_switching_a_stove_on_makes_its_switch_off_at_the_start(words: str) -> None:
    g = read(words)
    assert switches(g) == {"switch": ("stove", False)}
    assert goals(g) == [("switched_on", ("switch",), ())]
    assert tuple(g.variable("switch").size) == pytest.approx(switch_size("stove"))
    assert account(words, g).complete


@pytest.mark.parametrize("words", ["switch off the lamp", "the lamp is on, turn it off"])
def test_switching_a_lamp_off_starts_its_switch_on(words: str) -> None:
    g = read(words)
    assert switches(g) == {"switch": ("lamp", True)}
    assert goals(g) == [("switched_off", ("switch",), ())]
    assert tuple(g.variable("switch").size) == pytest.approx(switch_size("lamp"))


def test_turn_on_the_stove_then_put_the_pot_on_it() -> None:
    g = read("turn on the black stove, then put the pot on it")
    assert switches(g) == {"switch": ("black_stove", False)}
    assert goals(g) == [("switched_on", ("switch",), ()), ("on", ("bowl",), ("black_stove",))]
    assert before(g, "switched_on", "on")


def test_put_a_block_on_the_stove_then_switch_it_on() -> None:
    g = read("put the red block on the white stove, then switch it on")
    assert goals(g) == [("on", ("red_block",), ("white_stove",)),
                        ("switched_on", ("switch",), ())]
    assert before(g, "on", "switched_on")


def test_two_hosts_of_different_kinds_each_switched() -> None:
    g = read("turn on the red stove and the lamp")
    assert switches(g) == {"red_stove_switch": ("red_stove", False),
                           "lamp_switch": ("lamp", False)}
    assert sorted(goals(g)) == [("switched_on", ("lamp_switch",), ()),
                                ("switched_on", ("red_stove_switch",), ())]


@pytest.mark.parametrize(("words", "unread"), [
    ("open the left microwave door", "left"),  # one door: no side to name
    ("open the top door of the microwave", "top"),  # one door: no level either
])
def test_words_the_reading_cannot_place_are_reported(words: str, unread: str) -> None:
    assert unread in account(words, read(words)).unread_words()


@pytest.mark.parametrize(("name", "words"), [
    ("open-microwave", "open the gray microwave"),
    ("put-bowl-in-microwave-and-close-it", "open the gray microwave, then put the blue bowl "
     "into the gray microwave, then close the gray microwave"),
    ("turn-on-stove", "turn on the gray stove"),
    ("turn-on-lamp", "turn on the yellow lamp"),
    ("turn-on-stove-and-put-pot-on-it", "turn on the gray stove, then put the blue bowl onto "
     "the gray stove"),
])
def test_describe_names_a_lone_part_by_its_host(name: str, words: str) -> None:
    assert describe(get_task(name)) == words


def test_the_metric_labels_a_switch_on_or_off_and_a_door_open_or_shut() -> None:
    assert _seats(get_task("turn-on-stove")) == {"stove_switch": "level 1 of 1, off"}
    assert _seats(get_task("turn-off-stove")) == {"stove_switch": "level 1 of 1, on"}
    assert _seats(get_task("close-microwave")) == {"microwave_door": "level 1 of 1, open"}
    # a switch that starts on is not one that starts off
    on = get_task("turn-off-stove")
    off = get_task("turn-on-stove")
    assert not compare(on, off).equivalent


def test_hosts_past_the_bound_on_mentions_are_left_out_with_their_parts() -> None:
    from factask.gen.reading.group_counts import MAX_SPLIT_MENTIONS

    found = mentions("BLOCK:STOVE:CABINET:ORANGE:BLUE:RED:GREEN:CABINET")
    assert len(found) <= MAX_SPLIT_MENTIONS
    names = {m.name for m in found}
    hosts = {m.name for m in found if m.kind in ("stove", "cabinet")}
    seated = {v for m in found for k, v in m.start if k in ("host", "cabinet")}
    assert seated == hosts and seated <= names  # every host kept has its part, and only those
