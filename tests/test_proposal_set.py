"""The proposal set: task proposals in plain English with hand-built reference graphs.

``tests/data/proposals.json`` holds task proposals written for factask (none of them
one of the 192 of ``factask/data/gensim_tasks.json``), each with a ``reference``: the
graph its words mean, as ``TaskGraph.to_json()`` writes it, and ``phrase_kinds``: the
kinds of phrase it exercises (:data:`PHRASE_KINDS`). ``load_tasks`` reads the file as
a benchmark task list (it ignores ``phrase_kinds``), so ``factask benchmark --tasks``
scores the *faithful* rate on it.

Checked here: the size of the set, no overlap with the 192 (names, and descriptions
after lowercasing and normalising whitespace, nor a near copy), every reference a valid
task graph that compiles and resets, every phrase kind documented and used by at least
:data:`MIN_PER_KIND` proposals, and every kind a proposal lists backed by its words
(and, where the graph can show it, by its graph).
"""

from __future__ import annotations

import difflib
import json
import re
from collections import Counter
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from factask.evaluation.benchmark import BenchTask, default_tasks_path, load_tasks
from factask.gen.compare import colours_named
from factask.graph import TaskGraph, parse_graph
from factask.sim.build.compile import compile_graph
from factask.sim.layout.reset import reset_layout
from factask.vocabulary.palette import COLOR_NAMES

DATA = Path(__file__).parent / "data" / "proposals.json"
ORIGIN = "factask-proposal-set"
MIN_PROPOSALS = 150
MIN_PER_KIND = 10
#: A description at least this similar (difflib ratio, lowercased) to one of the 192 is
#: a near copy.
NEAR_COPY = 0.75

#: The documented kinds of phrase, with what each covers.
PHRASE_KINDS: dict[str, str] = {
    "colour_count_groups": "groups named by count and colour: 'four red and four white flat "
                           "boxes', 'two blue blocks and three green ones'",
    "plural_colour_groups": "groups named by colour alone: 'the blue blocks ... the green "
                            "blocks'",
    "ordinals": "first / second / third / fourth / last: of bowls in a row, of a tower's "
                "blocks, of steps",
    "another_other": "'another brown box', 'the other cylinder', 'the other two boxes'",
    "shapes_of_many": "staircases, rings and circles, rows and lines, pyramids, towers and "
                      "columns, bridges, walls, squares, grids, checkerboards, plus signs",
    "sides_and_regions": "left / right half of the table, front / back (near / far from the "
                         "robot), its corners, centre and edges, zones placed there",
    "quantifiers": "each / every / all / both / same colour / different colours / matching",
    "relations": "in, into, on top of, next to, beside, between, aligned with, along a line, "
                 "stacked, inside a zone, around, across, sorted by colour",
    "counts": "numbers, as words and as digits",
    "distractors": "objects in the scene that no goal moves",
    "negation": "'do not move', 'leave ... where it is', 'not the red one', 'only'",
    "order_words": "first ... then, after that, before, finally, one at a time",
    "sizes": "small / large / tall / short / flat / long / big / little",
    "initial_state": "where things start: stacked, in a bowl, on a pallet, on one side",
    "milestones": "states passed through on the way: 'put it in the red bowl, then move it "
                  "on to the blue bowl'",
    "politeness": "please, could you, would you, kindly",
    "british_spelling": "colour, centre, grey (and their American forms elsewhere)",
}

_COLOURS = "|".join(sorted({*COLOR_NAMES, "grey"}, key=len, reverse=True))
#: Counts (not "one": "the other one", "one of the bowls" count nothing).
_NUMBER = r"(?:\d+|two|three|four|five|six|seven|eight|nine|ten|eleven|twelve)"
#: Words a proposal listed under a kind must contain (one way: a kind is listed only
#: where its words are).
CUES: dict[str, re.Pattern[str]] = {k: re.compile(v, re.IGNORECASE) for k, v in {
    "plural_colour_groups": rf"\b(?:{_COLOURS}) (?:blocks|balls|cylinders|boxes|cubes|ells|"
                            r"pillars|ones)\b",
    "ordinals": r"\b(?:first|second|third|fourth|last)\b",
    "another_other": r"\b(?:another|other)\b",
    "shapes_of_many": r"\b(?:stair\w*|steps?|ring|circle|line|row|pyramid|towers?|stack\w*|"
                      r"bridges?|wall|square|grid|checkerboard|plus sign|columns?|pile)\b",
    "sides_and_regions": r"\b(?:left|right|front|back|near|far|corners?|centre|center|middle|"
                         r"half|edge|side)\b",
    "quantifiers": r"\b(?:each|every|all|both|same|share|different|matching|matches|own)\b",
    "relations": r"\b(?:in|into|inside|within|on|onto|next to|beside|between|align\w*|"
                 r"along|line|stack\w*|sort\w*|across|around|slot|fit|insert|fill|from)\b",
    "negation": r"\b(?:not|don't|without|leave|keeping|only|stays?|alone|bare)\b",
    "order_words": r"\b(?:first|then|after|afterwards|before|finally|once|in turn|one at a "
                   r"time|in (?:this|that) order)\b",
    "initial_state": r"\b(?:starts?|already|holds|sits|stands?|is in|out of|from)\b",
}.items()}
#: Kinds listed exactly where these words are (both ways).
EXACT_CUES: dict[str, re.Pattern[str]] = {k: re.compile(v, re.IGNORECASE) for k, v in {
    "counts": rf"\b{_NUMBER}\b|\b\d+x\d+\b|\ba single\b",
    "sizes": r"\b(?:small|large|tall|short|flat|long|big|little|largest|smallest)\b",
    "politeness": r"\b(?:please|could you|would you|kindly)\b",
    "british_spelling": r"\b(?:colours?|centred?|grey)\b",
}.items()}
#: "four red ... two white ...": a count before a colour, at least twice.
_COUNTED_COLOUR = re.compile(rf"\b(?:{_NUMBER}|one|a single)\s+(?:flat\s+)?(?:{_COLOURS})\b",
                             re.IGNORECASE)


@cache
def _raw() -> tuple[dict[str, Any], ...]:
    return tuple(json.loads(DATA.read_text()))


@cache
def _tasks() -> tuple[BenchTask, ...]:
    return tuple(load_tasks(DATA))


@cache
def _graph(name: str) -> TaskGraph:
    task = next(t for t in _tasks() if t.name == name)
    assert isinstance(task.reference, dict), f"{name}: reference is not a graph dict"
    return parse_graph(task.reference)


def _names() -> list[str]:
    return [t.name for t in _tasks()]


def _normal(text: str) -> str:
    return " ".join(text.lower().split())


def test_the_set_is_a_task_list_that_load_tasks_reads() -> None:
    tasks = _tasks()
    assert len(tasks) >= MIN_PROPOSALS
    names = [t.name for t in tasks]
    assert len(set(names)) == len(names), [n for n, k in Counter(names).items() if k > 1]
    descriptions = [_normal(t.description) for t in tasks]
    assert len(set(descriptions)) == len(descriptions)
    for t in tasks:
        assert re.fullmatch(r"[a-z0-9]+(?:-[a-z0-9]+)*", t.name), t.name
        assert t.description.strip(), t.name
        assert t.origin == ORIGIN, t.name
        assert isinstance(t.reference, dict), t.name
    assert [e["name"] for e in _raw()] == names


def test_no_proposal_is_one_of_the_192() -> None:
    theirs = load_tasks(default_tasks_path())
    assert len(theirs) == 192
    their_names = {t.name.lower() for t in theirs}
    their_texts = [_normal(t.description) for t in theirs]
    for t in _tasks():
        assert t.name.lower() not in their_names, t.name
        mine = _normal(t.description)
        assert mine not in their_texts, t.name
        matcher = difflib.SequenceMatcher(None, mine)
        for text in their_texts:
            matcher.set_seq1(text)
            if matcher.real_quick_ratio() >= NEAR_COPY and matcher.quick_ratio() >= NEAR_COPY:
                assert matcher.ratio() < NEAR_COPY, f"{t.name} nearly copies {text!r}"


@pytest.mark.parametrize("name", _names())
def test_every_reference_is_a_valid_task_graph_of_its_proposal(name: str) -> None:
    graph = _graph(name)
    assert graph.problems() == []
    assert graph.task_problems() == []
    task = next(t for t in _tasks() if t.name == name)
    assert graph.name == task.name
    assert graph.description == task.description
    # Every colour the words name is a colour of the graph (nothing named is left out).
    assert colours_named(task.description) <= {v.color for v in graph.variables}


def test_every_phrase_kind_is_documented_and_has_ten_proposals() -> None:
    counts: Counter[str] = Counter()
    for entry in _raw():
        kinds = entry.get("phrase_kinds")
        assert isinstance(kinds, list) and kinds, entry["name"]
        assert len(set(kinds)) == len(kinds), entry["name"]
        unknown = set(kinds) - set(PHRASE_KINDS)
        assert not unknown, f"{entry['name']}: undocumented phrase kinds {sorted(unknown)}"
        counts.update(kinds)
    few = {k: counts[k] for k in PHRASE_KINDS if counts[k] < MIN_PER_KIND}
    assert not few, f"phrase kinds with fewer than {MIN_PER_KIND} proposals: {few}"


def _moved(graph: TaskGraph) -> set[str]:
    return {name for f in graph.factors for name in f.goal.objects}


def _mentioned(graph: TaskGraph) -> set[str]:
    return {name for f in graph.factors for name in (f.scope or [])} | _moved(graph)


def test_every_listed_kind_is_backed_by_the_words_and_the_graph() -> None:
    wrong: list[str] = []
    for entry in _raw():
        name, words, kinds = entry["name"], entry["description"], set(entry["phrase_kinds"])
        graph = _graph(name)
        for kind, cue in CUES.items():
            if kind in kinds and not cue.search(words):
                wrong.append(f"{name}: listed as {kind}, but no word of it")
        for kind, cue in EXACT_CUES.items():
            if (kind in kinds) != bool(cue.search(words)):
                wrong.append(f"{name}: {kind} listed {kind in kinds}, words say "
                             f"{bool(cue.search(words))}")
        if "colour_count_groups" in kinds and len(_COUNTED_COLOUR.findall(words)) < 2:
            wrong.append(f"{name}: listed as colour_count_groups, but fewer than two counted "
                         "colours")
        has_milestone = any(f.milestone for f in graph.factors)
        if ("milestones" in kinds) != has_milestone:
            wrong.append(f"{name}: milestones listed {'milestones' in kinds}, graph has "
                         f"{has_milestone}")
        has_after = any(f.after for f in graph.factors)
        if ("order_words" in kinds) != has_after:
            wrong.append(f"{name}: order_words listed {'order_words' in kinds}, explicit order "
                         f"in the graph {has_after}")
        if "distractors" in kinds and not {v.name for v in graph.variables} - _mentioned(graph):
            wrong.append(f"{name}: listed as distractors, but every object is in a goal")
        if "initial_state" in kinds and not any(
                v.initial.type in ("on", "inside", "region") and not v.is_fixed
                for v in graph.variables):
            wrong.append(f"{name}: listed as initial_state, but everything starts anywhere")
    assert not wrong, "\n".join(wrong)


def test_every_reference_compiles_and_resets() -> None:
    failed = []
    for name in _names():
        graph = _graph(name)
        try:
            compile_graph(graph)
            reset_layout(graph, np.random.default_rng(0))
        except Exception as exc:  # collect every failure, report them all
            failed.append(f"{name}: {type(exc).__name__}: {exc}")
    assert not failed, "\n".join(failed)
