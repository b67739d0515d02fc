"""Fuzzing every entry point that takes outside input (hypothesis).

Whatever comes in — random JSON, a library graph with one field corrupted, a
graph mutated after construction, a valid graph the sampler may not be able to
lay out, junk files given to the CLI — what comes out is a result or a
``FactaskError`` whose message names node and field, is bounded in length, and
arrives in bounded time. Never another exception, a traceback or a hang.
"""

from __future__ import annotations

import json
import time
from typing import Any

import numpy as np
import pytest
from graph_strategies import task_graphs
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from factask.graph import GraphValidationError, TaskGraph, parse_graph
from factask.library import get_task
from factask.vocabulary.errors import FactaskError
from scripts.fuzz_graphs import json_paths

#: Longest message a validation report may have, characters.
MAX_MESSAGE = 20_000
#: Seconds one parse may take.
PARSE_SECONDS = 5.0

json_leaves = st.one_of(st.none(), st.booleans(), st.integers(-10**12, 10**12),
                        st.floats(allow_nan=True, allow_infinity=True),
                        st.text(max_size=40), st.just("block"), st.just("in_zone"),
                        st.just(1e-310), st.just(-0.0))
json_values = st.recursive(json_leaves, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=12), inner, max_size=4)),
    max_leaves=25)

LIBRARY = [get_task(n).to_dict() for n in ("stack-block-pyramid", "put-block-in-bowl",
                                           "towers-of-hanoi", "align-box-corner")]


def _set(data: Any, path: tuple, value: Any) -> Any:
    if not path:
        return value
    data[path[0]] = _set(data[path[0]], path[1:], value)
    return data


def _check_parse(data: Any) -> None:
    start = time.monotonic()
    try:
        graph = parse_graph(data)
    except GraphValidationError as exc:
        text = str(exc)
        assert exc.problems and len(text) < MAX_MESSAGE
        for p in exc.problems:
            assert p.message and isinstance(p.node, str) and isinstance(p.field, str)
    else:
        assert isinstance(graph, TaskGraph) and graph.problems() == []
    assert time.monotonic() - start < PARSE_SECONDS


@settings(max_examples=150, suppress_health_check=[HealthCheck.too_slow])
@given(json_values)
def test_random_json_parses_or_fails_typed(data: Any) -> None:
    _check_parse(data)
    _check_parse(json.dumps(data))


@settings(max_examples=250, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(range(len(LIBRARY))), st.data(), json_values)
def test_a_library_graph_with_one_corrupted_value_parses_or_fails_naming_it(
        which: int, data: st.DataObject, junk: Any) -> None:
    graph = json.loads(json.dumps(LIBRARY[which]))
    path = data.draw(st.sampled_from(json_paths(graph)[1:]))
    corrupted = _set(graph, path, junk)
    try:
        parse_graph(corrupted)
    except GraphValidationError as exc:
        assert len(str(exc)) < MAX_MESSAGE
        if path[0] in ("variables", "factors") and len(path) > 2:
            # The problem names the node (by its name, or its index if the name broke).
            named = corrupted[path[0]][path[1]]
            name = named.get("name") if isinstance(named, dict) else None
            assert any(p.node in (name, f"{path[0]}[{path[1]}]") or p.node == ""
                       or "after" in p.field or "goal" in p.field or "scope" in p.field
                       or "initial" in p.field for p in exc.problems), exc


@settings(max_examples=150, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(range(len(LIBRARY))), st.data(), json_values)
def test_mutating_a_built_graph_is_caught_where_it_enters(which: int, data: st.DataObject,
                                                         junk: Any) -> None:
    graph = parse_graph(LIBRARY[which])
    node = data.draw(st.sampled_from([*graph.variables, *graph.factors]))
    field = data.draw(st.sampled_from(sorted(type(node).model_fields)))
    object.__setattr__(node, field, junk)  # what `node.field = junk` does, unchecked
    try:
        graph.ensure_valid()
    except GraphValidationError as exc:
        assert len(str(exc)) < MAX_MESSAGE
    except FactaskError:
        pass


def test_a_field_set_to_none_after_construction_is_caught_as_none() -> None:
    """A count set to None was left out of the re-check (refilled with its default)
    while the graph kept the None: the whole-graph check then raised a TypeError."""
    graph = parse_graph(LIBRARY[0])
    object.__setattr__(graph.variables[0], "count", None)
    with pytest.raises(GraphValidationError, match="count"):
        graph.ensure_valid()


@pytest.mark.slow
@settings(max_examples=12, deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(task_graphs(max_factors=3), st.integers(0, 2**16))
def test_every_accepted_graph_compiles_and_resets_or_fails_typed(graph: TaskGraph,
                                                                seed: int) -> None:
    from factask.sim.build.compile import compile_graph
    from factask.sim.layout.reset import reset_layout

    if not graph.factors:
        return
    compile_graph(graph)
    start = time.monotonic()
    try:
        reset_layout(graph, np.random.default_rng(seed))
    except FactaskError as exc:
        assert len(str(exc)) < MAX_MESSAGE
    assert time.monotonic() - start < 15.0  # the reset's budget plus one attempt


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.one_of(st.binary(max_size=300), json_values.map(lambda v: json.dumps(v).encode())))
def test_validate_on_junk_files_exits_with_a_code_never_a_traceback(tmp_path_factory,
                                                                    content: bytes) -> None:
    from typer.testing import CliRunner

    from factask.cli import app

    path = tmp_path_factory.mktemp("junk") / "task.json"
    path.write_bytes(content)
    result = CliRunner().invoke(app, ["validate", str(path)])
    assert result.exit_code in (0, 1, 2), result.output
    assert "Traceback" not in result.output and len(result.output) < MAX_MESSAGE
