"""Never a confident wrong task: every meaningful word of a proposal is used by the graph
or reported unread (factask.gen.reading.accounting), and a generation that leaves words
unread ends at level partial."""

from __future__ import annotations

import json

import pytest
from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

from factask.cli import app
from factask.gen.demo import DEMO_PROPOSAL, demo_graph, demo_responder
from factask.gen.loopback import LoopbackServer
from factask.gen.reading.accounting import account
from factask.gen.reading.describe import describe
from factask.graph import TaskGraph, parse_graph
from factask.library.tasks import get_task, task_names
from tests.graph_strategies import task_graphs

runner = CliRunner()


def _graph(variables: list[dict], factors: list[dict]) -> TaskGraph:
    for f in factors:
        f.setdefault("weight", 1 / len(factors))
    return parse_graph({"name": "t", "variables": variables, "factors": factors})


TWO_BOXES = _graph([{"name": "boxes", "kind": "box", "count": 2},
                    {"name": "zone", "kind": "zone"}],
                   [{"name": "f", "goal": {"type": "in_zone", "objects": ["boxes"],
                                           "zone": "zone"}}])


@given(name=st.sampled_from(task_names()))
def test_a_library_graph_told_in_words_reads_back_in_full(name: str) -> None:
    graph = get_task(name)
    result = account(describe(graph), graph)
    assert result.complete, (describe(graph), [str(w) for w in result.unread])


@given(graph=task_graphs())
def test_any_graph_told_in_words_reads_back_in_full(graph: TaskGraph) -> None:
    result = account(describe(graph), graph)
    assert result.complete, (describe(graph), [str(w) for w in result.unread])


@pytest.mark.parametrize(("proposal", "unread"), [
    # colour groups with counts read as two uncoloured boxes
    ("put four red and four white flat boxes in the zone", {"four", "red", "white", "flat"}),
    # ordinals with no order among the goals
    ("put the first box in the zone, then the second box", {"first", "then", "second"}),
    # sides of the table no relation expresses
    ("put the boxes on the left half of the table", {"left", "half"}),
    # shapes no relation makes
    ("arrange the boxes as a staircase in a checkerboard", {"staircase", "checkerboard"}),
    # negation, measures
    ("put the boxes in the zone, not the box 5 cm from the edge", {"not", "5", "cm", "edge"}),
])
def test_words_the_graph_does_not_use_are_reported(proposal: str, unread: set[str]) -> None:
    result = account(proposal, TWO_BOXES)
    assert set(result.unread_words()) == unread, [str(w) for w in result.unread]
    assert all(w.why for w in result.unread)


def test_words_the_graph_uses_are_read_with_what_uses_them() -> None:
    result = account("put the two boxes into the zone", TWO_BOXES)
    assert result.complete
    assert {(w.text, w.category) for w in result.read} == {
        ("two", "number"), ("boxes", "kind"), ("into", "relation"), ("zone", "kind")}


def test_order_words_are_read_only_when_the_goals_are_ordered() -> None:
    free = _graph([{"name": "r", "kind": "block", "color": "red"},
                   {"name": "b", "kind": "block", "color": "blue"},
                   {"name": "z", "kind": "zone", "color": "green"}],
                  [{"name": "f", "goal": {"type": "in_zone", "objects": ["r"], "zone": "z"}},
                   {"name": "g", "goal": {"type": "in_zone", "objects": ["b"], "zone": "z"}}])
    text = "put the red block into the green zone, then the blue block"
    assert account(text, free).unread_words() == ["then"]
    data = free.model_dump(mode="json", exclude_none=True)
    data["factors"][1]["after"] = ["f"]
    assert account(text, parse_graph(data)).complete


def test_a_completed_generation_with_unread_words_ends_partial(tmp_path) -> None:
    proposal = DEMO_PROPOSAL + " on the left side of the table"
    args = ["generate", proposal, "--approach", "one-shot", "--model", "openai/scripted",
            "--episodes", "1", "--cache", str(tmp_path / "cache")]
    with LoopbackServer(demo_responder()) as server:
        res = runner.invoke(app, [*args, "--api-base", server.url,
                                  "--out", str(tmp_path / "g.json"), "--json"])
        strict = runner.invoke(app, [*args, "--api-base", server.url,
                                     "--out", str(tmp_path / "s.json"), "--strict"])
    assert res.exit_code == 1, res.output
    record = json.loads(res.stdout.strip().splitlines()[-1])
    assert record["level_reached"] == "partial"
    assert {w["word"] for w in record["unread"]} == {"left", "side"}
    assert "unread" in record["failure"]
    assert (tmp_path / "g.json").exists()  # written, and said to be partial
    assert strict.exit_code == 1 and not (tmp_path / "s.json").exists()
    assert "no graph written (--strict)" in strict.output


def test_the_demo_proposal_is_read_in_full() -> None:
    assert account(DEMO_PROPOSAL, parse_graph(demo_graph())).complete
