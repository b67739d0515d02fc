"""Prompt templates, the vocabulary rendered from code, examples and memory."""

from __future__ import annotations

import pytest

from factask.gen.answers.examples import Example, overlap, template_examples, top_k, words
from factask.gen.demo import demo_graph
from factask.gen.memory import SubtaskMemory
from factask.gen.prompts import (
    STEP_TEMPLATES,
    PromptError,
    load_template,
    placeholders,
    render,
    vocabulary,
)
from factask.graph import ASSET_KINDS, COLOR_NAMES, RELATION_TYPES, extract_fragment, parse_graph


def test_every_step_has_a_template_with_a_step_line_after_its_fixed_part() -> None:
    import re

    for step in STEP_TEMPLATES:
        text = load_template(step)
        assert text.strip()
        if step in ("system", "system_compact", "feedback"):
            continue
        head, sep, _ = text.partition(f"\nStep: {step}")
        assert sep, step
        # What comes before the task's own text is the same for every task (the
        # schema aside, where a step's schema is): the local server evaluates
        # that prefix once and reuses it (factask.gen.local, prompt cache).
        assert set(re.findall(r"\{\{\s*(\w+)\s*\}\}", head)) <= {"schema", "examples"}, step


def test_system_prompt_lists_exactly_what_the_library_has() -> None:
    text = render("system")
    for kind in ASSET_KINDS:
        assert f"`{kind}`" in text
    for colour in COLOR_NAMES:
        assert colour in text
    for rtype, cls in RELATION_TYPES.items():
        assert f"`{rtype}`" in text
        first_doc_words = " ".join((cls.__doc__ or "").split()[:4])
        assert first_doc_words in text
        for field in cls.model_fields:
            if field != "tolerances":
                assert f'"{field}"' in text
    assert "{{" not in text


def test_vocabulary_never_mentions_unknown_kinds() -> None:
    vocab = vocabulary()["asset_kinds"]
    listed = [line.split("`")[1] for line in vocab.splitlines()]
    assert listed == list(ASSET_KINDS)


def test_render_checks_placeholders_both_ways() -> None:
    assert "task_name" in placeholders(load_template("one_shot"))
    with pytest.raises(PromptError, match="needs values"):
        render("one_shot", task_name="x")
    with pytest.raises(PromptError, match="no placeholder"):
        render("feedback", step="s", attempt=1, max_attempts=2, feedback="f", bogus=1)
    text = render("feedback", step="one_shot", attempt=1, max_attempts=4, feedback="BROKEN")
    assert "BROKEN" in text and "one_shot" in text


def test_word_overlap_retrieval() -> None:
    assert words("Stacking the blocks-on pallets") >= {"stacking", "block", "pallet"}
    assert overlap("stack blocks", "block stack tower") == 2
    cands = [Example("x", "circle", "arrange balls in a circle", {}),
             Example("x", "stack", "stack the blocks into a tower", {})]
    assert top_k(cands, "build a tower of blocks", 1)[0].name == "stack"


def test_template_examples_come_from_the_library() -> None:
    found = template_examples("stack the blocks", 2)
    pytest.importorskip("factask.library.templates")
    assert found and all(e.source == "template" for e in found)
    assert any("stack" in e.name for e in found)


def test_memory_saves_and_retrieves_verified_subtasks(tmp_path) -> None:
    graph = parse_graph(demo_graph())
    mem = SubtaskMemory(tmp_path / "mem")
    assert mem.retrieve("anything") == []
    for f in graph.factors:
        mem.save(extract_fragment(graph, f.name), task=graph.name, approach="one-shot")
    mem.save(extract_fragment(graph, "stack_blue_on_red"), task=graph.name, approach="x")
    assert len(mem) == 2  # same content, same entry
    (tmp_path / "mem" / "garbage.json").write_text("{not json")
    best = mem.retrieve("stack the blue block on red", k=1)
    assert best[0].name == "stack_blue_on_red" and best[0].source == "memory"
    assert parse_graph(best[0].payload).factors[0].weight == 1.0
    assert SubtaskMemory.from_env(None) is None or SubtaskMemory.from_env(None).directory


def test_library_task_examples_are_valid_graphs_shown_in_the_one_shot_prompt() -> None:
    pytest.importorskip("factask.library")
    from factask.gen.answers.examples import library_task_examples, render_examples

    found = library_task_examples("stack the blocks on the pallet", 2)
    assert len(found) == 2 and found[0].score >= found[1].score
    for e in found:
        parse_graph(e.payload)
    text = render("one_shot", task_name="t", task_description="d", mentions="-",
                  examples=render_examples(found), schema="{}")
    assert found[0].name in text and "Step: one_shot" in text


def test_same_task_matches_normalised_names_and_near_duplicates() -> None:
    from factask.gen.answers.examples import same_task

    assert same_task("build-bridge", "Build_Bridge")
    assert same_task("stack-blocks-in-tower", "stack-block-in-tower")  # plural folded
    assert same_task("place-red-block-in-green-zone", "place-red-blocks-in-green-zone-now")
    assert not same_task("build-bridge", "build-car")
    assert not same_task("build-bridge", "")


def test_library_examples_never_show_the_task_itself() -> None:
    pytest.importorskip("factask.library")
    from factask.gen.answers.examples import library_task_examples, same_task
    from factask.library import task_names

    names = task_names()
    for name in names[:5]:
        query = f"{name}: {name.replace('-', ' ')}"
        assert library_task_examples(query, 2)[0].name == name  # it would be shown
        shown = [e.name for e in library_task_examples(query, len(names), exclude=name)]
        # Left out: the task and its near-duplicates, nothing else.
        assert sorted(set(names) - set(shown)) == [n for n in names if same_task(n, name)]
        assert name not in shown
    shown = [e.name for e in library_task_examples("x", len(names), exclude="Build_Bridges")]
    assert "build-bridge" not in shown


def test_memory_never_shows_entries_of_the_same_task(tmp_path) -> None:
    graph = parse_graph(demo_graph())
    mem = SubtaskMemory(tmp_path / "mem")
    fragment = extract_fragment(graph, "stack_blue_on_red")
    mem.save(fragment, task=graph.name, approach="one-shot")
    assert mem.retrieve("stack blue on red", k=3)
    assert mem.retrieve("stack blue on red", k=3, exclude_task=graph.name) == []
    assert mem.retrieve("stack blue on red", k=3, exclude_task=graph.name.upper()) == []
    assert mem.retrieve("stack blue on red", k=3, exclude_task="other-task")
