"""The verification ladder: syntax -> runtime -> completion, each failure a message.

Level 1, *syntax*: the answer parses and validates (pydantic + ``graph.ensure_valid()``).
Level 2, *runtime*: the graph compiles, a seeded reset succeeds (layout sampled,
relations solved) and the environment steps without error.
Level 3, *completion*: the scripted oracle reaches reward >= 0.99 in at least half
of several episodes with different seeds (the research's definition).

:class:`Verifier` is pluggable: the default calls the MuJoCo backend
(:func:`factask.sim.episode.check_runtime` / ``run_episode``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

from factask.gen.answers.schemas import (
    AnswerError,
    format_problems,
    read_json,
    several_objects_note,
)
from factask.graph.taskgraph import TaskGraph, parse_graph
from factask.sim.episode import check_runtime, run_episode
from factask.sim.robots.registry import robot_entry
from factask.vocabulary.errors import FactaskError, GraphValidationError, InvalidValueError

Level = Literal["none", "syntax", "runtime", "partial", "completion"]
#: The ladder, lowest first. ``partial``: the oracle completes the graph, but the graph
#: leaves words of the proposal unread (:mod:`factask.gen.reading.accounting`); the
#: verifier itself never returns it (it does not read proposals), the generator does.
LEVELS: tuple[Level, ...] = ("none", "syntax", "runtime", "partial", "completion")


def level_index(level: str) -> int:
    """Position of ``level`` on the ladder (0 = none)."""
    return LEVELS.index(level)  # type: ignore[arg-type]


def at_least(level: str, wanted: str) -> bool:
    """True if ``level`` is ``wanted`` or higher."""
    return level_index(level) >= level_index(wanted)


@dataclass
class VerifyOutcome:
    """What the ladder found for one graph.

    Attributes:
        level: Highest level passed.
        feedback: Why the next level failed (a message for the model), or None
            when the target level was reached.
        episodes: Per-episode summaries of the completion check.
    """

    level: Level
    feedback: str | None = None
    episodes: list[dict[str, Any]] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.feedback is None


def graph_syntax(text_or_data: str | dict[str, Any]) -> TaskGraph:
    """Level 1 for a whole graph: read the answer and validate it as a TaskGraph.

    Args:
        text_or_data: The model's answer text, or already-decoded JSON.

    Returns:
        The valid graph.

    Raises:
        AnswerError: not JSON, not a graph, or not valid as a whole; the message
            lists every problem with its node.
    """
    note = ""
    if isinstance(text_or_data, str):
        data, count = read_json(text_or_data)
        note = several_objects_note(count)
    else:
        data = text_or_data
    try:
        return parse_graph(data)
    except RecursionError:
        raise AnswerError("The answer is nested too deeply to read. Reply with one flat JSON "
                          "object following the schema.") from None
    except GraphValidationError as exc:
        raise AnswerError(
            f"The task graph is not valid ({len(exc.problems)} problem(s)):\n"
            f"{format_problems(exc.problems)}{note}", exc.problems
        ) from None


def completion_seeds(episodes: int, base_seed: int = 0) -> list[int]:
    """Distinct, deterministic episode seeds."""
    return [base_seed + 1 + 7919 * i for i in range(episodes)]


class Verifier:
    """The ladder's checks. Subclass and override to plug another backend.

    Args:
        episodes: Oracle episodes of the completion check.
        robot: Robot of the episodes, a name of :data:`factask.sim.robots.registry.ROBOTS`
            (``floating`` is the fast one).
        base_seed: Seeds derive from it (:func:`completion_seeds`).
        success_fraction: Fraction of episodes that must succeed (research: half).

    Raises:
        InvalidValueError: ``episodes`` < 1.
        RobotError: no robot of that name.
    """

    def __init__(self, episodes: int = 3, robot: str = "floating", base_seed: int = 0,
                 success_fraction: float = 0.5) -> None:
        if episodes < 1:
            raise InvalidValueError("episodes must be >= 1")
        robot_entry(robot)
        self.episodes = episodes
        self.robot = robot
        self.base_seed = base_seed
        self.success_fraction = success_fraction

    # ---------------------------------------------------------------- levels
    def syntax(self, text_or_data: str | dict[str, Any]) -> TaskGraph:
        """Level 1 (see :func:`graph_syntax`)."""
        return graph_syntax(text_or_data)

    def runtime(self, graph: TaskGraph) -> str | None:
        """Level 2: None if the graph compiles, resets and steps, else the error."""
        check_runtime, _ = self._backend()
        try:
            return check_runtime(graph, seed=self.base_seed, robot=self.robot)
        except FactaskError as exc:
            return f"{type(exc).__name__}: {exc}"
        except Exception as exc:  # a crash in the backend is a runtime failure too
            return f"unexpected {type(exc).__name__}: {exc}"

    def completion(self, graph: TaskGraph, seeds: Sequence[int]) -> VerifyOutcome:
        """Level 3: run the oracle once per seed.

        Returns:
            ``level='completion'`` with no feedback if enough episodes succeed, else
            ``level='runtime'`` and feedback naming the factors that failed and why.
        """
        _, run_episode = self._backend()
        episodes: list[dict[str, Any]] = []
        for seed in seeds:
            try:
                r = run_episode(graph, seed=seed, robot=self.robot)
            except Exception as exc:
                episodes.append({"seed": seed, "success": False, "reward": 0.0,
                                 "failure": f"episode crashed: {type(exc).__name__}: {exc}",
                                 "factors": {}, "details": {}})
                continue
            episodes.append({
                "seed": r.seed, "success": bool(r.success), "reward": float(r.reward),
                "steps": int(getattr(r, "steps", 0)), "failure": r.failure,
                "factors": dict(getattr(r, "factors", {}) or {}),
                "details": dict(getattr(r, "details", {}) or {}),
            })
        wins = sum(1 for e in episodes if e["success"])
        needed = max(1, math.ceil(self.success_fraction * len(episodes)))
        if wins >= needed:
            return VerifyOutcome("completion", None, episodes)
        return VerifyOutcome("runtime", completion_feedback(episodes, wins, needed), episodes)

    # ---------------------------------------------------------------- ladder
    def check(self, graph: TaskGraph, target: Level = "completion") -> VerifyOutcome:
        """Run levels 2 and 3 on a graph that passed level 1.

        Args:
            graph: A valid graph.
            target: Stop once this level is reached.

        Returns:
            The highest level reached and, if short of ``target``, why.
        """
        if not at_least(target, "runtime"):
            return VerifyOutcome("syntax")
        error = self.runtime(graph)
        if error is not None:
            return VerifyOutcome(
                "syntax",
                "Level 2 (runtime) failed: the graph is valid but the scene could not be "
                f"built, reset or stepped:\n{error}\nChange sizes, counts, initial "
                "placements or goal relations so that every object fits on the table and "
                "every goal has room.")
        if not at_least(target, "completion"):
            return VerifyOutcome("runtime")
        return self.completion(graph, completion_seeds(self.episodes, self.base_seed))

    def _backend(self) -> tuple[Any, Any]:
        """The runtime check and the episode runner (a seam: tests script episodes)."""
        return check_runtime, run_episode


def completion_feedback(episodes: Sequence[dict[str, Any]], wins: int, needed: int) -> str:
    """The message for a failed completion check: which factors failed, and why."""
    lines = [
        f"Level 3 (completion) failed: the scripted oracle succeeded in {wins} of "
        f"{len(episodes)} episodes (reward >= 0.99 needed in at least {needed})."
    ]
    for e in episodes:
        if e["success"]:
            continue
        head = f"- episode seed {e['seed']}: reward {e['reward']:.2f}"
        if e.get("failure"):
            head += f"; the oracle gave up: {e['failure']}"
        lines.append(head)
        unmet = {k: v for k, v in e.get("factors", {}).items() if v < 0.99}
        for name, progress in unmet.items():
            why = e.get("details", {}).get(name, "")
            lines.append(f"    factor {name!r} progress {progress:.2f}" + (f": {why}" if why
                                                                              else ""))
    lines.append("Fix the factors named above (goal relation, sizes, or what they rest on) "
                 "so the oracle can satisfy every factor.")
    return "\n".join(lines)


__all__ = [
    "LEVELS",
    "AnswerError",
    "Level",
    "Verifier",
    "VerifyOutcome",
    "at_least",
    "completion_feedback",
    "completion_seeds",
    "graph_syntax",
    "level_index",
]
