"""What each generation step asks the model for, as pydantic schemas, and how an
answer is read.

An answer is *data*: :func:`extract_json` finds the first JSON object in the
text (tolerating ```json fences and leading prose), pydantic validates it
against the step's schema, and every failure becomes an :class:`AnswerError`
whose message is precise enough to send back to the model. Nothing in an answer
is ever executed.
"""

from __future__ import annotations

import json
import re
from typing import Any, TypeVar

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from factask.model.errors import FactaskError, Problem
from factask.model.graph import problems_from_pydantic
from factask.model.names import Name
from factask.model.relations import Relation
from factask.model.variables import StateVariable

T = TypeVar("T", bound=BaseModel)

_FENCE_RE = re.compile(r"```(?:json|JSON)?\s*\n?(.*?)```", re.DOTALL)


class AnswerError(FactaskError):
    """An answer is not usable; ``feedback`` says exactly why (sent to the model).

    Attributes:
        feedback: The message for the model.
        problems: Structured problems where known.
    """

    def __init__(self, feedback: str, problems: list[Problem] | None = None) -> None:
        self.feedback = feedback
        self.problems = list(problems or [])
        super().__init__(feedback)


# --------------------------------------------------------------------- schemas
class VariablesAnswer(BaseModel):
    """Approach 1, step 1: the task's state variables."""

    model_config = ConfigDict(extra="forbid")
    variables: list[StateVariable] = Field(min_length=1)


class PlannedSubtask(BaseModel):
    """Approach 1, step 2: one subtask over a subset of the variables."""

    model_config = ConfigDict(extra="forbid")
    name: Name
    description: str
    variables: list[Name] = Field(min_length=1,
                                  description="The variables this subtask uses.")
    initial_setup: str = Field("", description="What must already hold before it runs.")


class SubtaskPlan(BaseModel):
    """Approach 1, step 2: the subtasks, in the order they are done."""

    model_config = ConfigDict(extra="forbid")
    subtasks: list[PlannedSubtask] = Field(min_length=1)


class GoalAnswer(BaseModel):
    """Approach 1, step 3: one subtask's goal relation."""

    model_config = ConfigDict(extra="forbid")
    goal: Relation
    description: str = Field("", description="Language goal; default the planned one.")


class OutlinedSubtask(BaseModel):
    """Approach 2, step 1: a subtask's name and description."""

    model_config = ConfigDict(extra="forbid")
    name: Name
    description: str


class SubtaskOutline(BaseModel):
    """Approach 2, step 1: the subtasks, in the order they are done."""

    model_config = ConfigDict(extra="forbid")
    subtasks: list[OutlinedSubtask] = Field(min_length=1)


class SubtaskDesign(BaseModel):
    """Approach 2, step 2: one subtask's own variables and its goal."""

    model_config = ConfigDict(extra="forbid")
    variables: list[StateVariable] = Field(
        default_factory=list,
        description="Variables the subtask uses; reuse an earlier subtask's variable by "
                    "repeating it identically (or leave it out: it is taken as is).")
    goal: Relation
    description: str = ""


# --------------------------------------------------------------------- parsing
def _top_level_objects(text: str) -> tuple[list[str], bool]:
    """Balanced top-level ``{...}`` spans of ``text`` (JSON strings respected), and
    whether an object was still open at the end (a truncated answer)."""
    spans: list[str] = []
    depth, start, in_str, esc = 0, -1, False, False
    for i, ch in enumerate(text):
        if depth and in_str:
            if esc:
                esc = False
            elif ch == "\\":
                esc = True
            elif ch == '"':
                in_str = False
            continue
        if ch == '"' and depth:
            in_str = True
        elif ch == "{":
            if depth == 0:
                start = i
            depth += 1
        elif ch == "}" and depth:
            depth -= 1
            if depth == 0:
                spans.append(text[start:i + 1])
    return spans, depth > 0


def extract_json(text: str) -> Any:
    """The first JSON object in ``text``.

    Accepts a bare object, one inside a Markdown fence, or one after leading
    prose; trailing text after the object is ignored. Only *top-level* objects
    count: an object nested in a truncated answer is never taken for the answer.

    Args:
        text: The model's answer.

    Returns:
        The decoded object (a dict).

    Raises:
        AnswerError: no JSON object can be read; the message says what was seen.
    """
    if not text or not text.strip():
        raise AnswerError("The answer was empty. Reply with one JSON object only.")
    candidates = [m.group(1) for m in _FENCE_RE.finditer(text)] + [text]
    last_error = ""
    truncated = False
    for candidate in candidates:
        spans, open_end = _top_level_objects(candidate)
        truncated = truncated or open_end
        for span in spans:
            try:
                value = json.loads(span)
            except json.JSONDecodeError as exc:
                last_error = f"{exc.msg} at line {exc.lineno} column {exc.colno}"
                continue
            if isinstance(value, dict):
                return value
    snippet = text.strip()[:160].replace("\n", " ")
    detail = f" (JSON error: {last_error})" if last_error else ""
    if truncated:
        detail += " (the object is not closed: the answer looks cut off, keep it shorter)"
    raise AnswerError(
        "The answer contains no complete JSON object" + detail + f". It began: {snippet!r}. "
        "Reply with exactly one JSON object following the schema, nothing else."
    )


def format_problems(problems: list[Problem], limit: int = 25) -> str:
    """One problem per line, each naming its node and field."""
    lines = [f"- {p}" for p in problems[:limit]]
    if len(problems) > limit:
        lines.append(f"- ... and {len(problems) - limit} more")
    return "\n".join(lines)


def validate_answer(data: Any, schema: type[T]) -> T:
    """Validate decoded JSON against a step schema.

    Args:
        data: The decoded answer.
        schema: The step's pydantic model.

    Returns:
        The validated model.

    Raises:
        AnswerError: listing every validation error, each naming its node/field.
    """
    try:
        return schema.model_validate(data)
    except ValidationError as exc:
        problems = problems_from_pydantic(exc, data)
        raise AnswerError(
            f"The answer does not match the {schema.__name__} schema "
            f"({len(problems)} problem(s)):\n{format_problems(problems)}", problems
        ) from None


def parse_answer(text: str, schema: type[T]) -> T:
    """:func:`extract_json` then :func:`validate_answer`."""
    return validate_answer(extract_json(text), schema)


def schema_of(model: type[BaseModel]) -> dict[str, Any]:
    """The JSON Schema of a step's answer (sent as structured-output format)."""
    return model.model_json_schema()
