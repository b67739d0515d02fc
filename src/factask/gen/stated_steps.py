"""Variables-first and subtasks-first where the words state every goal.

Where the clause reading (:mod:`factask.gen.reading.clauses`) accounts for every
named object and each stated goal can be written and laid out
(:func:`factask.gen.reading.grounded.stated_schema`), the grounded one-shot's
grammar *is* that reading: the model writes only where the movable objects start
and the numbers the words leave open. The factorized approaches ask the same
decisions piece by piece, each piece checked as the research's approaches check
it, so they mean the proposal exactly where one-shot does:

* **variables-first**: (1) where each named movable object starts (the objects
  themselves are the words'); (2) the plan, one subtask per stated goal, its
  name and variables pinned (the model writes each description); (3) each
  subtask's goal under that goal's pinned schema, verified alone as a fragment.
* **subtasks-first**: (1) the outline, one subtask per stated goal, names
  pinned; (2) each subtask's goal under its pinned schema, verified alone as a
  fragment, over the named objects declared from the words (on the table).

Either way the pieces are the grounded one-shot answer's parts, and the whole is
expanded as one-shot's is (:func:`factask.gen.reading.grounded.expand_graph`: the
anchors the goals fill grown, the words' steps the factors' ``after``). Where
there is no such reading the strategies keep their general steps.
"""

from __future__ import annotations

import json
import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from pydantic import ValidationError

from factask.gen.answers import step_schemas as ss
from factask.gen.answers.schemas import (
    GoalAnswer,
    SubtaskOutline,
    SubtaskPlan,
    format_problems,
    validate_answer,
)
from factask.gen.fragments import checked_fragment, closure, earlier_text, make_factor
from factask.gen.prompts import render, schema_skeleton
from factask.gen.reading import grounded
from factask.gen.reading.clauses import ReadGoal, read_goals
from factask.gen.reading.cover import tuple_schema
from factask.gen.reading.mentions import Mention, mentions_text
from factask.gen.steps import Abort, Evaluation, StepRunner, read_strict
from factask.graph.taskgraph import TaskGraph, graph_problems, problems_from_pydantic
from factask.vocabulary.variables import StateVariable

Schema = ss.Schema


@dataclass(frozen=True)
class StatedTask:
    """What the words decide of a task, and the schemas of what is left.

    Attributes:
        found: The proposal's mentions (as read; the expansion grows anchors).
        goals: The stated goals, in the answer's order.
        names: One factor name per goal (:func:`grounded.factor_names`).
        goal_schemas: One pinned ``goal`` schema per goal (the one-shot grammar's).
        starts: The ``variables`` tuple schema: each movable object's ``name``
            and ``initial`` (the one-shot grammar's).
        variables: The named objects as variables, declared from the words, on
            the table, anchors grown to hold what the goals put there.
    """

    found: tuple[Mention, ...]
    goals: tuple[ReadGoal, ...]
    names: tuple[str, ...]
    goal_schemas: tuple[Schema, ...]
    starts: Schema
    variables: tuple[StateVariable, ...]

    def objects_of(self, i: int) -> list[str]:
        """Goal ``i``'s named objects: what it moves, then its anchor."""
        goal = self.goals[i]
        return list(dict.fromkeys([*goal.objects, *([goal.anchor] if goal.anchor else [])]))


def stated_task(found: Sequence[Mention], proposal: str) -> StatedTask | None:
    """The task the words state (None: there is no such reading, or a goal of it
    cannot be written or laid out)."""
    factors = grounded.stated_schema(found, proposal)
    goals = read_goals(proposal, found)
    if not factors or not goals:
        return None
    compact = grounded.compact_graph_schema(found, proposal)["properties"]
    items = compact["factors"].get("prefixItems")
    if not items or len(items) != len(goals):
        return None  # the grammar is not the reading (defensive: stated_schema said it is)
    names = grounded.factor_names([{"type": g.relation, "objects": list(g.objects)}
                                   for g in goals])
    declared = tuple(StateVariable.model_validate(m.as_variable())
                     for m in grounded.graph_mentions(found, proposal))
    return StatedTask(found=tuple(found), goals=tuple(goals), names=tuple(names),
                      goal_schemas=tuple(i["properties"]["goal"] for i in items),
                      starts=compact["variables"], variables=declared)


def _says(text: str) -> bool:
    """Whether a description has a word in it ("a", "" -- the reader-only model's
    first choices -- say less than the expansion's own)."""
    return re.search(r"[A-Za-z]{3}", text) is not None


def _goal_step_schema(stated: StatedTask, i: int) -> Schema:
    return ss.obj({"goal": stated.goal_schemas[i], "description": ss.text(grounded.GROUNDED_TEXT)})


def _assembled(stated: StatedTask, task: str, desc: str, starts: Sequence[dict[str, Any]],
               goals: Sequence[dict[str, Any]], descriptions: Sequence[str],
               ) -> tuple[TaskGraph | None, str | None]:
    """The whole graph of the pieces, expanded as one-shot's answer is."""
    data = grounded.expand_graph({"variables": list(starts),
                                  "factors": [{"goal": g} for g in goals]},
                                 stated.found, task, desc)
    written = {n: d for n, d in zip(stated.names, descriptions, strict=True) if _says(d)}
    for factor in data["factors"]:
        if written.get(factor["name"]):
            factor["description"] = written[factor["name"]][:200]
    try:
        return TaskGraph.model_validate(data), None
    except ValidationError as exc:
        return None, format_problems(problems_from_pydantic(exc, data))


def _ask_goals(runner: StepRunner, task: str, desc: str, stated: StatedTask,
               descriptions: Sequence[str], by_subtask: str,
               ) -> tuple[list[dict[str, Any]], list[str]]:
    """Each stated goal under its pinned schema, verified alone as a fragment.

    Args:
        by_subtask: ``"goal"`` (variables-first's step 3) or ``"design"``
            (subtasks-first's step 2): the step's name and prompt.

    Returns:
        The goals (JSON) and the descriptions the answers give.

    Raises:
        Abort: a subtask with no valid goal.
    """
    pool = {v.name: v for v in stated.variables}
    outline = "; ".join(f"`{n}`: {d}" for n, d in zip(stated.names, descriptions, strict=True))
    goals: list[dict[str, Any]] = []
    written: list[str] = []
    earlier: list[dict[str, Any]] = []
    for i, name in enumerate(stated.names):
        schema = _goal_step_schema(stated, i)
        scope = [pool[n] for n in stated.objects_of(i) if n in pool]

        def prompt(lv: Any, i: int = i, name: str = name, scope: Any = scope,
                   schema: Schema = schema) -> str:
            examples = runner.examples(f"{name} {descriptions[i]}", ("memory", "templates"),
                                       lv.examples)
            if by_subtask == "goal":
                return render("subtask_goal", task_name=task, task_description=desc,
                              subtask_name=name, subtask_description=descriptions[i],
                              initial_setup="(nothing)",
                              variables="\n".join(v.model_dump_json(exclude_none=True)
                                                  for v in closure(scope, pool)),
                              examples=examples, schema=schema_skeleton(schema))
            return render("subtask_design_grounded", task_name=task, task_description=desc,
                          mentions=mentions_text(f"{desc} {task}"), outline=outline,
                          subtask_name=name, subtask_description=descriptions[i],
                          object=stated.goals[i].objects[0], earlier=earlier_text(earlier),
                          examples=examples, schema=schema_skeleton(schema))

        def evaluate(text: str, i: int = i, name: str = name, scope: Any = scope,
                     schema: Schema = schema) -> Evaluation:
            data = read_strict(text, schema)
            answer = validate_answer(data, GoalAnswer)
            factor = make_factor(name, answer.description or descriptions[i], answer.goal,
                                 scope=None)
            piece, level, feedback = checked_fragment(runner, task, factor, closure(scope, pool))
            return (data["goal"], answer.description, piece), level, feedback

        step, kind = ("subtask_goal", "goal_answer") if by_subtask == "goal" \
            else ("subtask_design", "subtask_design")
        out = runner.ask(f"{step}:{name}", prompt, schema, kind, evaluate)
        if out.value is None:
            raise Abort(f"subtask {name!r}: no valid goal after "
                        f"{runner.max_repairs + 1} attempt(s): {out.feedback}")
        goal, description, piece = out.value
        if out.ok:
            runner.remember(piece, task)
        goals.append(goal)
        written.append(description if _says(description) else descriptions[i])
        earlier.append({"subtask": name, "verified": out.ok, "goal": goal})
    return goals, written


def variables_first(runner: StepRunner, task: str, desc: str,
                    stated: StatedTask) -> tuple[TaskGraph | None, str | None]:
    """Approach 1 over a stated task: starts, plan, goals (each step checked).

    Returns:
        The assembled graph (None where it is not valid) and the problem, if any,
        for the assembly step.

    Raises:
        Abort: a step with no valid answer.
    """
    starts = _ask_starts(runner, task, desc, stated)
    plan = _ask_plan(runner, task, desc, stated, starts)
    descriptions = [s.description for s in plan.subtasks]
    goals, written = _ask_goals(runner, task, desc, stated, descriptions, "goal")
    return _assembled(stated, task, desc, starts, goals, written)


def subtasks_first(runner: StepRunner, task: str, desc: str,
                   stated: StatedTask) -> tuple[TaskGraph | None, str | None]:
    """Approach 2 over a stated task: outline, then each subtask's goal (checked).

    Returns:
        As :func:`variables_first` (every object starts on the table: the objects
        are declared from the words, as grounded subtasks-first declares them).

    Raises:
        Abort: a step with no valid answer.
    """
    outline = _ask_outline(runner, task, desc, stated)
    descriptions = [s.description for s in outline.subtasks]
    goals, written = _ask_goals(runner, task, desc, stated, descriptions, "design")
    return _assembled(stated, task, desc, [], goals, written)


def _ask_starts(runner: StepRunner, task: str, desc: str,
                stated: StatedTask) -> list[dict[str, Any]]:
    """Variables-first step 1: where each movable named object starts."""
    schema = ss.obj({"variables": stated.starts})

    def prompt(lv: Any) -> str:
        return render("variables_stated", task_name=task, task_description=desc,
                      mentions=mentions_text(f"{desc} {task}"), schema=schema_skeleton(schema))

    def evaluate(text: str) -> Evaluation:
        starts = read_strict(text, schema)["variables"]
        given = {s["name"]: s["initial"] for s in starts}
        variables = [v if v.name not in given else StateVariable.model_validate(
            {**v.model_dump(mode="json", exclude_none=True), "initial": given[v.name]})
            for v in stated.variables]
        problems = graph_problems(TaskGraph(name=task, variables=variables))
        if problems:
            return None, "none", ("The starts are not consistent:\n"
                                  + format_problems(problems))
        return starts, "syntax", None

    out = runner.ask("variables", prompt, schema, "variables_answer", evaluate)
    if not out.ok:
        raise Abort(f"variables: {out.feedback}")
    return list(out.value)


def _pinned_subtasks(stated: StatedTask, with_variables: bool) -> Schema:
    items = [ss.obj({"name": {"const": n}, "description": ss.text(grounded.GROUNDED_TEXT),
                     **({"variables": {"const": stated.objects_of(i)}} if with_variables
                        else {})})
             for i, n in enumerate(stated.names)]
    return ss.obj({"subtasks": tuple_schema(items)})


def _ask_plan(runner: StepRunner, task: str, desc: str, stated: StatedTask,
              starts: Sequence[dict[str, Any]]) -> SubtaskPlan:
    """Variables-first step 2: one subtask per stated goal (the model describes each)."""
    schema = _pinned_subtasks(stated, with_variables=True)
    given = {s["name"]: s["initial"] for s in starts}
    shown = "\n".join(json.dumps({"name": v.name, "kind": v.kind, "color": v.color,
                                   "count": v.count,
                                   "initial": given.get(v.name, {"type": "table"})})
                       for v in stated.variables)

    def prompt(lv: Any) -> str:
        return render("subtask_plan", task_name=task, task_description=desc, variables=shown,
                      examples=runner.examples(f"{task} {desc}", ("memory", "templates"),
                                               lv.examples),
                      schema=schema_skeleton(schema))

    def evaluate(text: str) -> Evaluation:
        return validate_answer(read_strict(text, schema), SubtaskPlan), "syntax", None

    out = runner.ask("subtask_plan", prompt, schema, "subtask_plan", evaluate)
    if not out.ok:
        raise Abort(f"subtask_plan: {out.feedback}")
    return out.value


def _ask_outline(runner: StepRunner, task: str, desc: str,
                 stated: StatedTask) -> SubtaskOutline:
    """Subtasks-first step 1: one subtask per stated goal (the model describes each)."""
    schema = _pinned_subtasks(stated, with_variables=False)

    def prompt(lv: Any) -> str:
        return render("subtask_outline", task_name=task, task_description=desc,
                      examples=runner.examples(f"{task} {desc}", ("memory", "templates"),
                                               lv.examples),
                      schema=schema_skeleton(schema))

    def evaluate(text: str) -> Evaluation:
        return validate_answer(read_strict(text, schema), SubtaskOutline), "syntax", None

    out = runner.ask("subtask_outline", prompt, schema, "subtask_outline", evaluate)
    if not out.ok:
        raise Abort(f"subtask_outline: {out.feedback}")
    return out.value


__all__ = ["StatedTask", "stated_task", "subtasks_first", "variables_first"]
