"""The machinery every strategy's steps share: ask, read, check, feed back.

:class:`StepRunner` holds one generation's state (the result being built, the
task) and runs one step as a conversation (:meth:`StepRunner.ask`): the prompt
variant that fits the model's context, ``max_tokens`` sized to the step, the
step's strict schema sent in the provider's form, the answer checked against
that schema and then by the step's own evaluation (the verification ladder),
and the feedback sent back — each retry sampled differently, stopping early
when the model repeats itself (:mod:`factask.gen.conversation`).
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

from pydantic import BaseModel

from factask.gen.answers.examples import (
    Example,
    library_task_examples,
    render_examples,
    template_examples,
)
from factask.gen.answers.schemas import (
    AnswerError,
    read_json,
    several_objects_note,
    validate_answer,
)
from factask.gen.answers.step_schemas import empty_choices, schema_problems, with_empty_fields
from factask.gen.conversation import (
    RETRY_TEMPERATURES,
    Budget,
    PromptLevel,
    answer_tokens,
    cut_feedback,
    normalised_answer,
    sampling,
)
from factask.gen.llm import LLMClient, LLMError, LLMRequestError, Usage
from factask.gen.memory import SubtaskMemory, SubtaskMemoryError
from factask.gen.prompts import render, schema_skeleton, schema_text
from factask.gen.results import AttemptRecord, GenerationResult
from factask.gen.verify import Level, Verifier, at_least, level_index
from factask.graph.taskgraph import TaskGraph, parse_graph
from factask.vocabulary.errors import FactaskError, GraphValidationError, InvalidValueError

T = TypeVar("T")
M = TypeVar("M", bound=BaseModel)

#: A step stops once the model has repeated earlier answers this many times.
MAX_REPEATS = 2
StepCallback = Callable[[AttemptRecord], None]
#: An evaluation turns answer text into (artefact or None, level, feedback or None).
Evaluation = tuple[Any, Level, "str | None"]
PromptBuilder = Callable[[PromptLevel], str]


class Abort(FactaskError):
    """A planning step never produced a usable answer; the generation stops."""


@dataclass
class Outcome(Generic[T]):
    """What a step ended with: the best artefact, its level, whether it passed."""

    value: T | None
    level: Level
    ok: bool
    feedback: str | None


def read_strict(text: str, schema: Mapping[str, Any],
                overrides: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """The answer's JSON object, checked against the step's strict schema.

    Args:
        text: The model's answer.
        schema: The step's schema (:mod:`factask.gen.answers.step_schemas`).
        overrides: Top-level values that are ours, not the model's (the task's
            name), set before the check.

    Returns:
        The decoded object.

    Raises:
        AnswerError: not JSON, or every place it breaks the schema.
    """
    data, count = read_json(text)
    if overrides:
        data = {**data, **overrides}
    data = with_empty_fields(data, schema)  # a left-out "none" is not a mistake
    problems = schema_problems(data, schema)
    if problems:
        lines = "\n".join(f"- {p}" for p in problems)
        raise AnswerError(f"The answer does not follow the schema ({len(problems)} "
                          f"problem(s)):\n{lines}{several_objects_note(count)}")
    return data


def read_graph_answer(text: str, schema: Mapping[str, Any],
                      overrides: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """A whole-graph answer: checked against the step's strict schema, or, where that
    refuses it, accepted when it is a valid task graph all the same.

    The strict schema is the grammar a small model is held to (fewer, shorter fields);
    a capable model that writes what ``factask schema`` or ``factask show --json``
    print (``fixed``, ``tolerances``, ``scope``, a long description) writes a valid
    graph, and a valid graph is never refused.

    Args:
        text: The model's answer.
        schema: The step's whole-graph schema.
        overrides: Top-level values that are ours (the task's name).

    Returns:
        The graph's data (the strict schema's form, or the graph model's).

    Raises:
        AnswerError: not JSON, or neither the schema nor the graph model takes it
            (the schema's problems are the feedback: the form the prompt asked for).
    """
    try:
        return read_strict(text, schema, overrides)
    except AnswerError as strict:
        data, _ = read_json(text)
        try:
            graph = parse_graph({**data, **dict(overrides or {})})
        except (GraphValidationError, TypeError):
            raise strict from None
        return graph.model_dump(mode="json", exclude_none=True)


def read_valid(text: str, schema: Mapping[str, Any], model: type[M]) -> M:
    """A step's answer: checked against its strict schema, or, where that refuses it,
    taken when the step's answer model takes it all the same (a list anchor such as
    a row ``between`` two zones, more objects than the grammar's bound, a longer
    description). What a capable model writes that is valid is never refused for the
    grammar's sake; the checks after the schema (scopes, the graph, the oracle)
    still apply. Grounded steps keep their schema (it carries the reading).

    Args:
        text: The model's answer.
        schema: The step's strict schema.
        model: The step's answer model (:mod:`factask.gen.answers.schemas`).

    Returns:
        The validated answer.

    Raises:
        AnswerError: not JSON, or neither the schema nor the model takes it (the
            schema's problems are the feedback).
    """
    try:
        return validate_answer(read_strict(text, schema), model)
    except AnswerError as strict:
        data, _ = read_json(text)
        try:
            return model.model_validate(data)
        except (TypeError, ValueError):  # a pydantic ValidationError is a ValueError
            raise strict from None


class StepRunner:
    """One generation's state and the step conversation.

    Args:
        client: The LLM client.
        verifier: The ladder's checks (default :class:`Verifier`).
        memory: Subtask memory (examples in, verified subtasks out).
        max_repairs: Repairs per step after the first answer.
        on_step: Called with every :class:`AttemptRecord` as it happens.
        n_examples: In-context examples per source at the fullest prompt level.

    Raises:
        InvalidValueError: ``max_repairs`` < 0.
    """

    def __init__(self, client: LLMClient, verifier: Verifier | None = None,
                 memory: SubtaskMemory | None = None, max_repairs: int = 3,
                 on_step: StepCallback | None = None, n_examples: int = 2) -> None:
        if max_repairs < 0:
            raise InvalidValueError("max_repairs must be >= 0")
        self.client = client
        self.verifier = verifier or Verifier()
        self.memory = memory
        self.max_repairs = max_repairs
        self.on_step = on_step
        self.n_examples = n_examples
        config = getattr(client, "config", None)
        self.budget = Budget(client, getattr(config, "model", "the model"))
        self._result: GenerationResult | None = None
        self._task = ""

    # ------------------------------------------------------------ bookkeeping
    def _record(self, rec: AttemptRecord) -> None:
        assert self._result is not None
        self._result.steps.append(rec)
        if self.on_step is not None:
            self.on_step(rec)

    def _usage(self) -> Usage:
        assert self._result is not None
        return self._result.usage

    def _sampling(self, attempt: int) -> tuple[float, int]:
        config = getattr(self.client, "config", None)
        return sampling(attempt, float(getattr(config, "temperature", 0.0)),
                        int(getattr(config, "seed", 0)))

    def _max_tokens(self, step: str) -> int:
        config = getattr(self.client, "config", None)
        return answer_tokens(step, getattr(config, "max_tokens", None),
                             local=bool(getattr(config, "is_local", True)))

    # -------------------------------------------------------------- prompts
    def schema_for_prompt(self, schema: Mapping[str, Any], level: PromptLevel) -> str:
        """The schema as the prompt shows it at ``level`` (JSON, or a skeleton)."""
        return schema_text(schema) if level.schema == "full" else schema_skeleton(schema)

    def examples(self, query: str, sources: tuple[str, ...], k: int | None = None) -> str:
        """In-context examples (never the task itself), ``k`` per source."""
        found: list[Example] = []
        k = self.n_examples if k is None else min(k, self.n_examples)
        if k <= 0:
            return "(none)"
        if "tasks" in sources:
            found += library_task_examples(query, k, exclude=self._task or None)
        if "templates" in sources:
            found += template_examples(query, k)
        if "memory" in sources and self.memory is not None:
            found += self.memory.retrieve(query, k, exclude_task=self._task or None)
        return render_examples(found)

    def remember(self, fragment: TaskGraph, task: str) -> None:
        """Save a verified subtask in the memory (a failure to write only warns)."""
        if self.memory is None or self._result is None:
            return
        try:
            self.memory.save(fragment, task=task, approach=self._result.approach)
        except SubtaskMemoryError as exc:  # memory is a help, never a reason to fail
            warnings.warn(str(exc), stacklevel=2)

    # ------------------------------------------------------------ the step
    def ask(self, step: str, prompt: PromptBuilder, schema: Mapping[str, Any],
            schema_name: str, evaluate: Callable[[str], Evaluation],
            first_attempt: int = 0) -> Outcome[Any]:
        """Ask, evaluate, feed back, up to ``max_repairs`` repairs; keep the best
        artefact together with its own feedback.

        Args:
            step: Step name (``subtask_goal:<name>`` for a subtask's step).
            prompt: The user prompt at a prompt level.
            schema: The step's strict schema (sent, and checked first).
            schema_name: Its name.
            evaluate: Answer text -> (artefact, level, feedback or None).
            first_attempt: Number of the first attempt (assembly repairs start at 1).

        Returns:
            The best artefact, its level, whether the step passed, its feedback.

        Raises:
            LLMContextError: no prompt variant fits the model's context.
            LLMRequestError: the provider rejected the first request.
            LLMError: any other failure of the call.
        """
        max_tokens = self._max_tokens(step)
        empty = empty_choices(schema)
        if empty:  # no answer can follow it: no call (and no grammar the server fails on)
            feedback = (f"No answer can follow the schema of step {step}: nothing to choose "
                        f"at {', '.join(empty[:3])} (e.g. a goal over objects none of which "
                        "can be moved).")
            self._record(AttemptRecord(step, first_attempt, False, "none", feedback))
            return Outcome(None, "none", False, feedback)

        def build(level: PromptLevel) -> list[dict[str, str]]:
            system = render("system_compact" if level.compact_vocabulary else "system")
            return [{"role": "system", "content": system},
                    {"role": "user", "content": prompt(level)}]

        messages, level_index_ = self.budget.choose(step, build, max_tokens)
        best: tuple[int, Any, Level, str | None] | None = None
        feedback: str | None = None
        seen: set[str] = set()
        repeats = 0
        last = first_attempt + self.max_repairs
        for attempt in range(first_attempt, last + 1):
            conversation = self.budget.trim(messages, max_tokens)
            if conversation is None:
                feedback = (feedback or "") + "\n(the repair conversation no longer fits " \
                    "the model's context)"
                break
            # After a repeated answer the next try samples at the warmest temperature:
            # a small model under a grammar often repeats itself at 0.4.
            temperature, seed = self._sampling(
                len(RETRY_TEMPERATURES) if repeats else attempt - first_attempt)
            seed += attempt if repeats else 0
            try:
                reply = self.client.complete(conversation, schema=schema,
                                             schema_name=schema_name, max_tokens=max_tokens,
                                             temperature=temperature, seed=seed)
            except LLMRequestError as exc:
                if best is None:
                    raise
                return Outcome(best[1], best[2], False,
                               f"{best[3]}\n(then the LLM request was rejected: {exc})")
            self._usage().add(reply.usage)
            value, level, feedback = self._evaluate(evaluate, reply.text)
            if feedback is not None and getattr(reply, "finish_reason", "") == "length":
                feedback += (f"\n(The answer was cut off at {max_tokens} tokens: write a "
                             "shorter answer.)")
            norm = normalised_answer(reply.text)
            repeated = norm in seen
            seen.add(norm)
            repeats += repeated
            if repeated and feedback is not None:
                feedback += ("\n(The model repeated an earlier answer twice: the step stops "
                             "here.)" if repeats >= MAX_REPEATS else
                             "\n(This answer repeats an earlier one: write a different one.)")
            self._record(AttemptRecord(step, attempt, feedback is None, level, feedback,
                                       reply.cached, reply.usage.total_tokens,
                                       reply.usage.cost_usd, prompt_level=level_index_,
                                       temperature=temperature))
            if value is not None and (best is None or level_index(level) > best[0]):
                best = (level_index(level), value, level, feedback)
            if feedback is None:
                return Outcome(value, level, True, None)
            if repeats >= MAX_REPEATS:
                break
            if attempt < last:
                note = render("feedback", step=step, attempt=attempt + 1,
                              max_attempts=last + 1, feedback=cut_feedback(feedback))
                if repeated:
                    # A small model copies an answer it can see, at any temperature:
                    # after a repeat the answers leave the conversation; the feedback
                    # stays, with the first prompt.
                    messages = [messages[0], {"role": "user", "content":
                                              f"{messages[1]['content']}\n\n{note}"}]
                else:
                    messages = [*messages, {"role": "assistant", "content": reply.text},
                                {"role": "user", "content": note}]
        if best is None:
            return Outcome(None, "none", False, feedback)
        return Outcome(best[1], best[2], False, best[3])

    @staticmethod
    def _evaluate(evaluate: Callable[[str], Evaluation], text: str) -> Evaluation:
        try:
            return evaluate(text)
        except AnswerError as exc:
            return None, "none", exc.feedback
        except (LLMError, Abort):
            raise
        except Exception as exc:  # a bug or an odd answer must not kill the run
            return None, "none", (f"Checking the answer failed unexpectedly "
                                  f"({type(exc).__name__}: {exc}). Send a simpler, valid "
                                  "answer following the schema.")

    def ask_or_abort(self, step: str, prompt: PromptBuilder, schema: Mapping[str, Any],
                     schema_name: str, evaluate: Callable[[str], Evaluation]) -> Any:
        """:meth:`ask` for a step the approach cannot go on without (variables, a plan,
        an outline): its artefact.

        Raises:
            Abort: the step did not pass (naming the step and its last feedback).
        """
        out = self.ask(step, prompt, schema, schema_name, evaluate)
        if not out.ok:
            raise Abort(f"{step}: {out.feedback}")
        return out.value

    # ------------------------------------------------------------ finishing
    def finish(self, graph: TaskGraph | None, level: Level, failure: str | None) -> None:
        """Set the result's graph, level and (short of completion) failure."""
        assert self._result is not None
        self._result.graph = graph
        self._result.level_reached = level if graph is not None else "none"
        if failure and not at_least(self._result.level_reached, "completion"):
            self._result.failure = failure


__all__ = ["Abort", "Evaluation", "Outcome", "PromptBuilder", "StepCallback", "StepRunner",
           "read_graph_answer", "read_strict"]
