"""Milestones: ordered, latched factors (model rules, latching, env, oracle).

Property tests cover the order algebra: composition keeps each part's order and
milestone flags, cycles are rejected naming their factors, and a reached
milestone never loses progress whatever the live checks say afterwards.
"""

from __future__ import annotations

import networkx as nx
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.graph import (
    GraphValidationError,
    InZone,
    On,
    StateVariable,
    SubtaskFactor,
    TaskGraph,
    compose,
)
from factask.relations.status import FactorStatus
from factask.sim.layout.checks import latch_milestones


@st.composite
def move_sequences(draw: st.DrawFn, prefix: str = "") -> TaskGraph:
    """A chain of moves over a few blocks and zones: each factor puts one block in a
    zone, after the previous move; a block's last move is final, its earlier moves
    are milestones."""
    n_blocks = draw(st.integers(1, 3))
    n_zones = draw(st.integers(1, 3))
    blocks = [StateVariable(name=f"{prefix}block_{i}", kind="block") for i in range(n_blocks)]
    zones = [StateVariable(name=f"{prefix}zone_{i}", kind="zone") for i in range(n_zones)]
    seq = draw(st.lists(st.tuples(st.integers(0, n_blocks - 1), st.integers(0, n_zones - 1)),
                        min_size=1, max_size=7))
    last = {b: k for k, (b, _) in enumerate(seq)}
    factors = []
    for k, (b, z) in enumerate(seq):
        factors.append(SubtaskFactor(
            name=f"{prefix}move_{k}", goal=InZone(objects=[blocks[b].name], zone=zones[z].name),
            weight=1 / len(seq), milestone=last[b] != k,
            after=[factors[-1].name] if factors else []))
    return TaskGraph(name="moves", variables=blocks + zones, factors=factors)


@given(move_sequences())
def test_a_chain_of_moves_is_valid_and_ordered(graph: TaskGraph) -> None:
    assert graph.problems() == []
    assert graph.factor_order() == graph.factor_names()


@given(move_sequences(prefix="a_"), move_sequences(prefix="b_"))
def test_composition_keeps_each_parts_order_and_milestones(a: TaskGraph, b: TaskGraph) -> None:
    c = compose(a, b, name="both").ensure_valid()
    d = c.dependency_graph()
    for part in (a, b):
        for u, v in part.dependency_graph().edges:
            assert nx.has_path(d, u, v)
        assert set(part.milestones()) <= set(c.milestones())
    assert set(c.milestones()) == set(a.milestones()) | set(b.milestones())


@given(move_sequences())
def test_a_cycle_is_rejected_naming_its_factors(graph: TaskGraph) -> None:
    if len(graph.factors) < 2:
        return
    first, last = graph.factors[0], graph.factors[-1]
    looped = graph.model_copy(update={"factors": [
        first.model_copy(update={"after": [last.name]}), *graph.factors[1:]]})
    with pytest.raises(GraphValidationError) as err:
        looped.ensure_valid()
    cycles = [p for p in err.value.problems if "cycle" in p.message]
    assert cycles and first.name in cycles[0].message and last.name in cycles[0].message


def test_an_object_moved_twice_needs_order_and_an_earlier_milestone() -> None:
    block = StateVariable(name="block", kind="block")
    zones = [StateVariable(name=f"zone_{i}", kind="zone") for i in range(2)]

    def move(k: int, **kw: object) -> SubtaskFactor:
        return SubtaskFactor(name=f"move_{k}", goal=InZone(objects=["block"], zone=f"zone_{k}"),
                             weight=0.5, **kw)

    unordered = TaskGraph(name="t", variables=[block, *zones], factors=[move(0), move(1)])
    [p] = unordered.problems()
    assert (p.node, p.field) == ("move_1", "after") and "no order" in p.message
    both_final = TaskGraph(name="t", variables=[block, *zones],
                           factors=[move(0), move(1, after=["move_0"])])
    [p] = both_final.problems()
    assert (p.node, p.field) == ("move_0", "milestone") and "milestone=true" in p.fix
    good = TaskGraph(name="t", variables=[block, *zones],
                     factors=[move(0, milestone=True), move(1, after=["move_0"])])
    assert good.problems() == []


def test_an_anchor_moved_later_gives_no_edge_backwards() -> None:
    # 'top' rests on 'base' after base's first move; base's second move comes later.
    base = StateVariable(name="base", kind="block")
    top = StateVariable(name="top", kind="block")
    zones = [StateVariable(name=f"zone_{i}", kind="zone") for i in range(2)]
    factors = [
        SubtaskFactor(name="base_first", goal=InZone(objects=["base"], zone="zone_0"),
                      weight=0.25, milestone=True),
        SubtaskFactor(name="top_on_base", goal=On(objects=["top"], support="base"),
                      weight=0.25, milestone=True, after=["base_first"]),
        SubtaskFactor(name="base_again", goal=InZone(objects=["base"], zone="zone_1"),
                      weight=0.25, after=["top_on_base"]),
        SubtaskFactor(name="top_last", goal=InZone(objects=["top"], zone="zone_0"),
                      weight=0.25, after=["base_again"]),
    ]
    g = TaskGraph(name="t", variables=[base, top, *zones], factors=factors).ensure_valid()
    assert g.factor_order() == ["base_first", "top_on_base", "base_again", "top_last"]
    assert not g.dependency_graph().has_edge("base_again", "top_on_base")


@settings(max_examples=60)
@given(move_sequences(), st.data())
def test_a_reached_milestone_never_loses_progress(graph: TaskGraph, data: st.DataObject) -> None:
    names = graph.factor_names()
    reached: frozenset[str] = frozenset()
    preds = {n: set(graph.dependency_graph().predecessors(n)) for n in names}
    for _ in range(data.draw(st.integers(1, 8))):
        live = data.draw(st.lists(st.booleans(), min_size=len(names), max_size=len(names)))
        statuses = {n: FactorStatus(1.0 if ok else 0.25, ok) for n, ok in zip(names, live,
                                                                            strict=True)}
        before = reached
        reached = latch_milestones(graph, statuses, reached)
        assert before <= reached
        for f in graph.factors:
            st_ = statuses[f.name]
            if f.milestone and f.name in reached:
                assert st_.progress == 1.0 and st_.satisfied and st_.latched
            if f.name in reached - before:  # newly reached: its predecessors were first
                assert preds[f.name] <= reached
            if f.milestone and f.name not in reached:
                assert not st_.satisfied
                if preds[f.name] - reached:
                    assert st_.progress == 0.0 and st_.waiting_for
            upstream = nx.ancestors(graph.dependency_graph(), f.name)
            if not f.milestone and any(m not in reached for m in upstream
                                       if graph.factor(m).milestone):
                # Nothing after a pending milestone counts yet.
                assert st_.progress == 0.0 and not st_.satisfied and st_.waiting_for


def test_the_library_towers_of_hanoi_has_seven_moves_four_milestones() -> None:
    from factask.library import get_task

    g = get_task("towers-of-hanoi")
    assert len(g.factors) == 7
    assert g.milestones() == [g.factor_names()[k] for k in (0, 1, 2, 4)]
    assert g.factor_order() == g.factor_names()


@given(move_sequences(), st.data())
def test_a_listed_plan_gets_the_order_and_milestones_its_listing_implies(
        graph: TaskGraph, data: st.DataObject) -> None:
    from factask.graph.order import in_listed_order

    # Forget the order and the milestones (what an LLM's plan gives): the listing
    # alone restores a valid graph whose order keeps the listing for each block.
    keep = data.draw(st.lists(st.booleans(), min_size=len(graph.factors),
                              max_size=len(graph.factors)))
    loose = [f.model_copy(update={"after": f.after if k else [], "milestone": False})
             for f, k in zip(graph.factors, keep, strict=True)]
    fixed = in_listed_order(loose)
    result = graph.model_copy(update={"factors": fixed})
    assert result.problems() == []
    order = result.factor_order()
    for var in {o for f in fixed for o in f.goal.objects}:
        movers = [f.name for f in fixed if var in f.goal.objects]
        assert [n for n in order if n in movers] == movers
        assert [f.milestone for f in fixed if f.name in movers] == \
            [True] * (len(movers) - 1) + [False]
    assert in_listed_order(fixed) == fixed  # nothing left to add
