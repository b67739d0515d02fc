"""The capable-model path (issue 34): a valid graph is never refused by a step that asks
for a whole graph, whatever optional fields it writes (what `factask schema` and
`factask show --json` print), and a model answering with the reference graph yields the
reference task."""

from __future__ import annotations

import json

import pytest
from hypothesis import given
from hypothesis import strategies as st

from factask.gen.answers.schemas import AnswerError
from factask.gen.answers.step_schemas import graph_schema
from factask.gen.compare import compare
from factask.gen.llm import LLMClient, LLMConfig
from factask.gen.loopback import LoopbackServer, ScriptedResponder
from factask.gen.steps import read_graph_answer
from factask.gen.strategies import Generator
from factask.gen.verify import Verifier, at_least
from factask.graph import TaskGraph, parse_graph
from factask.library.tasks import get_task, task_names
from tests.graph_strategies import task_graphs


def _read_back(graph: TaskGraph) -> TaskGraph:
    data = read_graph_answer(graph.to_json(), graph_schema(graph.name), {"name": graph.name})
    return parse_graph(data)


@given(name=st.sampled_from(task_names()))
def test_every_library_graph_passes_the_whole_graph_step(name: str) -> None:
    graph = get_task(name)
    assert compare(_read_back(graph), graph).equivalent


@given(graph=task_graphs())
def test_every_valid_graph_passes_the_whole_graph_step(graph: TaskGraph) -> None:
    assert compare(_read_back(graph), graph).equivalent


def test_what_is_not_a_valid_graph_is_still_refused_with_the_schemas_problems() -> None:
    schema = graph_schema("t")
    with pytest.raises(AnswerError, match="does not follow the schema"):
        read_graph_answer('{"variables": [], "factors": [{"name": "f"}]}', schema)
    bad = get_task("build-bridge").to_dict()
    bad["factors"][0]["goal"]["objects"] = ["no_such_variable"]
    with pytest.raises(AnswerError):
        read_graph_answer(json.dumps(bad), schema)


def test_a_model_answering_with_the_library_graph_gets_the_library_task() -> None:
    reference = get_task("build-bridge")
    with LoopbackServer(ScriptedResponder({"one_shot": reference.to_json()})) as server:
        client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                     num_retries=0))
        result = Generator(client, Verifier(episodes=1), max_repairs=0).generate(
            f"build-bridge: {reference.description}", "one-shot")
    assert result.graph is not None, result.failure
    assert [s.ok for s in result.steps] == [True]  # accepted at once: no refusal
    assert at_least(result.level_reached, "runtime")
    assert compare(result.graph, reference).equivalent
