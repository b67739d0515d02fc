"""Property tests of every parser of outside input in generation: server replies,
provider errors, answers against the strict step schemas, weights, prompts."""

from __future__ import annotations

import json

import pytest
from hypothesis import given
from hypothesis import strategies as st

from factask.gen.answers.schemas import AnswerError
from factask.gen.answers.step_schemas import all_step_schemas, goal_answer, schema_problems
from factask.gen.conversation import normalised_answer, sampling
from factask.gen.llm import backoff_delays
from factask.gen.llm_errors import (
    LLMContextError,
    LLMError,
    LLMFatalError,
    LLMQuotaError,
    LLMTransientError,
    classify_llm_exception,
    one_line,
)
from factask.gen.local import parse_count_reply, parse_models_reply
from factask.gen.prompts import schema_skeleton
from factask.gen.steps import read_strict
from factask.gen.strategies import normalise_weights

JSON = st.recursive(st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False)
                    | st.text(max_size=20),
                    lambda inner: st.lists(inner, max_size=4)
                    | st.dictionaries(st.text(max_size=8), inner, max_size=4), max_leaves=20)
SCHEMAS = all_step_schemas()


@given(st.binary(max_size=200) | JSON.map(lambda v: json.dumps(v).encode()))
def test_server_replies_never_crash_the_readers(body: bytes) -> None:
    ids = parse_models_reply(body)
    assert isinstance(ids, list) and all(isinstance(i, str) for i in ids)
    count = parse_count_reply(body)
    assert count is None or (isinstance(count, int) and count >= 0)


@given(st.lists(st.text(min_size=1, max_size=10), max_size=5), st.integers(0, 10**6))
def test_well_formed_server_replies_are_read(ids: list[str], n: int) -> None:
    body = json.dumps({"data": [{"id": i, "object": "model"} for i in ids]}).encode()
    assert parse_models_reply(body) == ids
    assert parse_count_reply(json.dumps({"count": n}).encode()) == n
    assert parse_count_reply(json.dumps({"count": -1 - n}).encode()) is None


@given(st.text(max_size=300), st.none() | st.integers(100, 599))
def test_any_provider_error_is_classified_into_an_llm_error(message: str, status) -> None:
    exc = type("ProviderError", (Exception,), {"status_code": status})(message)
    kind = classify_llm_exception(exc)
    assert issubclass(kind, LLMError)
    if status in (401, 403):
        assert issubclass(kind, LLMFatalError)
    if status is None:
        assert kind is LLMTransientError


def test_quota_and_context_messages_are_fatal_and_plain_overload_is_transient() -> None:
    def err(status: int, msg: str) -> Exception:
        return type("E", (Exception,), {"status_code": status})(msg)

    assert classify_llm_exception(err(429, "insufficient_quota: check billing")) is LLMQuotaError
    assert classify_llm_exception(err(429, "slow down")) is LLMTransientError
    assert classify_llm_exception(err(400, "maximum context length is 8192")) is LLMContextError
    assert classify_llm_exception(err(503, "overloaded")) is LLMTransientError


@given(st.text(max_size=500))
def test_one_line_is_one_bounded_line(text: str) -> None:
    line = one_line(text, 120)
    assert "\n" not in line and len(line) <= 120


@given(st.integers(0, 12))
def test_backoff_is_bounded_and_grows(retries: int) -> None:
    delays = backoff_delays(retries)
    assert len(delays) == retries and all(0 < d <= 8.0 for d in delays)
    assert delays == sorted(delays)


@given(st.sampled_from(sorted(SCHEMAS)), JSON)
def test_schema_check_of_any_json_never_crashes(step: str, data) -> None:
    problems = schema_problems(data, SCHEMAS[step])
    assert all(isinstance(p, str) and p for p in problems)


@given(st.text(max_size=400))
def test_reading_any_text_against_a_schema_raises_only_answer_errors(text: str) -> None:
    try:
        data = read_strict(text, SCHEMAS["subtask_outline"])
    except AnswerError as exc:
        assert exc.feedback
    else:  # accepted only if it really follows the schema
        assert schema_problems(data, SCHEMAS["subtask_outline"]) == []
        assert data["subtasks"]


def test_a_valid_outline_is_read() -> None:
    text = 'Sure: {"subtasks": [{"name": "put_red", "description": "red in zone"}]}'
    assert read_strict(text, SCHEMAS["subtask_outline"])["subtasks"][0]["name"] == "put_red"


@given(st.sampled_from(["red_block", "blue_block"]), st.text(max_size=30))
def test_a_goal_may_name_only_the_declared_variables(good: str, other: str) -> None:
    schema = goal_answer({"red_block": "block", "blue_block": "block", "zone": "zone"})
    answer = {"goal": {"type": "in_zone", "objects": [good], "zone": "zone"},
              "description": "x"}
    assert schema_problems(answer, schema) == []
    bad = {**answer, "goal": {**answer["goal"], "objects": [other]}}
    assert (schema_problems(bad, schema) == []) == (other in ("red_block", "blue_block"))


@given(st.text(max_size=60))
def test_strings_with_control_characters_quotes_or_backslashes_are_refused(text: str) -> None:
    answer = {"subtasks": [{"name": "place_it", "description": text, "after": []}]}
    ok = not schema_problems(answer, SCHEMAS["subtask_outline"])
    assert ok == all(" " <= c <= "~" and c not in "\"\\" for c in text)


@given(st.lists(st.floats(0.001, 100) | st.integers(-3, 3) | st.none(), min_size=0,
                max_size=6))
def test_weights_are_normalised_only_when_all_positive(weights) -> None:
    data = {"factors": [{"weight": w} for w in weights]}
    out = normalise_weights(data)
    if weights and all(isinstance(w, (int, float)) and w > 0 for w in weights):
        assert abs(sum(f["weight"] for f in out["factors"]) - 1.0) < 1e-9
    else:
        assert out == data


@given(st.text(max_size=200))
def test_answers_compare_by_content(text: str) -> None:
    assert normalised_answer(text) == normalised_answer(f"  {text}  ")


@given(JSON)
def test_json_answers_compare_by_value(value) -> None:
    assert normalised_answer(json.dumps(value)) == normalised_answer(json.dumps(value,
                                                                                indent=2))


@given(st.integers(0, 10), st.floats(0, 1), st.integers(0, 1000))
def test_retries_sample_differently(attempt: int, temperature: float, seed: int) -> None:
    t, s = sampling(attempt, temperature, seed)
    assert 0 <= t <= 1
    if attempt == 0:
        assert (t, s) == (temperature, seed)
    else:
        assert s != seed and t >= temperature and t > 0


def test_every_step_schema_is_strict_and_its_skeleton_is_short() -> None:
    from jsonschema import Draft202012Validator

    def walk(node):
        if isinstance(node, dict):
            if node.get("type") == "object" and "properties" in node:
                assert set(node["required"]) == set(node["properties"])
                assert node["additionalProperties"] is False
            if node.get("type") == "string":
                assert {"enum", "pattern", "const"} & set(node)
            for v in node.values():
                walk(v)
        elif isinstance(node, list):
            for v in node:
                walk(v)

    for step, schema in SCHEMAS.items():
        Draft202012Validator.check_schema(schema)
        walk(schema)
        assert len(schema_skeleton(schema)) < len(json.dumps(schema)) / 2, step


def test_llama_grammar_schema_keeps_the_length_bound_and_drops_only_the_text_pattern() -> None:
    from factask.gen.providers import for_llama_grammar, response_format_param

    schema = SCHEMAS["subtask_outline"]
    sent = response_format_param("llama_cpp", schema, "outline")
    assert sent is not None and sent["type"] == "json_object"
    desc = sent["schema"]["properties"]["subtasks"]["items"]["properties"]["description"]
    assert desc == {"type": "string", "maxLength": 100}
    name = sent["schema"]["properties"]["subtasks"]["items"]["properties"]["name"]
    # No character class repeated a bounded number of times; the parts still bounded.
    assert name["pattern"] == "^[a-z][a-z0-9]*(_[a-z0-9]+)?(_[a-z0-9]+)?(_[a-z0-9]+)?$"
    assert for_llama_grammar(schema) != schema and schema_problems(
        {"subtasks": [{"name": "a", "description": "x\ny"}]}, schema)  # the check keeps it


@given(st.floats(0.5001, 1e6, allow_nan=False) | st.floats(-1e6, 0.0, allow_nan=False))
def test_an_out_of_range_optional_number_is_reported_with_its_bound(spacing: float) -> None:
    # A nullable number is an anyOf [number, null]: the feedback must name the bound
    # the number broke, not "not valid under any of the given schemas".
    schema = goal_answer({"red_block": "block", "blue_block": "block"})
    answer = {"goal": {"type": "row", "objects": ["red_block"], "spacing": spacing,
                       "along": None, "on": None, "ordered": False}, "description": "x"}
    problems = schema_problems(answer, schema)
    assert len(problems) == 1 and problems[0].startswith("goal.spacing: ")
    assert "maximum of 0.5" in problems[0] or "less than or equal to the minimum" \
        in problems[0], problems


def _numbers(node: object) -> list[dict]:
    """Every number schema (or enum of numbers) in a schema tree."""
    found: list[dict] = []
    if isinstance(node, dict):
        if node.get("type") in ("number", "integer") or (
                "enum" in node and node["enum"] and all(
                    isinstance(v, (int, float)) and not isinstance(v, bool)
                    for v in node["enum"])):
            found.append(node)
        for v in node.values():
            found += _numbers(v)
    elif isinstance(node, list):
        for v in node:
            found += _numbers(v)
    return found


@pytest.mark.parametrize("step", sorted(SCHEMAS))
def test_llama_grammar_numbers_are_round_values_within_the_bounds(step: str) -> None:
    from jsonschema import Draft202012Validator

    from factask.gen.providers import for_llama_grammar

    sent = for_llama_grammar(SCHEMAS[step])
    for node in _numbers(sent):
        # Bounded numbers became enums; every value passes the real schema's bounds.
        assert "enum" in node, (step, node)
        assert node["enum"] == sorted(node["enum"]) and 5 <= len(node["enum"]) <= 40
    for strict, loose in zip(_numbers(SCHEMAS[step]), _numbers(sent), strict=True):
        for value in loose["enum"]:
            assert Draft202012Validator(strict).is_valid(value), (step, strict, value)


def test_a_size_taller_than_the_workspace_breaks_the_variables_schema() -> None:
    variable = {"name": "zone", "description": "x", "kind": "zone", "size": [0.3, 0.3, 0.75],
                "color": "green", "count": 1, "fixed": None, "initial": {"type": "table"}}
    problems = schema_problems({"variables": [variable]}, SCHEMAS["variables"])
    assert problems == ["variables.0.size.2: 0.75 is greater than the maximum of 0.3"]


def test_a_text_field_ending_in_a_newline_is_refused() -> None:
    # Python's ``$`` matches before a final newline; JSON Schema's does not.
    answer = {"subtasks": [{"name": "place_it", "description": "ok\n"}]}
    assert schema_problems(answer, SCHEMAS["subtask_outline"])


@given(st.lists(st.from_regex(r"[a-z][a-z0-9]{0,5}", fullmatch=True), min_size=1, max_size=6))
def test_the_grammar_name_pattern_bounds_the_parts_as_the_check_does(parts: list[str]) -> None:
    import re

    from factask.gen.answers.step_schemas import NAME_REGEX
    from factask.gen.providers import for_llama_grammar

    name = "_".join(parts)
    loose = for_llama_grammar({"type": "string", "pattern": NAME_REGEX})["pattern"]
    # Parts of at most 15 characters: the grammar allows a name iff the check does.
    assert bool(re.fullmatch(loose, name)) == bool(re.fullmatch(NAME_REGEX, name))


@given(st.lists(st.sampled_from(["a", "b", "a_2", "put_x"]), max_size=8),
       st.lists(st.sampled_from(["a", "b", "c"]), max_size=3))
def test_distinct_names_are_distinct_and_keep_first_uses(names, taken) -> None:
    from factask.gen.fragments import distinct_names

    out = distinct_names(names, taken)
    assert len(out) == len(names) and len(set(out)) == len(out)
    assert not set(out) & set(taken)
    for n, o in zip(names, out, strict=True):
        assert o == n or o.startswith(f"{n}_")
    for i, n in enumerate(names):  # a first use of a free name is kept as it is
        if n not in taken and n not in names[:i] and n not in out[:i]:
            assert out[i] == n


def test_a_repeated_variable_is_dropped_only_where_nothing_is_lost() -> None:
    from factask.gen.fragments import without_repeats
    from factask.vocabulary.variables import StateVariable

    red = StateVariable(name="blocks", kind="block", color="red", count=2)
    again = red.model_copy(update={"description": "the same, described again"})
    blue = StateVariable(name="blocks", kind="block", color="blue", count=2)
    assert without_repeats([red, again]) == [red]
    assert without_repeats([red, blue]) == [red, blue]  # two objects: the check reports it
    assert without_repeats([red, blue], named=["blocks"]) == [red]  # the proposal's wins
