"""The meaning metric (factask.gen.compare): what keeps a graph the same task and what
does not, on the library's graphs and hypothesis-built ones, and `factask compare`."""

from __future__ import annotations

import json
import random
from pathlib import Path
from typing import Any

from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

from factask.cli import app
from factask.gen.compare import compare
from factask.graph import TaskGraph, parse_graph, rename
from factask.library.tasks import get_task, task_names
from tests.graph_strategies import task_graphs

NAMES = task_names()


def _data(graph: TaskGraph) -> dict[str, Any]:
    return graph.model_dump(mode="json", exclude_none=True)


def _renamed_and_shuffled(graph: TaskGraph, seed: int) -> TaskGraph:
    """Every name changed, variables and factors listed in another order, descriptions,
    weights and tolerances changed: the same task."""
    rng = random.Random(seed)
    names = graph.variable_names() + graph.factor_names()
    out = rename(graph, {n: f"n{i}_{rng.randrange(1000)}" for i, n in enumerate(names)})
    data = _data(out)
    rng.shuffle(data["variables"])
    rng.shuffle(data["factors"])
    for f in data["factors"]:
        f["description"] = "something else"
        f["goal"].pop("tolerances", None)
    data["name"], data["description"] = "renamed", "other words"
    return parse_graph(data)


@given(name=st.sampled_from(NAMES), seed=st.integers(0, 10**6))
def test_names_order_and_wording_do_not_change_the_task(name: str, seed: int) -> None:
    graph = get_task(name)
    result = compare(_renamed_and_shuffled(graph, seed), graph)
    assert result.equivalent, result.differences
    assert (result.object_f1, result.relation_f1, result.order_agreement) == (1.0, 1.0, 1.0)
    assert result.differences == []


@given(graph=task_graphs())
def test_every_hypothesis_graph_is_its_own_task(graph: TaskGraph) -> None:
    assert compare(graph, graph).equivalent
    assert compare(_renamed_and_shuffled(graph, 0), graph).equivalent


@given(name=st.sampled_from(NAMES), data=st.data())
def test_a_changed_colour_is_another_task(name: str, data: st.DataObject) -> None:
    graph = get_task(name)
    coloured = [v for v in graph.variables if v.color]
    if not coloured:
        return
    victim = data.draw(st.sampled_from(coloured))
    other = "purple" if victim.color != "purple" else "orange"
    changed = _data(graph)
    next(v for v in changed["variables"] if v["name"] == victim.name)["color"] = other
    result = compare(parse_graph(changed), graph)
    assert not result.equivalent
    assert result.object_f1 < 1.0
    assert any(line.startswith("missing object") for line in result.differences)


@given(name=st.sampled_from(NAMES))
def test_a_dropped_goal_is_another_task(name: str) -> None:
    graph = get_task(name)
    if len(graph.factors) < 2:
        return
    data = _data(graph)
    dropped = data["factors"].pop()
    for f in data["factors"]:
        f["after"] = [a for a in f.get("after", []) if a != dropped["name"]]
    total = sum(f.get("weight", 1.0) for f in data["factors"])
    for f in data["factors"]:
        f["weight"] = f.get("weight", 1.0) / total
    result = compare(parse_graph(data), graph)
    assert not result.equivalent
    assert result.relation_f1 < 1.0
    assert any(line.startswith("missing goal") for line in result.differences)


def _blocks(split: bool, order: bool = False) -> TaskGraph:
    """Three red blocks into the green zone: as one variable of count 3 and one goal, or
    as three variables with a goal each (the same task); or the goals in a fixed order."""
    if split:
        variables = [{"name": f"b{i}", "kind": "block", "color": "red"} for i in range(3)]
        factors = [{"name": f"f{i}", "goal": {"type": "in_zone", "objects": [f"b{i}"],
                                              "zone": "z"}, "weight": 1 / 3,
                    "after": [f"f{i - 1}"] if order and i else []} for i in range(3)]
    else:
        variables = [{"name": "blocks", "kind": "block", "color": "red", "count": 3}]
        factors = [{"name": "f", "goal": {"type": "in_zone", "objects": ["blocks"],
                                          "zone": "z"}}]
    variables.append({"name": "z", "kind": "zone", "color": "green"})
    return parse_graph({"name": "t", "variables": variables, "factors": factors})


def test_objects_counted_or_listed_one_by_one_are_the_same_task() -> None:
    assert compare(_blocks(split=True), _blocks(split=False)).equivalent
    assert compare(_blocks(split=False), _blocks(split=True)).equivalent


def test_order_counts_only_where_the_reference_orders() -> None:
    ordered, free = _blocks(split=True, order=True), _blocks(split=True)
    assert compare(ordered, free).equivalent  # an order the reference does not ask for
    result = compare(free, ordered)
    assert not result.equivalent and result.order_agreement == 0.0
    # f0 before f1, f1 before f2, and (transitively) f0 before f2
    assert sum(line.startswith("order not kept") for line in result.differences) == 3


def test_which_object_plays_which_role_counts() -> None:
    def on(top: str, bottom: str) -> TaskGraph:
        return parse_graph({"name": "t", "variables": [
            {"name": "r", "kind": "block", "color": "red"},
            {"name": "b", "kind": "block", "color": "blue"}],
            "factors": [{"name": "f", "goal": {"type": "on", "objects": [top],
                                               "support": bottom}}]})
    result = compare(on("r", "b"), on("b", "r"))
    assert not result.equivalent and result.object_f1 == 1.0 and result.relation_f1 == 0.0


def test_the_command_compares_files_and_library_names(tmp_path: Path) -> None:
    runner = CliRunner()
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    a.write_text(_blocks(split=True).to_json())
    b.write_text(_blocks(split=False).to_json())
    same = runner.invoke(app, ["compare", str(a), str(b), "--json"])
    assert same.exit_code == 0, same.output
    assert json.loads(same.output)["equivalent"] is True
    other = runner.invoke(app, ["compare", str(a), "build-house"])
    assert other.exit_code == 1
    assert "missing goal" in other.output and "object F1" in other.output
    bad = runner.invoke(app, ["compare", str(tmp_path / "nope.json"), "build-house"])
    assert bad.exit_code == 2 and "Traceback" not in bad.output


def _bowl_task(block: str, bowl: str) -> dict[str, Any]:
    return {"name": "t", "variables": [
        {"name": "b", "kind": "block", "color": block},
        {"name": "w", "kind": "bowl", "color": bowl}],
        "factors": [{"name": "f", "goal": {"type": "inside", "objects": ["b"],
                                           "container": "w"}}]}


def test_a_colour_the_words_do_not_name_matches_any_colour() -> None:
    """"put a block in the green bowl": any block colour means it; the bowl's colour is
    named, so it still counts."""
    words = "put a block in the green bowl"
    assert not compare(_bowl_task("red", "green"), _bowl_task("blue", "green")).equivalent
    assert compare(_bowl_task("red", "green"), _bowl_task("blue", "green"), words).equivalent
    assert not compare(_bowl_task("red", "yellow"), _bowl_task("red", "green"),
                       words).equivalent
    assert compare(_bowl_task("red", "green"), _bowl_task("blue", "green"),
                   "put the blue block in the green bowl").equivalent is False


@given(st.sampled_from(NAMES), st.data())
def test_with_the_words_a_named_colour_still_counts(name: str, data: st.DataObject) -> None:
    """Recolouring an object whose colour the words name is another task, with or
    without the words; any graph is still its own task given any words."""
    graph = get_task(name)
    coloured = [v for v in graph.variables if v.color]
    words = graph.description or ""
    assert compare(graph, graph, words).equivalent
    if not coloured:
        return
    target = data.draw(st.sampled_from(coloured))
    other = "pink" if target.color != "pink" else "cyan"
    changed = _data(graph)
    for v in changed["variables"]:
        if v["name"] == target.name:
            v["color"] = other
    named = f"{words} the {target.color} one"
    assert not compare(changed, graph, named).equivalent


def test_the_command_reads_the_words(tmp_path: Path) -> None:
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    a.write_text(json.dumps(_bowl_task("red", "green")))
    b.write_text(json.dumps(_bowl_task("blue", "green")))
    assert CliRunner().invoke(app, ["compare", str(a), str(b)]).exit_code == 1
    same = CliRunner().invoke(app, ["compare", str(a), str(b), "--proposal",
                                    "put a block in the green bowl"])
    assert same.exit_code == 0, same.output
