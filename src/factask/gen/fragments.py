"""Pieces the strategies build from answers: subtask fragments, scopes, merges.

Each function checks what a schema cannot (scopes, conflicts between subtasks,
the fragment valid as a graph) and raises :class:`~factask.gen.answers.schemas.AnswerError`
with a message for the model.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping, Sequence
from typing import Any, TypeVar

from pydantic import ValidationError

from factask.gen.answers import step_schemas as ss
from factask.gen.answers.schemas import (
    AnswerError,
    GoalAnswer,
    OutlinedSubtask,
    PlannedSubtask,
    SubtaskDesign,
    SubtaskPlan,
    format_problems,
)
from factask.gen.steps import Abort, Evaluation, PromptBuilder, StepRunner
from factask.graph.factors import SubtaskFactor
from factask.graph.order import in_listed_order
from factask.graph.taskgraph import TaskGraph, graph_problems, problems_from_pydantic
from factask.graph.templates import extract_fragment
from factask.vocabulary.errors import GraphValidationError, Problem
from factask.vocabulary.names import unique_name
from factask.vocabulary.variables import StateVariable


def vars_json(variables: list[StateVariable]) -> str:
    return json.dumps([v.model_dump(mode="json", exclude_none=True) for v in variables],
                      separators=(",", ":"))


def earlier_text(earlier: list[dict[str, Any]]) -> str:
    if not earlier:
        return "(this is the first subtask)"
    return "\n".join(json.dumps(e, separators=(",", ":")) for e in earlier)


def closure(variables: list[StateVariable],
             pool: dict[str, StateVariable]) -> list[StateVariable]:
    """``variables`` plus every variable their initial placements rest on/inside."""
    out = list(variables)
    names = {v.name for v in out}
    i = 0
    while i < len(out):
        for ref in out[i].references():
            if ref not in names and ref in pool:
                out.append(pool[ref])
                names.add(ref)
        i += 1
    return out


def check_goal_scope(answer: GoalAnswer, subtask: str, scope: list[str],
                      pool: dict[str, StateVariable]) -> None:
    """Approach 1: the goal may use only the subtask's planned variables.

    Raises:
        AnswerError: naming each variable outside the scope, plus any other problem
            the goal has with those variables (e.g. a zone used as a support).
    """
    outside = [n for n in answer.goal.variable_names() if n not in scope]
    if not outside:
        return
    problems = [Problem(subtask, "goal", f"uses {n!r}, which is not one of this subtask's "
                        f"variables {scope}" + ("" if n in pool else " nor a task variable"),
                        f"use only {scope}") for n in outside]
    trial = TaskGraph(name="trial", variables=closure(
        [pool[n] for n in [*scope, *outside] if n in pool], pool),
        factors=[SubtaskFactor(name=subtask, goal=answer.goal)])
    problems += [p for p in graph_problems(trial) if "missing variable" not in p.message]
    raise AnswerError("The goal does not fit the subtask:\n" + format_problems(problems),
                      problems)


def make_factor(name: str, description: str, goal: Any, scope: list[str] | None,
                 initial_setup: str = "", after: Sequence[str] = ()) -> SubtaskFactor:
    data: dict[str, Any] = {"name": name, "description": description,
                            "goal": goal.model_dump(mode="python", exclude_none=True),
                            "initial_setup": initial_setup, "after": list(after)}
    if scope is not None:
        data["scope"] = scope
    try:
        return SubtaskFactor.model_validate(data)
    except ValidationError as exc:
        problems = problems_from_pydantic(exc, data)
        raise AnswerError(f"The subtask is not valid:\n{format_problems(problems)}",
                          problems) from None


def prerequisites(factor: SubtaskFactor, variables: Sequence[StateVariable],
                  earlier: Sequence[SubtaskFactor]) -> list[SubtaskFactor]:
    """The earlier subtasks ``factor`` builds on: those that move one of its variables,
    and, in turn, those that move one of theirs, in their order.

    A subtask after others finds the objects they moved where they left them (the
    pyramid's middle layer rests on the bottom layer; the third Hanoi move takes the
    small disk from the goal stand; the fifth finds the start stand empty), so it is
    checked with them, not from the task's start alone.
    """
    needed = {v.name for v in variables}
    chosen: list[SubtaskFactor] = []
    for f in reversed(earlier):
        if needed & set(f.goal.objects):
            chosen.append(f)
            needed |= set(f.scope_names)
    return chosen[::-1]


def fragment(task: str, factor: SubtaskFactor, variables: list[StateVariable],
             earlier: Sequence[SubtaskFactor] = (),
             pool: Mapping[str, StateVariable] | None = None) -> TaskGraph:
    """The graph that checks one subtask: its factor with its variables, after the
    earlier subtasks it builds on (:func:`prerequisites`), valid as a whole.

    Args:
        task: The task's name.
        factor: The subtask's factor.
        variables: Its variables.
        earlier: The subtasks before it, in order (none: it is checked alone).
        pool: Every variable by name (for the earlier subtasks' variables).

    Returns:
        The fragment (one factor of weight 1 when nothing earlier is needed).

    Raises:
        AnswerError: the fragment has problems (each naming its node).
    """
    before = prerequisites(factor, variables, earlier)
    if before:
        names = {f.name for f in before}
        pool = dict(pool or {})
        have = {v.name for v in variables}
        extra = dict.fromkeys(n for f in before for n in f.scope_names
                              if n in pool and n not in have)
        variables = closure(list(variables) + [pool[n] for n in extra], pool)
        factors = in_listed_order([
            f.model_copy(update={"weight": 1.0 / (len(before) + 1), "milestone": False,
                                 "after": [a for a in f.after if a in names]})
            for f in [*before, factor]])
    else:
        factors = [factor.model_copy(update={"weight": 1.0, "after": []})]
    name = f"{task}-{factor.name.replace('_', '-')}"[:100]
    graph = TaskGraph(name=name, description=factor.description, variables=variables,
                      factors=factors)
    try:
        graph.ensure_valid()
    except GraphValidationError as exc:
        alone = "on its own" if not before else \
            f"after the subtasks it builds on ({', '.join(f.name for f in before)})"
        raise AnswerError(f"The subtask is not valid {alone} ({len(exc.problems)} "
                          f"problem(s)):\n{format_problems(exc.problems)}",
                          exc.problems) from None
    return graph


def own_fragment(piece: TaskGraph, factor: str) -> TaskGraph:
    """The one-factor fragment of ``factor`` from a :func:`fragment` (the same graph
    when it is already one): what subtasks-first merges and the memory keeps."""
    if len(piece.factors) == 1:
        return piece
    return extract_fragment(piece, factor, name=piece.name)


def checked_fragment(runner: StepRunner, task: str, factor: SubtaskFactor,
                     variables: list[StateVariable], earlier: Sequence[SubtaskFactor] = (),
                     pool: Mapping[str, StateVariable] | None = None) -> Evaluation:
    """The factor's fragment (:func:`fragment`) through the verification ladder; the
    artefact is its own one-factor fragment (:func:`own_fragment`)."""
    piece = fragment(task, factor, variables, earlier, pool)
    outcome = runner.verifier.check(piece)
    return own_fragment(piece, factor.name), outcome.level, outcome.feedback


def ask_design(runner: StepRunner, task: str, subtask: str, prompt: PromptBuilder,
               schema: dict[str, Any], evaluate: Any) -> tuple[TaskGraph, bool]:
    """Approach 2, step 2 for one subtask: its verified fragment (remembered when it
    passed) and whether it passed.

    Raises:
        Abort: no answer gave a fragment.
    """
    out = runner.ask(f"subtask_design:{subtask}", prompt, schema, "subtask_design", evaluate)
    if out.value is None:
        raise Abort(f"subtask {subtask!r}: no valid design after "
                    f"{runner.max_repairs + 1} attempt(s): {out.feedback}")
    if out.ok:
        runner.remember(out.value, task)
    return out.value, out.ok


def merge_problems(design: SubtaskDesign,
                   defined: dict[str, tuple[StateVariable, str]]) -> list[Problem]:
    """Conflicts of a new subtask with the earlier ones: a shared name defined
    differently. (An object that an earlier subtask moved may be moved again: the
    outline's order sequences the two, the earlier one a milestone --
    :func:`factask.graph.order.in_listed_order`.)"""
    problems = []
    for v in design.variables:
        if v.name in defined and defined[v.name][0] != v:
            old, where = defined[v.name]
            diff = [f"{k}: {getattr(old, k)!r} vs {getattr(v, k)!r}"
                    for k in type(v).model_fields if getattr(old, k) != getattr(v, k)]
            problems.append(Problem(v.name, "", f"defined differently by subtask {where!r} "
                                    f"({'; '.join(diff)})",
                                    "repeat it exactly, leave it out, or use a new name"))
    return problems


def distinct_names(names: Sequence[str], taken: Iterable[str] = ()) -> list[str]:
    """``names`` made distinct from each other and from ``taken``: a repeat gets the
    first free suffix (``put_block``, ``put_block_2``). A subtask's name is a label
    that nothing refers to when it is given (a small model repeats one, or reuses a
    variable's), so it is made distinct rather than sent back.

    Args:
        names: The names, in order.
        taken: Names already in use (the variables').

    Returns:
        The names, the first of each kept as it is.
    """
    used = set(taken)
    return [unique_name(n, used) for n in names]


Listed = TypeVar("Listed", PlannedSubtask, OutlinedSubtask)


def relabelled(subtasks: Sequence[Listed], taken: Iterable[str] = ()) -> list[Listed]:
    """A plan's or outline's subtasks under :func:`distinct_names`, each ``after``
    following the name its subtask now has (a repeated name: its first holder)."""
    labels = distinct_names([s.name for s in subtasks], taken)
    now: dict[str, str] = {}
    for s, label in zip(subtasks, labels, strict=True):
        now.setdefault(s.name, label)
    return [s.model_copy(update={"name": label, "after": [now.get(a, a) for a in s.after]})
            for s, label in zip(subtasks, labels, strict=True)]


def order_problems(subtasks: Sequence[PlannedSubtask | OutlinedSubtask]) -> list[Problem]:
    """Each subtask's ``after`` names only subtasks listed before it (the list is the
    order they are done in, so a later or unknown name is a mistake)."""
    problems: list[Problem] = []
    earlier: list[str] = []
    for s in subtasks:
        for a in s.after:
            if a not in earlier:
                problems.append(Problem(
                    s.name, "after", f"{a!r} is not a subtask listed before it",
                    f"name only earlier subtasks ({', '.join(earlier)})" if earlier
                    else "leave `after` empty for the first subtask"))
        earlier.append(s.name)
    return problems


def as_planned(factors: Sequence[SubtaskFactor],
               subtasks: Sequence[PlannedSubtask | OutlinedSubtask]) -> list[SubtaskFactor]:
    """The factors in the order the plan gives: each ``after`` its subtask's ``after``
    (names of factors that exist), then the listing's order for objects moved more
    than once (:func:`factask.graph.order.in_listed_order`).

    Args:
        factors: One factor per subtask, named as the subtasks, in the listed order.
        subtasks: The plan's or outline's subtasks.

    Returns:
        Copies of the factors.
    """
    wanted = {s.name: s.after for s in subtasks}
    names = {f.name for f in factors}
    out = []
    for f in factors:
        extra = [a for a in wanted.get(f.name, ()) if a in names and a != f.name]
        out.append(f.model_copy(update={"after": list(dict.fromkeys([*f.after, *extra]))})
                   if extra else f)
    return in_listed_order(out)


def without_repeats(variables: Sequence[StateVariable],
                    named: Iterable[str] = ()) -> list[StateVariable]:
    """The variables with repeats of an earlier one's name dropped where that loses
    nothing: the same object again (every field but the description equal), or, for
    a name in ``named`` (the proposal's own objects, already declared as it says),
    any later declaration. Other repeats stay, for the check to report.

    Args:
        variables: The answer's variables, in order.
        named: Names whose first declaration is authoritative.
    """
    first: dict[str, StateVariable] = {}
    fixed_names = set(named)
    out = []
    for v in variables:
        seen = first.get(v.name)
        if seen is not None and (v.name in fixed_names or seen.model_dump(
                exclude={"description"}) == v.model_dump(exclude={"description"})):
            continue
        first.setdefault(v.name, v)
        out.append(v)
    return out


def plan_problems(plan: SubtaskPlan, variables: list[StateVariable]) -> list[Problem]:
    """What a schema cannot check in a subtask plan: unique subtask names, none
    named like a variable, only declared variables, and in each subtask something a
    goal relation can move (else its goal step has no possible answer)."""
    names = [v.name for v in variables]
    problems: list[Problem] = []
    seen: set[str] = set()
    for s in plan.subtasks:
        if s.name in seen:
            problems.append(Problem(s.name, "name", "two subtasks have this name", "rename one"))
        if s.name in names:
            problems.append(Problem(s.name, "name", "a variable has this name",
                                    "rename the subtask"))
        seen.add(s.name)
        for v in s.variables:
            if v not in names:
                problems.append(Problem(s.name, "variables", f"unknown variable {v!r}",
                                        f"use only {names}"))
        kinds = {v.name: v.kind for v in variables if v.name in s.variables}
        moved = [v.name for v in variables if v.name in s.variables and v.fixed is False]
        if kinds and not ss.goal_schema(kinds, moved)["anyOf"]:
            problems.append(Problem(s.name, "variables", "no goal relation can move any of "
                                    "these variables", "add the object the subtask moves"))
    return problems + order_problems(plan.subtasks)
