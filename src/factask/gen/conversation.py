"""One step's conversation with the model: budgets, prompt variants, repairs.

* **Budgets.** Every request carries ``max_tokens`` sized to the answer the step
  wants (:data:`ANSWER_TOKENS`). The prompt is measured against the model's
  context (the client's ``context`` and ``count_tokens``); when the full prompt
  does not fit with its answer, a compact variant is used
  (:data:`PROMPT_LEVELS`: fewer examples, then a vocabulary summary instead of
  the whole vocabulary, then no examples and a schema skeleton); when nothing
  fits, :class:`~factask.gen.llm_errors.LLMContextError` is raised before the
  call. A repair conversation that outgrows the context is trimmed to the last
  answer and its feedback.
* **Repairs.** The answer is evaluated (schema, then the ladder); on failure the
  feedback goes back as the next user message. Each retry samples differently
  (:func:`sampling`: another seed, a higher temperature); after a repeated
  answer the next try is at the warmest temperature, and a step stops early when
  the model repeats itself twice (:data:`factask.gen.steps.MAX_REPEATS`).
"""

from __future__ import annotations

import json
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from factask.gen.llm_errors import LLMContextError, fix_for

Message = dict[str, str]

#: max_tokens per step: room for the answer the step asks for, no more.
#: A variable takes about 50 tokens, a factor about 70, a planned subtask 45; the
#: step schemas allow at most 12 variables, 8 factors and 8 subtasks.
ANSWER_TOKENS: dict[str, int] = {
    "one_shot": 1200, "assembly": 1200, "variables": 640, "subtask_plan": 400,
    "subtask_goal": 160, "subtask_outline": 280, "subtask_design": 520,
}
#: max_tokens of every step for a remote model (a bound on a runaway answer only).
REMOTE_ANSWER_TOKENS = 4096
#: Feedback longer than this (characters) is cut before it goes back.
MAX_FEEDBACK_CHARS = 2500
#: Temperatures of a step's attempts after the first (the first uses the config's).
RETRY_TEMPERATURES = (0.4, 0.7, 0.9, 1.0)


@dataclass(frozen=True)
class PromptLevel:
    """One prompt variant, from the fullest (level 0) to the most compact.

    Attributes:
        examples: In-context examples per source.
        compact_vocabulary: The vocabulary summary instead of the whole vocabulary.
        schema: ``full`` (the JSON Schema), or ``skeleton`` (an outline of the answer).
    """

    examples: int
    compact_vocabulary: bool
    schema: str


PROMPT_LEVELS: tuple[PromptLevel, ...] = (
    PromptLevel(2, False, "full"),
    PromptLevel(1, False, "full"),
    PromptLevel(1, True, "full"),
    PromptLevel(0, True, "full"),
    PromptLevel(0, True, "skeleton"),
)


def answer_tokens(step: str, cap: int | None = None, local: bool = True) -> int:
    """``max_tokens`` of a step's request (``step`` may carry ``:subtask``): sized to
    the answer for the local model (each token is CPU time), :data:`REMOTE_ANSWER_TOKENS`
    for a remote one (billed by the tokens it writes, and a capable model writes the
    schema's fields and longer texts: a 20-object graph is about 1,500 tokens)."""
    wanted = ANSWER_TOKENS.get(step.split(":", 1)[0], 800) if local else REMOTE_ANSWER_TOKENS
    return min(wanted, cap) if cap else wanted


def sampling(attempt: int, temperature: float, seed: int) -> tuple[float, int]:
    """(temperature, seed) of an attempt: the config's first, then warmer, new seeds."""
    if attempt <= 0:
        return temperature, seed
    warmer = RETRY_TEMPERATURES[min(attempt, len(RETRY_TEMPERATURES)) - 1]
    return max(temperature, warmer), seed + 7919 * attempt


def normalised_answer(text: str) -> str:
    """An answer reduced for comparison: canonical JSON if it is JSON, else its words."""
    try:
        return json.dumps(json.loads(text), sort_keys=True, separators=(",", ":"))
    except (ValueError, RecursionError):
        return " ".join(text.split())


def cut_feedback(text: str, limit: int = MAX_FEEDBACK_CHARS) -> str:
    """Feedback shortened to ``limit`` characters (whole lines where possible)."""
    if len(text) <= limit:
        return text
    head = text[:limit]
    return head[: head.rfind("\n")] if "\n" in head else head + "\n... (more problems)"


class Budget:
    """The model's context and how a request is fitted into it.

    Args:
        client: The LLM client (``context`` and ``count_tokens`` are used where it
            has them; a client without them is never checked).
        model: Model name for messages.
    """

    def __init__(self, client: Any, model: str) -> None:
        self.client = client
        self.model = model

    @property
    def context(self) -> int | None:
        return getattr(self.client, "context", None)

    def limit(self, max_tokens: int) -> int | None:
        """Most prompt tokens for an answer of ``max_tokens``: what the context leaves,
        at most the client's ``prompt_budget``; None when nothing is known."""
        ctx = self.context
        room = None if ctx is None else ctx - max_tokens
        budget = getattr(self.client, "prompt_budget", None)
        if budget is None:
            return room
        return budget if room is None else min(room, budget)

    def tokens(self, messages: Sequence[Mapping[str, Any]]) -> int:
        return int(self.client.count_tokens(messages))

    def fits(self, messages: Sequence[Mapping[str, Any]], max_tokens: int) -> bool:
        """True if the messages and an answer of ``max_tokens`` fit the context."""
        ctx = self.context
        return ctx is None or self.tokens(messages) + max_tokens <= ctx

    def _fits_budget(self, tokens: int, max_tokens: int) -> bool:
        limit = self.limit(max_tokens)
        return limit is None or tokens <= limit

    def choose(self, step: str, build: Callable[[PromptLevel], list[Message]],
               max_tokens: int) -> tuple[list[Message], int]:
        """The fullest prompt variant that fits with its answer.

        Args:
            step: The step (for the message).
            build: Messages for a prompt level.
            max_tokens: The answer's budget.

        Returns:
            (messages, level index).

        Raises:
            LLMContextError: not even the most compact variant fits the context
                (a client's ``prompt_budget`` only picks the variant).
        """
        smallest = 0
        for i, level in enumerate(PROMPT_LEVELS):
            messages = build(level)
            if self.limit(max_tokens) is None:
                return messages, i
            smallest = self.tokens(messages)
            if self._fits_budget(smallest, max_tokens):
                return messages, i
        if self.context is not None and smallest + max_tokens <= self.context:
            return messages, len(PROMPT_LEVELS) - 1  # over the budget, within the context
        raise LLMContextError(
            f"{self.model}: step {step}: the most compact prompt takes {smallest} tokens and "
            f"its answer up to {max_tokens}, more than the model's context of "
            f"{self.context} tokens", fix_for(LLMContextError, self.model))

    def trim(self, messages: list[Message], max_tokens: int) -> list[Message] | None:
        """A repair conversation cut to fit: first the oldest answer/feedback pairs,
        then the last answer (its feedback stays). None if even that does not fit."""
        if self.fits(messages, max_tokens):
            return messages
        head, tail = messages[:2], messages[2:]
        while len(tail) > 2:
            tail = tail[2:]
            if self.fits(head + tail, max_tokens):
                return head + tail
        if tail:
            only_feedback = head + tail[-1:]
            if self.fits(only_feedback, max_tokens):
                return only_feedback
        return None


__all__ = ["ANSWER_TOKENS", "PROMPT_LEVELS", "Budget", "PromptLevel", "answer_tokens",
           "cut_feedback", "normalised_answer", "sampling"]
