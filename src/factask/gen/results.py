"""What a generation returns: the graph (or not), the level reached, every step.

:class:`GenerationResult` is JSON-serialisable both ways; a benchmark's
``results.jsonl`` line is one of these (plus the benchmark's own fields).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Literal

from factask.gen.llm import Usage
from factask.gen.verify import Level, at_least
from factask.graph.taskgraph import TaskGraph

Approach = Literal["one-shot", "variables-first", "subtasks-first"]
#: The three strategies: the baseline and the research's approaches 1 and 2.
APPROACHES: tuple[Approach, ...] = ("one-shot", "variables-first", "subtasks-first")
#: The approach ``factask generate`` and :meth:`Generator.generate` take unless told: the
#: one with the best faithful rate measured on the 192 list and the proposal set
#: (docs/generation.md, the reader-only rows: one-shot 17.6 / 42.0 %, the factorized
#: approaches at most 3.2 / 18.8 %).
DEFAULT_APPROACH: Approach = "one-shot"


@dataclass
class AttemptRecord:
    """One attempt at one step.

    Attributes:
        step: Step name (``one_shot``, ``variables``, ``subtask_goal:<name>``, ...).
        attempt: 0 for the first answer, then 1, 2, ... for repairs.
        ok: The attempt reached the step's target level.
        level: Level the attempt's artefact reached (``none`` if it did not parse).
        feedback: The message sent back to the model (None if ok).
        cached: The answer came from the disk cache.
        tokens: Tokens of this attempt's LLM call (0 if cached or no call).
        cost_usd: Cost of this attempt's LLM call (0 if cached, unpriced or no call).
        prompt_level: The prompt variant used (0 = fullest; see
            :data:`factask.gen.conversation.PROMPT_LEVELS`).
        temperature: The sampling temperature of the call.
    """

    step: str
    attempt: int
    ok: bool
    level: Level = "none"
    feedback: str | None = None
    cached: bool = False
    tokens: int = 0
    cost_usd: float = 0.0
    prompt_level: int = 0
    temperature: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        return {"step": self.step, "attempt": self.attempt, "ok": self.ok, "level": self.level,
                "feedback": self.feedback, "cached": self.cached, "tokens": self.tokens,
                "cost_usd": self.cost_usd, "prompt_level": self.prompt_level,
                "temperature": self.temperature}

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> AttemptRecord:
        return cls(step=data["step"], attempt=int(data["attempt"]), ok=bool(data["ok"]),
                   level=data.get("level", "none"), feedback=data.get("feedback"),
                   cached=bool(data.get("cached", False)), tokens=int(data.get("tokens", 0)),
                   cost_usd=float(data.get("cost_usd", 0.0)),
                   prompt_level=int(data.get("prompt_level", 0)),
                   temperature=float(data.get("temperature", 0.0)))


@dataclass
class GenerationResult:
    """The outcome of one generation.

    Attributes:
        approach: The strategy used.
        proposal: The proposal text as given.
        task: The task name used.
        graph: The final graph (the best one reached), or None.
        level_reached: Highest ladder level the final whole-task graph passed.
        steps: Every attempt of every step, in order.
        usage: Tokens and cost of this generation's calls.
        failure: Why completion was not reached (None if it was).
        llm_error: The generation stopped because the LLM could not be reached
            (an infrastructure problem, not the model's answer: a benchmark
            retries such tasks on resume).
        unread: The proposal's words the final graph leaves unread (word, category,
            why; :func:`factask.gen.reading.accounting.account`): with any, a graph
            the oracle completes ends at ``partial``, not ``completion``.
    """

    approach: str
    proposal: str
    task: str
    graph: TaskGraph | None = None
    level_reached: Level = "none"
    steps: list[AttemptRecord] = field(default_factory=list)
    usage: Usage = field(default_factory=Usage)
    failure: str | None = None
    llm_error: bool = False
    unread: list[dict[str, str]] = field(default_factory=list)

    @property
    def completed(self) -> bool:
        """True if the final graph passed the completion check."""
        return at_least(self.level_reached, "completion")

    @property
    def repairs(self) -> int:
        """Number of repair attempts (answers after feedback)."""
        return sum(1 for s in self.steps if s.attempt > 0)

    def to_dict(self) -> dict[str, Any]:
        return {
            "approach": self.approach, "proposal": self.proposal, "task": self.task,
            "level_reached": self.level_reached, "failure": self.failure,
            "llm_error": self.llm_error,
            "graph": self.graph.to_dict() if self.graph is not None else None,
            "steps": [s.to_dict() for s in self.steps], "usage": self.usage.to_dict(),
            "unread": [dict(w) for w in self.unread],
        }

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> GenerationResult:
        graph = data.get("graph")
        return cls(
            approach=data["approach"], proposal=data.get("proposal", ""),
            task=data.get("task", ""),
            graph=TaskGraph.model_validate(graph) if graph else None,
            level_reached=data.get("level_reached", "none"),
            steps=[AttemptRecord.from_dict(s) for s in data.get("steps", [])],
            usage=Usage.from_dict(data.get("usage", {})), failure=data.get("failure"),
            llm_error=bool(data.get("llm_error", False)),
            unread=[dict(w) for w in data.get("unread", [])],
        )
