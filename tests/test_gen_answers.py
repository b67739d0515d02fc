"""Reading answers: JSON extraction, schema validation, precise feedback, never exec."""

from __future__ import annotations

import ast
import json
from pathlib import Path

import pytest

import factask.evaluation
import factask.gen
from factask.gen.demo import demo_graph
from factask.gen.schemas import (
    AnswerError,
    GoalAnswer,
    SubtaskDesign,
    VariablesAnswer,
    extract_json,
    parse_answer,
)
from factask.gen.verify import graph_syntax

GRAPH = demo_graph()


@pytest.mark.parametrize("text", [
    json.dumps(GRAPH),
    "```json\n" + json.dumps(GRAPH) + "\n```",
    "Let me think. The red block goes first.\n" + json.dumps(GRAPH) + "\nDone!",
    "Sure:\n```\n" + json.dumps(GRAPH, indent=2) + "\n```\nHope this helps {not json}",
])
def test_extract_json_tolerates_fences_and_prose(text: str) -> None:
    assert extract_json(text) == GRAPH


@pytest.mark.parametrize("text, phrase", [
    ("", "empty"),
    ("I cannot do that.", "no complete JSON object"),
    (json.dumps(GRAPH)[:-40], "no complete JSON object"),  # truncated
    ("[1, 2, 3]", "no complete JSON object"),
])
def test_junk_becomes_feedback(text: str, phrase: str) -> None:
    with pytest.raises(AnswerError, match=phrase) as info:
        extract_json(text)
    assert "JSON object" in info.value.feedback


def _mutated(**changes: object) -> dict:
    g = json.loads(json.dumps(GRAPH))
    for path, value in changes.items():
        node = g
        keys = path.split(".")
        for k in keys[:-1]:
            node = node[int(k)] if k.isdigit() else node[k]
        node[keys[-1]] = value
    return g


@pytest.mark.parametrize("graph, node, phrase", [
    (_mutated(**{"variables.0.kind": "rope"}), "red_block", "kind"),
    (_mutated(**{"variables.1.color": "sparkly"}), "blue_block", "unknown colour 'sparkly'"),
    (_mutated(**{"factors.1.goal.support": "yellow_block"}), "stack_blue_on_red",
     "missing variable 'yellow_block'"),
    (_mutated(**{"factors.0.weight": 0.9}), "<graph>", "sum to"),
    (_mutated(**{"factors.0.goal.type": "teleport"}), "place_red_in_zone", "goal"),
])
def test_graph_problems_name_the_node(graph: dict, node: str, phrase: str) -> None:
    with pytest.raises(AnswerError) as info:
        graph_syntax(json.dumps(graph))
    fb = info.value.feedback
    assert phrase in fb
    assert node in fb


def test_wrong_schema_for_a_step_is_reported() -> None:
    with pytest.raises(AnswerError, match="VariablesAnswer") as info:
        parse_answer(json.dumps({"objects": []}), VariablesAnswer)
    assert "variables" in info.value.feedback
    with pytest.raises(AnswerError, match="GoalAnswer"):
        parse_answer('{"goal": {"type": "on", "objects": ["a"]}}', GoalAnswer)


def test_answers_with_code_are_data_never_executed(tmp_path: Path) -> None:
    marker = tmp_path / "pwned"
    payload = f"__import__('os').system('touch {marker}')"
    # As a name: rejected by the identifier pattern.
    bad = _mutated(**{"variables.0.name": payload})
    with pytest.raises(AnswerError):
        graph_syntax(json.dumps(bad))
    # As free text (a description): kept verbatim as a string.
    ok = _mutated(**{"description": payload, "variables.0.description": "eval(" + payload + ")"})
    graph = graph_syntax(json.dumps(ok))
    assert graph.description == payload
    # As a whole answer (Python, not JSON): junk feedback.
    with pytest.raises(AnswerError):
        parse_answer(payload, SubtaskDesign)
    assert not marker.exists()


def test_no_module_calls_exec_eval_or_compile() -> None:
    roots = [Path(factask.gen.__file__).parent, Path(factask.evaluation.__file__).parent]
    offenders = []
    for root in roots:
        for path in root.rglob("*.py"):
            tree = ast.parse(path.read_text())
            for node in ast.walk(tree):
                if isinstance(node, ast.Call):
                    fn = node.func
                    # Builtins by name; as attributes only exec/eval/__import__ (so that
                    # re.compile, a regex, is allowed).
                    if (isinstance(fn, ast.Name) and fn.id in ("exec", "eval", "compile",
                                                               "__import__")) or (
                            isinstance(fn, ast.Attribute) and fn.attr in ("exec", "eval",
                                                                          "__import__")):
                        offenders.append(f"{path.name}:{node.lineno} {ast.unparse(fn)}")
    assert offenders == []
