"""The reader-only model (factask.gen.first_choice): the first choice of every step
schema, through the real pipeline over HTTP (issue 34, part 6)."""

from __future__ import annotations

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from factask.cli.app import app
from factask.gen.answers.step_schemas import all_step_schemas, schema_problems
from factask.gen.first_choice import FirstChoiceError, FirstChoiceResponder, first_choice
from factask.gen.reading import grounded
from factask.gen.reading.mentions import mentions
from factask.vocabulary.palette import COLOR_NAMES


@pytest.mark.parametrize("step", sorted(all_step_schemas()))
def test_the_first_choice_of_every_step_schema_follows_it(step: str) -> None:
    schema = all_step_schemas()[step]
    answer = first_choice(schema)
    assert schema_problems(answer, schema) == []
    assert first_choice(schema) == answer  # deterministic


@settings(max_examples=25, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(sorted(COLOR_NAMES)),
                          st.sampled_from(["block", "ball", "cylinder"])), min_size=1,
                max_size=3, unique=True),
       st.sampled_from(sorted(COLOR_NAMES)), st.sampled_from(["bowl", "zone"]))
def test_the_first_choice_of_a_grounded_schema_follows_it(movers, color, anchor) -> None:
    proposal = (" and ".join(f"put the {c} {k}" for c, k in movers)
                + f" in the {color} {anchor}")
    found = mentions(proposal)
    for schema in (grounded.variables_answer(found),
                   grounded.compact_graph_schema(found, proposal)):
        assert schema_problems(first_choice(schema), schema) == []


@pytest.mark.parametrize(("schema", "says"), [
    ({"enum": []}, "empty enum"),
    ({"$ref": "#/$defs/a", "$defs": {"a": {"$ref": "#/$defs/a"}}}, "deeper than 64"),
    ({"$ref": "http://example.com/s.json"}, "only local references"),
    ({"type": "string", "pattern": "^[A-Z]{3}$"}, "no short string matches"),
    ({"type": "array", "minItems": 2, "prefixItems": [{"type": "null"}], "items": False},
     "more items than its schema allows"),
    ({"not": {"type": "null"}}, "no instance"),
])
def test_a_schema_without_a_first_choice_is_a_typed_error(schema, says) -> None:
    with pytest.raises(FirstChoiceError, match=says):
        first_choice(schema)


def test_free_names_are_distinct_within_an_answer() -> None:
    name = {"type": "string", "pattern": "^[a-z][a-z0-9_]*$"}
    answer = first_choice({"type": "array", "prefixItems": [name, name, name]})
    assert len(set(answer)) == 3


def test_the_responder_refuses_a_request_with_no_schema() -> None:
    with pytest.raises(FirstChoiceError, match="only requests that send a schema"):
        FirstChoiceResponder()({"messages": []})
    reply = FirstChoiceResponder()({"response_format": {
        "type": "json_schema", "json_schema": {"name": "a", "schema": {"const": 3}}}})
    assert json.loads(reply) == 3


def test_generate_with_the_reader_writes_the_graph_the_words_mean(tmp_path) -> None:
    """No model at all: the reading and the schema's first choices make the task."""
    out = tmp_path / "g.json"
    ref = tmp_path / "ref.json"
    ref.write_text(json.dumps({
        "name": "ref", "variables": [
            {"name": "red_block", "kind": "block", "color": "red"},
            {"name": "green_bowl", "kind": "bowl", "color": "green"}],
        "factors": [{"name": "f", "goal": {"type": "inside", "objects": ["red_block"],
                                           "container": "green_bowl"}}]}))
    result = CliRunner().invoke(app, [
        "generate", "put the red block in the green bowl", "--model", "local/reader",
        "--approach", "one-shot", "--episodes", "1", "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "local/reader" in result.output
    same = CliRunner().invoke(app, ["compare", str(out), str(ref)])
    assert same.exit_code == 0, same.output
