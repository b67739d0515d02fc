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

from factask.graph.taskgraph import problems_from_pydantic
from factask.relations import Relation
from factask.vocabulary.errors import FactaskError, Problem
from factask.vocabulary.names import Name
from factask.vocabulary.variables import StateVariable

T = TypeVar("T", bound=BaseModel)

#: Plan size limits: an answer beyond them is sent back asking to merge steps.
MAX_SUBTASKS = 12
MAX_VARIABLES = 32
MAX_FACTORS = 16
_TOO_LONG_HINT = (f"The plan is too big (at most {MAX_SUBTASKS} subtasks, {MAX_VARIABLES} "
                  f"variables, {MAX_FACTORS} factors): merge steps into fewer, larger "
                  "subtasks and use counts (`count`) instead of one variable per object.")

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
    variables: list[StateVariable] = Field(min_length=1, max_length=MAX_VARIABLES)


class PlannedSubtask(BaseModel):
    """Approach 1, step 2: one subtask over a subset of the variables."""

    model_config = ConfigDict(extra="forbid")
    name: Name
    description: str
    variables: list[Name] = Field(min_length=1, max_length=MAX_VARIABLES,
                                  description="The variables this subtask uses.")
    initial_setup: str = Field("", description="What must already hold before it runs.")
    after: list[Name] = Field(default_factory=list, max_length=MAX_SUBTASKS,
                              description="Earlier subtasks that must be done first.")


class SubtaskPlan(BaseModel):
    """Approach 1, step 2: the subtasks, in the order they are done."""

    model_config = ConfigDict(extra="forbid")
    subtasks: list[PlannedSubtask] = Field(min_length=1, max_length=MAX_SUBTASKS)


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
    after: list[Name] = Field(default_factory=list, max_length=MAX_SUBTASKS,
                              description="Earlier subtasks that must be done first.")


class SubtaskOutline(BaseModel):
    """Approach 2, step 1: the subtasks, in the order they are done."""

    model_config = ConfigDict(extra="forbid")
    subtasks: list[OutlinedSubtask] = Field(min_length=1, max_length=MAX_SUBTASKS)


class SubtaskDesign(BaseModel):
    """Approach 2, step 2: one subtask's own variables and its goal."""

    model_config = ConfigDict(extra="forbid")
    variables: list[StateVariable] = Field(
        default_factory=list, max_length=MAX_VARIABLES,
        description="Variables the subtask uses; reuse an earlier subtask's variable by "
                    "repeating it identically (or leave it out: it is taken as is).")
    goal: Relation
    description: str = ""


# --------------------------------------------------------------------- parsing
_DECODER = json.JSONDecoder()


def _depth_error() -> AnswerError:
    return AnswerError("The answer is nested too deeply to read. Reply with one flat JSON "
                       "object following the schema.")


def _scan(candidate: str) -> tuple[list[dict[str, Any]], bool, str, bool]:
    """Top-level JSON objects of ``candidate`` in order.

    Every ``{`` outside an object already read is tried with
    :meth:`json.JSONDecoder.raw_decode`, so a stray ``{`` in prose does not hide a
    complete object after it. A ``{`` whose object runs to the end of the text (a
    cut-off answer) stops the scan: the objects inside it are not answers.

    Returns:
        (objects, truncated, last decode error, an array of objects came first).
    """
    found: list[dict[str, Any]] = []
    last_error = ""
    end_of_text = len(candidate.rstrip())
    first_brace = candidate.find("{")
    first_bracket = candidate.find("[")
    if first_bracket != -1 and (first_brace == -1 or first_bracket < first_brace):
        try:
            value, _ = _DECODER.raw_decode(candidate, first_bracket)
        except RecursionError:
            raise _depth_error() from None
        except ValueError:
            value = None
        if isinstance(value, list) and (not value or any(isinstance(v, dict) for v in value)):
            return found, False, "", True
    i = first_brace
    while i != -1:
        try:
            value, end = _DECODER.raw_decode(candidate, i)
        except RecursionError:
            raise _depth_error() from None
        except json.JSONDecodeError as exc:
            last_error = f"{exc.msg} at line {exc.lineno} column {exc.colno}"
            if exc.pos >= end_of_text or exc.msg.startswith("Unterminated string"):
                return found, True, last_error, False
            i = candidate.find("{", i + 1)
            continue
        except ValueError as exc:
            last_error = str(exc)
            i = candidate.find("{", i + 1)
            continue
        if isinstance(value, dict):
            found.append(value)
        i = candidate.find("{", end)
    return found, False, last_error, False


def read_json(text: str) -> tuple[dict[str, Any], int]:
    """The first JSON object in ``text`` and how many top-level objects it holds.

    See :func:`extract_json`.
    """
    if not text or not text.strip():
        raise AnswerError("The answer was empty. Reply with one JSON object only.")
    fenced = [m.group(1) for m in _FENCE_RE.finditer(text)]
    last_error = ""
    truncated = False
    for group in ([fenced] if fenced else []) + [[text]]:
        objects: list[dict[str, Any]] = []
        for candidate in group:
            found, cut, error, array = _scan(candidate)
            if array and not objects:
                raise AnswerError("The answer is a JSON array. Send one JSON object "
                                  "following the schema, not an array.")
            objects += found
            truncated = truncated or cut
            last_error = error or last_error
        if objects:
            return objects[0], len(objects)
    snippet = text.strip()[:160].replace("\n", " ")
    detail = f" (JSON error: {last_error})" if last_error else ""
    if truncated:
        detail += " (the object is not closed: the answer looks cut off, keep it shorter)"
    raise AnswerError(
        "The answer contains no complete JSON object" + detail + f". It began: {snippet!r}. "
        "Reply with exactly one JSON object following the schema, nothing else."
    )


def extract_json(text: str) -> Any:
    """The first JSON object in ``text``.

    Accepts a bare object, one inside a Markdown fence, or one after leading
    prose (a stray ``{`` in the prose included); trailing text after the object
    is ignored. Only *top-level* objects count: an object nested in a truncated
    answer is never taken for the answer.

    Args:
        text: The model's answer.

    Returns:
        The decoded object (a dict).

    Raises:
        AnswerError: no JSON object can be read, the answer is an array, or it is
            nested too deeply; the message says what was seen.
    """
    return read_json(text)[0]


def several_objects_note(count: int) -> str:
    """A feedback line for an answer holding ``count`` top-level objects ('' for 1)."""
    if count <= 1:
        return ""
    return (f"\nNote: the answer contained {count} JSON objects; only the first was read. "
            "Send exactly one JSON object.")


def format_problems(problems: list[Problem], limit: int = 25) -> str:
    """One problem per line, each naming its node and field."""
    lines = [f"- {p}" for p in problems[:limit]]
    if len(problems) > limit:
        lines.append(f"- ... and {len(problems) - limit} more")
    return "\n".join(lines)


def validate_answer(data: Any, schema: type[T], note: str = "") -> T:
    """Validate decoded JSON against a step schema.

    Args:
        data: The decoded answer.
        schema: The step's pydantic model.
        note: Appended to the feedback (e.g. :func:`several_objects_note`).

    Returns:
        The validated model.

    Raises:
        AnswerError: listing every validation error, each naming its node/field.
    """
    try:
        return schema.model_validate(data)
    except RecursionError:
        raise _depth_error() from None
    except ValidationError as exc:
        problems = problems_from_pydantic(exc, data)
        hint = ("\n" + _TOO_LONG_HINT) if any(e.get("type") == "too_long"
                                              for e in exc.errors()) else ""
        raise AnswerError(
            f"The answer does not match the {schema.__name__} schema "
            f"({len(problems)} problem(s)):\n{format_problems(problems)}{hint}{note}", problems
        ) from None


def parse_answer(text: str, schema: type[T]) -> T:
    """:func:`extract_json` then :func:`validate_answer` (the feedback says so when
    the answer held several objects)."""
    data, count = read_json(text)
    return validate_answer(data, schema, several_objects_note(count))


def check_graph_size(graph: Any) -> None:
    """A whole graph within the plan limits (:data:`MAX_FACTORS`, :data:`MAX_VARIABLES`).

    Raises:
        AnswerError: too many factors or variables, asking to merge steps.
    """
    problems = []
    if len(graph.factors) > MAX_FACTORS:
        problems.append(Problem("", "factors", f"{len(graph.factors)} factors; at most "
                                f"{MAX_FACTORS}", "merge steps"))
    if len(graph.variables) > MAX_VARIABLES:
        problems.append(Problem("", "variables", f"{len(graph.variables)} variables; at most "
                                f"{MAX_VARIABLES}", "use counts or fewer objects"))
    if problems:
        raise AnswerError(f"The task graph is too big:\n{format_problems(problems)}\n"
                          f"{_TOO_LONG_HINT}", problems)


def schema_of(model: type[BaseModel]) -> dict[str, Any]:
    """The JSON Schema of a step's answer (sent as structured-output format)."""
    return model.model_json_schema()
