"""Reading answers: JSON extraction, schema validation, precise feedback, never exec."""

from __future__ import annotations

import ast
import json
from pathlib import Path

import pytest

import factask.evaluation
import factask.gen
from factask.gen.answers.schemas import (
    AnswerError,
    GoalAnswer,
    SubtaskDesign,
    VariablesAnswer,
    extract_json,
    parse_answer,
)
from factask.gen.demo import demo_graph
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


# ---------------------------------------------------------------- review fixes
def test_deeply_nested_answer_is_feedback_not_a_crash() -> None:
    deep = '{"a":' * 1500 + "1" + "}" * 1500
    with pytest.raises(AnswerError, match="nested too deeply"):
        extract_json(deep)
    with pytest.raises(AnswerError):
        parse_answer(deep, VariablesAnswer)
    with pytest.raises(AnswerError):
        graph_syntax(deep)


def test_top_level_array_is_reported_not_taken() -> None:
    with pytest.raises(AnswerError, match="not an array"):
        extract_json(json.dumps([GRAPH]))
    with pytest.raises(AnswerError, match="not an array"):
        extract_json("Here you go:\n```json\n" + json.dumps([GRAPH, GRAPH]) + "\n```")


def test_stray_brace_in_prose_does_not_hide_the_object() -> None:
    text = "I will use the { layout from before. Answer:\n" + json.dumps(GRAPH) + "\nbye"
    assert extract_json(text) == GRAPH
    # A cut-off answer is still not mistaken for one of its inner objects.
    with pytest.raises(AnswerError, match="cut off"):
        extract_json("Answer: " + json.dumps(GRAPH)[:-40])


def test_several_objects_are_mentioned_in_the_feedback() -> None:
    text = '{"objects": ["red"]}\nor maybe\n{"variables": []}'
    with pytest.raises(AnswerError, match="2 JSON objects; only the first") as info:
        parse_answer(text, VariablesAnswer)
    assert "VariablesAnswer" in info.value.feedback
    with pytest.raises(AnswerError, match="2 JSON objects"):
        graph_syntax(json.dumps(_mutated(**{"variables.1.color": "sparkly"})) + "\n{}")
    assert extract_json('{"a": 1} {"b": 2}') == {"a": 1}


def test_oversized_plans_get_feedback_asking_to_merge_steps() -> None:
    from factask.gen.answers.schemas import (
        MAX_FACTORS,
        MAX_SUBTASKS,
        SubtaskOutline,
        SubtaskPlan,
        check_graph_size,
    )
    from factask.graph import parse_graph

    many = [{"name": f"s{i}", "description": "d"} for i in range(MAX_SUBTASKS + 1)]
    with pytest.raises(AnswerError, match="merge steps"):
        parse_answer(json.dumps({"subtasks": many}), SubtaskOutline)
    plan = [{**s, "variables": ["red_block"]} for s in many]
    with pytest.raises(AnswerError, match="merge steps"):
        parse_answer(json.dumps({"subtasks": plan}), SubtaskPlan)
    assert len(parse_answer(json.dumps({"subtasks": plan[:MAX_SUBTASKS]}),
                            SubtaskPlan).subtasks) == MAX_SUBTASKS
    var = GRAPH["variables"][0]
    with pytest.raises(AnswerError, match="merge steps"):
        parse_answer(json.dumps({"variables": [{**var, "name": f"v{i}"} for i in range(33)]}),
                     VariablesAnswer)
    graph = parse_graph(GRAPH)
    check_graph_size(graph)  # within limits
    big = graph.model_copy(update={"factors": graph.factors * (MAX_FACTORS // 2 + 1)})
    with pytest.raises(AnswerError, match="merge steps"):
        check_graph_size(big)
