"""Variables-first and subtasks-first asked in the grounded one-shot grammar's pieces.

Where the proposal names a movable object, the grounded one-shot grammar
(:func:`factask.gen.reading.grounded.compact_graph_schema`) holds what the words
decide: where they state every goal (:mod:`factask.gen.reading.clauses`), one list
of goals pinned to that reading; elsewhere, a few *shapes* (goal lists that use
every named object, :mod:`factask.gen.reading.cover`). The model writes only where
the movable objects start, which shape, and the numbers the words leave open. The
factorized approaches ask the same decisions piece by piece, each piece checked as
the research's approaches check it, so they mean the proposal wherever one-shot
does:

* **variables-first**: (1) where each named movable object starts (the objects
  themselves are the words'); (2) the plan: one subtask per goal of a shape, its
  name and variables pinned (the model picks the shape and describes each
  subtask); (3) each subtask's goal under the schemas of the shapes the answers
  so far leave open, verified alone as a fragment.
* **subtasks-first**: (1) the outline, as the plan without variables; (2) each
  subtask's goal as in (3), over the named objects declared from the words (on
  the table).

The pieces are the one-shot answer's parts, and the whole is expanded as
one-shot's is (:func:`factask.gen.reading.grounded.expand_graph`: the anchors
stated goals fill grown, the words' steps the factors' ``after``). Where the
grammar's goals are no list of fixed length (its plain fallback), the strategies
keep their general steps.
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
from factask.gen.answers.step_schemas import schema_problems
from factask.gen.fragments import checked_fragment, closure, earlier_text, make_factor
from factask.gen.prompts import render, schema_skeleton
from factask.gen.reading import grounded
from factask.gen.reading.cover import tuple_schema
from factask.gen.reading.mentions import Mention, mentions_text, unnamed_colour
from factask.gen.steps import Abort, Evaluation, StepRunner, read_strict
from factask.graph.taskgraph import TaskGraph, graph_problems, problems_from_pydantic
from factask.vocabulary.variables import StateVariable

Schema = ss.Schema


@dataclass(frozen=True)
class Shape:
    """One way the grammar lets the goals be: a subtask per goal, in order.

    Attributes:
        names: One subtask name per goal (:func:`grounded.factor_names` of the
            relation and objects the goal's schema pins).
        goal_schemas: One ``goal`` schema per subtask (the one-shot grammar's item).
        objects: The named objects each goal's schema may use.
    """

    names: tuple[str, ...]
    goal_schemas: tuple[Schema, ...]
    objects: tuple[tuple[str, ...], ...]


@dataclass(frozen=True)
class GroundedTask:
    """What the words decide of a task, and the schemas of what is left.

    Attributes:
        found: The proposal's mentions (as read; the expansion grows anchors).
        shapes: The goal lists the one-shot grammar allows (one where the words
            state every goal, :attr:`stated`).
        starts: The ``variables`` tuple schema: each movable object's ``name``
            and ``initial`` (the one-shot grammar's).
        variables: The named objects as variables, declared from the words, on
            the table (anchors a stated goal fills grown to hold what it puts there).
        stated: Whether the words state every goal (the one shape is that reading).
    """

    found: tuple[Mention, ...]
    shapes: tuple[Shape, ...]
    starts: Schema
    variables: tuple[StateVariable, ...]
    stated: bool


def grounded_task(found: Sequence[Mention], proposal: str) -> GroundedTask | None:
    """The grounded one-shot grammar of ``proposal`` split into subtasks: None where
    grounding does not apply (:func:`grounded.applies`), or where its goals are no
    list of fixed length (the plain array the grammar falls back
    to: the factorized approaches keep their own steps there)."""
    if not grounded.applies(found):
        return None  # nothing movable named: no grounded grammar
    compact = grounded.compact_graph_schema(found, proposal)["properties"]
    factors = compact["factors"]
    known = {m.name for m in found}
    shapes: list[Shape] = []
    for branch in factors.get("anyOf", [factors]):
        items = branch.get("prefixItems")
        if not items or branch.get("items") is not False or \
                branch.get("minItems") != len(items):
            return None
        goals = [item["properties"]["goal"] for item in items]
        objects = [tuple(_moved_first(g, known)) for g in goals]
        names = grounded.factor_names([_pinned(g, known) for g in goals])
        shapes.append(Shape(tuple(names), tuple(goals), tuple(objects)))
    unnamed = unnamed_colour(found)
    declared = tuple(StateVariable.model_validate(m.as_variable(unnamed=unnamed))
                     for m in grounded.graph_mentions(found, proposal))
    return GroundedTask(found=tuple(found), shapes=tuple(shapes), starts=compact["variables"],
                        variables=declared,
                        stated=grounded.stated_schema(found, proposal) is not None)


def _names_in(schema: Any, known: set[str]) -> list[str]:
    """The named objects a schema offers (its ``const`` and ``enum`` values), in order."""
    out: list[str] = []
    if isinstance(schema, dict):
        values = [schema["const"]] if "const" in schema else list(schema.get("enum", []))
        out += [v for v in values if isinstance(v, str) and v in known]
        for value in schema.values():
            out += _names_in(value, known)
    elif isinstance(schema, list):
        for value in schema:
            out += _names_in(value, known)
    return list(dict.fromkeys(out))


def _moved_first(goal: Schema, known: set[str]) -> list[str]:
    """The named objects a goal schema offers: those it may move, then its anchors."""
    moved = [n for branch in goal.get("anyOf", [goal])
             for n in _names_in(branch.get("properties", {}).get("objects", {}), known)]
    return list(dict.fromkeys([*moved, *_names_in(goal, known)]))


def _pinned(goal: Schema, known: set[str]) -> dict[str, Any]:
    """The relation and objects a goal schema pins (for its subtask's name)."""
    first = goal.get("anyOf", [goal])[0]
    props = first.get("properties", {})
    objects = props.get("objects", {}).get("prefixItems", [])
    return {"type": props.get("type", {}).get("const", "goal"),
            "objects": [o["const"] for o in objects if o.get("const") in known]}


def _says(text: str) -> bool:
    """Whether a description has a word in it ("a", "" -- the reader-only model's
    first choices -- say less than the expansion's own)."""
    return re.search(r"[A-Za-z]{3}", text) is not None


def _one_of(schemas: Sequence[Schema]) -> Schema:
    distinct: list[Schema] = []
    for schema in schemas:
        if schema not in distinct:
            distinct.append(schema)
    return distinct[0] if len(distinct) == 1 else {"anyOf": distinct}


def _assembled(task_: GroundedTask, task: str, desc: str, starts: Sequence[dict[str, Any]],
               goals: Sequence[dict[str, Any]], descriptions: Sequence[str],
               ) -> tuple[TaskGraph | None, str | None]:
    """The whole graph of the pieces, expanded as one-shot's answer is."""
    data = grounded.expand_graph({"variables": list(starts),
                                  "factors": [{"goal": g} for g in goals]},
                                 task_.found, task, desc)
    names = grounded.factor_names(list(goals))  # expand_graph's names, in the goals' order
    written = {n: d for n, d in zip(names, descriptions, strict=True) if _says(d)}
    for factor in data["factors"]:
        if written.get(factor["name"]):
            factor["description"] = written[factor["name"]][:200]
    try:
        return TaskGraph.model_validate(data), None
    except ValidationError as exc:
        return None, format_problems(problems_from_pydantic(exc, data))


def _ask_goals(runner: StepRunner, task: str, desc: str, task_: GroundedTask,
               shapes: Sequence[Shape], descriptions: Sequence[str], by_subtask: str,
               ) -> tuple[list[dict[str, Any]], list[str]]:
    """Each subtask's goal under the schemas of the shapes still open, verified alone
    as a fragment (an answer closes the shapes whose schema it does not follow).

    Args:
        shapes: The shapes the plan or outline chose (same names, in order).
        by_subtask: ``"goal"`` (variables-first's step 3) or ``"design"``
            (subtasks-first's step 2): the step's name and prompt.

    Returns:
        The goals (JSON) and the descriptions the answers give.

    Raises:
        Abort: a subtask with no valid goal.
    """
    pool = {v.name: v for v in task_.variables}
    names = shapes[0].names
    outline = "; ".join(f"`{n}`: {d}" for n, d in zip(names, descriptions, strict=True))
    goals: list[dict[str, Any]] = []
    written: list[str] = []
    earlier: list[dict[str, Any]] = []
    open_shapes = list(shapes)
    for i, name in enumerate(names):
        schema = ss.obj({"goal": _one_of([s.goal_schemas[i] for s in open_shapes]),
                         "description": ss.text(grounded.GROUNDED_TEXT)})
        offered = list(dict.fromkeys(n for s in open_shapes for n in s.objects[i]))
        scope = [pool[n] for n in offered if n in pool]

        def prompt(lv: Any, i: int = i, name: str = name, scope: Any = scope,
                   schema: Schema = schema, first: str = (offered or [name])[0]) -> str:
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
                          object=first, earlier=earlier_text(earlier),
                          examples=examples, schema=schema_skeleton(schema))

        def evaluate(text: str, i: int = i, name: str = name,
                     schema: Schema = schema) -> Evaluation:
            data = read_strict(text, schema)
            answer = validate_answer(data, GoalAnswer)
            factor = make_factor(name, answer.description or descriptions[i], answer.goal,
                                 scope=None)
            used = [pool[n] for n in answer.goal.variable_names() if n in pool]
            piece, level, feedback = checked_fragment(runner, task, factor, closure(used, pool))
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
        open_shapes = [s for s in open_shapes if not schema_problems(goal, s.goal_schemas[i])]
        goals.append(goal)
        written.append(description if _says(description) else descriptions[i])
        earlier.append({"subtask": name, "verified": out.ok, "goal": goal})
    return goals, written


def variables_first(runner: StepRunner, task: str, desc: str,
                    task_: GroundedTask) -> tuple[TaskGraph | None, str | None]:
    """Approach 1 over a grounded task: starts, plan, goals (each step checked).

    Returns:
        The assembled graph (None where it is not valid) and the problem, if any,
        for the assembly step.

    Raises:
        Abort: a step with no valid answer.
    """
    starts = _ask_starts(runner, task, desc, task_)
    given = {s["name"]: s["initial"] for s in starts}
    shown = "\n".join(json.dumps({"name": v.name, "kind": v.kind, "color": v.color,
                                   "count": v.count,
                                   "initial": given.get(v.name, {"type": "table"})})
                       for v in task_.variables)
    shapes, descriptions = _ask_subtasks(runner, task, desc, task_, shown)
    goals, written = _ask_goals(runner, task, desc, task_, shapes, descriptions, "goal")
    return _assembled(task_, task, desc, starts, goals, written)


def subtasks_first(runner: StepRunner, task: str, desc: str,
                   task_: GroundedTask) -> tuple[TaskGraph | None, str | None]:
    """Approach 2 over a grounded task: outline, then each subtask's goal (checked).

    Returns:
        As :func:`variables_first` (every object starts on the table: the objects
        are declared from the words, as grounded subtasks-first declares them).

    Raises:
        Abort: a step with no valid answer.
    """
    shapes, descriptions = _ask_subtasks(runner, task, desc, task_, None)
    goals, written = _ask_goals(runner, task, desc, task_, shapes, descriptions, "design")
    return _assembled(task_, task, desc, [], goals, written)


def _ask_starts(runner: StepRunner, task: str, desc: str,
                task_: GroundedTask) -> list[dict[str, Any]]:
    """Variables-first step 1: where each movable named object starts."""
    schema = ss.obj({"variables": task_.starts})

    def prompt(lv: Any) -> str:
        return render("variables_stated", task_name=task, task_description=desc,
                      mentions=mentions_text(f"{desc} {task}"), schema=schema_skeleton(schema))

    def evaluate(text: str) -> Evaluation:
        starts = read_strict(text, schema)["variables"]
        given = {s["name"]: s["initial"] for s in starts}
        variables = [v if v.name not in given else StateVariable.model_validate(
            {**v.model_dump(mode="json", exclude_none=True), "initial": given[v.name]})
            for v in task_.variables]
        problems = graph_problems(TaskGraph(name=task, variables=variables))
        if problems:
            return None, "none", ("The starts are not consistent:\n"
                                  + format_problems(problems))
        return starts, "syntax", None

    return list(runner.ask_or_abort("variables", prompt, schema, "variables_answer", evaluate))


def _subtask_items(shape: Shape, with_variables: bool) -> Schema:
    """A shape's subtasks as a tuple: names (and variables) pinned, descriptions free."""
    return tuple_schema([
        ss.obj({"name": {"const": n}, "description": ss.text(grounded.GROUNDED_TEXT),
                **({"variables": {"const": list(shape.objects[i])}} if with_variables else {})})
        for i, n in enumerate(shape.names)])


def _ask_subtasks(runner: StepRunner, task: str, desc: str, task_: GroundedTask,
                  variables: str | None) -> tuple[list[Shape], list[str]]:
    """Variables-first step 2 (the plan, ``variables`` shown) or subtasks-first step 1
    (the outline, ``variables`` None): which shape, one subtask per goal, each
    described by the model.

    Returns:
        The shapes the answer chose (those whose subtasks it lists) and the
        subtasks' descriptions.

    Raises:
        Abort: no valid answer.
    """
    plan = variables is not None
    schema = ss.obj({"subtasks": _one_of([_subtask_items(s, plan) for s in task_.shapes])})
    examples = f"{task} {desc}"

    def prompt(lv: Any) -> str:
        shown = schema_skeleton(schema)
        if plan:
            return render("subtask_plan", task_name=task, task_description=desc,
                          variables=variables,
                          examples=runner.examples(examples, ("memory", "templates"),
                                                   lv.examples), schema=shown)
        return render("subtask_outline", task_name=task, task_description=desc,
                      examples=runner.examples(examples, ("memory", "templates"), lv.examples),
                      schema=shown)

    def evaluate(text: str) -> Evaluation:
        data = read_strict(text, schema)
        answer = validate_answer(data, SubtaskPlan if plan else SubtaskOutline)
        return (data, [s.description for s in answer.subtasks]), "syntax", None

    step = "subtask_plan" if plan else "subtask_outline"
    data, descriptions = runner.ask_or_abort(step, prompt, schema, step, evaluate)
    chosen = [s for s in task_.shapes if not schema_problems(data["subtasks"],
                                                             _subtask_items(s, plan))]
    return chosen, descriptions


__all__ = ["GroundedTask", "Shape", "grounded_task", "subtasks_first", "variables_first"]
