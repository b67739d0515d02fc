"""Property-based tests of the graph algebra (hypothesis)."""

from __future__ import annotations

import json
import math

import networkx as nx
import pytest
from graph_strategies import task_graphs
from hypothesis import given
from hypothesis import strategies as st

from factask.graph import (
    GraphValidationError,
    TaskGraph,
    compose,
    empty_graph,
    extract_fragment,
    extract_template,
    parse_graph,
    rename,
)


@given(task_graphs())
def test_json_round_trip_is_identity(graph: TaskGraph) -> None:
    assert parse_graph(graph.to_json()) == graph
    assert TaskGraph.model_validate(json.loads(graph.to_json())) == graph


@given(task_graphs())
def test_validation_accepts_every_generated_graph(graph: TaskGraph) -> None:
    assert graph.problems() == []
    graph.ensure_valid()


@given(task_graphs())
def test_factor_order_respects_every_dependency(graph: TaskGraph) -> None:
    order = graph.factor_order()
    assert sorted(order) == sorted(graph.factor_names())
    pos = {n: i for i, n in enumerate(order)}
    for f in graph.factors:
        for a in f.after:
            assert pos[a] < pos[f.name]
    movers = {v: f.name for f in graph.factors for v in f.moved()}
    for f in graph.factors:
        for anchor in f.anchors():
            if anchor in movers:
                assert pos[movers[anchor]] < pos[f.name]


@given(task_graphs())
def test_networkx_view_is_bipartite_with_scope_edges(graph: TaskGraph) -> None:
    g = graph.to_networkx()
    assert nx.is_bipartite(g)
    for _node, data in g.nodes(data=True):
        assert data["bipartite"] == (0 if data["kind"] == "variable" else 1)
    for f in graph.factors:
        assert set(g.neighbors(f.name)) == set(f.scope_names)


@given(task_graphs(prefix="a_"), task_graphs(prefix="b_"))
def test_composition_preserves_bipartiteness_and_scope_integrity(
    a: TaskGraph, b: TaskGraph
) -> None:
    c = compose(a, b, name="composed")
    c.ensure_valid()
    g = c.to_networkx()
    assert nx.is_bipartite(g)
    names = set(c.variable_names())
    for f in c.factors:
        assert set(f.scope_names) <= names
    assert len(c.factors) == len(a.factors) + len(b.factors)
    if c.factors:
        assert math.isclose(sum(f.weight for f in c.factors), 1.0, abs_tol=1e-9)


@given(task_graphs())
def test_composing_with_the_empty_graph_is_identity(graph: TaskGraph) -> None:
    assert compose(graph, empty_graph()) == graph
    assert compose(empty_graph(), graph) == graph


def _canonical(graph: TaskGraph) -> dict:
    return {
        "variables": sorted(v.model_dump_json() for v in graph.variables),
        "factors": {
            f.name: (f.goal.model_dump_json(), sorted(f.after), round(f.weight, 9))
            for f in graph.factors
        },
    }


@given(task_graphs(prefix="a_"), task_graphs(prefix="b_"), task_graphs(prefix="c_"))
def test_composition_is_associative(a: TaskGraph, b: TaskGraph, c: TaskGraph) -> None:
    left = compose(compose(a, b), c, name="x")
    right = compose(a, compose(b, c), name="x")
    assert _canonical(left) == _canonical(right)


@given(task_graphs(prefix="a_"), task_graphs(prefix="b_"))
def test_composition_is_associative_up_to_renaming(a: TaskGraph, b: TaskGraph) -> None:
    # Renaming b's names into a fresh namespace commutes with composition.
    mapping = {n: n.replace("b_", "z_", 1) for n in b.variable_names() + b.factor_names()}
    lhs = rename(compose(a, b, name="x"), mapping)
    rhs = compose(a, rename(b, mapping), name="x")
    assert _canonical(lhs) == _canonical(rhs)


@given(task_graphs(prefix="a_"))
def test_shared_variables_are_identified_by_name(graph: TaskGraph) -> None:
    # Composing a graph with a copy whose factors are renamed shares every variable.
    mapping = {f: f.replace("a_", "b_", 1) for f in graph.factor_names()}
    twin = rename(graph, mapping)
    c = compose(graph, twin, name="twin")
    assert c.variable_names() == graph.variable_names()


@given(task_graphs(), st.data())
def test_extracted_factor_is_a_valid_reusable_fragment(graph: TaskGraph, data) -> None:
    if not graph.factors:
        return
    name = data.draw(st.sampled_from(graph.factor_names()))
    frag = extract_fragment(graph, name)
    frag.ensure_valid()
    template = extract_template(graph, name)
    bound = {v: graph.variable(v) for v in graph.factor(name).scope_names}
    inst = template.instantiate(prefix="", **bound)
    assert inst.factors[0].goal == graph.factor(name).goal
    inst.ensure_valid()


# ---------------------------------------------------------------- corruptions
def _corrupt(data: dict, choice: int, pick: int) -> str:
    """Apply one corruption to a graph dict; return the name the error must mention."""
    variables, factors = data["variables"], data["factors"]
    v = variables[pick % len(variables)]
    f = factors[pick % len(factors)] if factors else None
    kinds = [
        "color", "kind", "size_zero", "size_nan", "dup_var", "bad_name",
        "scope_missing", "objects_missing", "after_unknown", "weight_neg", "cycle",
        "extra_field", "fixed_moved", "count_zero",
    ]
    kind = kinds[choice % len(kinds)]
    if f is None and kind in {"scope_missing", "objects_missing", "after_unknown", "weight_neg",
                              "cycle", "extra_field", "fixed_moved"}:
        kind = "color"
    if kind == "color":
        v["color"] = "ultraviolet"
        return v["name"]
    if kind == "kind":
        v["kind"] = "spaceship"
        return v["name"]
    if kind == "size_zero":
        v["size"] = [0.0, 0.04, 0.04]
        return v["name"]
    if kind == "size_nan":
        v["size"] = [float("nan"), 0.04, 0.04]
        return v["name"]
    if kind == "count_zero":
        v["count"] = 0
        return v["name"]
    if kind == "dup_var":
        other = dict(variables[(pick + 1) % len(variables)])
        other["name"] = v["name"]
        if other is v or len(variables) == 1:
            variables.append(dict(v))
        else:
            variables.append(other)
        return v["name"]
    if kind == "bad_name":
        v["name"] = "Bad Name!"
        return "Bad Name!"
    assert f is not None
    if kind == "scope_missing":
        f["scope"] = [*f["scope"], "ghost_variable"]
        return f["name"]
    if kind == "objects_missing":
        f["goal"]["objects"] = ["ghost_object"]
        return f["name"]
    if kind == "after_unknown":
        f["after"] = ["ghost_factor"]
        return f["name"]
    if kind == "weight_neg":
        f["weight"] = -0.5
        return f["name"]
    if kind == "cycle":
        f["after"] = [*f["after"], f["name"]]
        return f["name"]
    if kind == "extra_field":
        f["reward_shaping"] = "dense"
        return f["name"]
    if kind == "fixed_moved":
        moved = f["goal"]["objects"][0]
        for var in variables:
            if var["name"] == moved:
                var["fixed"] = True
        return f["name"]
    raise AssertionError(kind)


@given(task_graphs(), st.integers(0, 1000), st.integers(0, 1000))
def test_each_single_corruption_is_rejected_naming_the_node(
    graph: TaskGraph, choice: int, pick: int
) -> None:
    data = json.loads(graph.to_json())
    node = _corrupt(data, choice, pick)
    with pytest.raises(GraphValidationError) as info:
        parse_graph(json.dumps(data))
    assert node in str(info.value)
    assert node in info.value.nodes or any(node in str(p) for p in info.value.problems)
