"""Subtasks-first (approach 2) grounded in the objects the proposal names.

The ungrounded approach asks a tiny model for a free outline (names it repeats,
lists it writes until the token cap) and then for each subtask's whole design
(variables and goal under the full schema). When the proposal names a movable
object (:func:`factask.gen.reading.grounded.applies`) the two steps ask only for what is
left to decide, as the grounded one-shot does:

* **outline**: at most one subtask per movable named object, each an
  ``object`` (a named movable object: the subtask is about it) and a short
  ``description``; the subtask's name is derived from the object
  (``place_red_block``), so names are unique when the objects are. Where the
  ordered choices are few (:data:`MAX_SEQUENCES`) the schema is an ``anyOf`` of
  tuples of distinct objects -- no object twice, by construction; beyond that an
  array of at most as many items as movable objects, a repeated object refused
  by :func:`read_outline` (fed back). Either way the answer's length is bounded.
* **design** (per subtask): the named objects are constants, declared from the
  proposal's words (:func:`named_variables`: kind, colour, count, size ``null``,
  on the table) and never re-declared; the model writes only the goal over them
  (the relation among those the proposal's words name,
  :func:`factask.gen.reading.grounded.goal_answer`), the subtask's own object first in
  every list the grammar offers. The goal must use that object (moved, or as the
  anchor): :func:`design_problems`.

The merge and assembly are the ungrounded path's (fragments composed, the outline's
order sequencing subtasks that move the same object), and the verification
ladder is unchanged.
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import permutations
from typing import Any

from factask.gen.answers import step_schemas as ss
from factask.gen.answers.schemas import (
    AnswerError,
    GoalAnswer,
    OutlinedSubtask,
    SubtaskOutline,
    validate_answer,
)
from factask.gen.conversation import PromptLevel
from factask.gen.fragments import (
    ask_design,
    checked_fragment,
    closure,
    earlier_text,
    make_factor,
)
from factask.gen.prompts import render, schema_skeleton
from factask.gen.reading import grounded
from factask.gen.reading.cover import must_use, used_names
from factask.gen.reading.mentions import Mention, mentions_text, unnamed_colour
from factask.gen.steps import Evaluation, StepRunner, read_strict
from factask.graph.taskgraph import TaskGraph
from factask.vocabulary.names import slugify
from factask.vocabulary.variables import StateVariable

Schema = ss.Schema

#: Most ordered outlines written out as tuples (3 movable objects: 15).
MAX_SEQUENCES = 16
#: The verb of a subtask's name (``place_red_block``).
VERB = "place"


def subtask_name(obj: str) -> str:
    """The subtask's name for its object (``red_block`` -> ``place_red_block``)."""
    return slugify(f"{VERB} {obj}", "_", 48, VERB)


def movers(found: Sequence[Mention]) -> list[str]:
    """The names of the movable named objects, in the proposal's order (at most
    :data:`~factask.gen.answers.step_schemas.STEP_MAX_SUBTASKS`)."""
    return [m.name for m in grounded.movable(found)][:ss.STEP_MAX_SUBTASKS]


def _sequences(names: Sequence[str]) -> list[tuple[str, ...]] | None:
    """Every ordered choice of distinct ``names`` (longest first, the proposal's
    order first), or None when there are more than :data:`MAX_SEQUENCES`."""
    out: list[tuple[str, ...]] = []
    for k in range(len(names), 0, -1):
        for seq in permutations(names, k):
            out.append(seq)
            if len(out) > MAX_SEQUENCES:
                return None
    return out


def _item(obj: Schema) -> Schema:
    return ss.obj({"object": obj, "description": ss.text(grounded.GROUNDED_TEXT)})


def outline_schema(found: Sequence[Mention]) -> Schema:
    """Approach 2, step 1, grounded: ``{"subtasks": [{object, description}, ...]}``.

    Args:
        found: The proposal's mentions (with a movable one: :func:`grounded.applies`).

    Returns:
        The schema: an ``anyOf`` of tuples of distinct objects when few, else an
        array of 1..n items whose ``object`` is an enum of the movable objects.
    """
    names = movers(found)
    sequences = _sequences(names)
    if sequences is None:
        subtasks: Schema = ss.array(_item(ss.name(names)), 1, len(names))
    else:
        tuples = [{"type": "array", "prefixItems": [_item({"const": n}) for n in seq],
                   "items": False, "minItems": len(seq), "maxItems": len(seq)}
                  for seq in sequences]
        subtasks = tuples[0] if len(tuples) == 1 else {"anyOf": tuples}
    return ss.obj({"subtasks": subtasks})


def read_outline(data: dict[str, Any], found: Sequence[Mention]) -> SubtaskOutline:
    """The outline of a (schema-checked) grounded answer.

    Args:
        data: The answer, ``{"subtasks": [{"object", "description"}, ...]}``.
        found: The proposal's mentions.

    Returns:
        One subtask per object, named by :func:`subtask_name`, in the answer's order.

    Raises:
        AnswerError: an object that is not a movable named one, or one named twice.
    """
    allowed = movers(found)
    items = data.get("subtasks")
    if not isinstance(items, list) or not items:
        raise AnswerError("The outline needs at least one subtask.")
    objects = [i.get("object") if isinstance(i, dict) else None for i in items]
    unknown = [o for o in objects if o not in allowed]
    if unknown:
        raise AnswerError(f"Each subtask's `object` is one of {allowed}; not {unknown}.")
    repeated = sorted({o for o in objects if objects.count(o) > 1})
    if repeated:
        raise AnswerError(f"One subtask per object; named more than once: {repeated}. "
                          "Put everything done to an object in its one subtask.")
    return SubtaskOutline(subtasks=[
        OutlinedSubtask(name=subtask_name(o),
                        description=str(i.get("description") or f"place the {o}"))
        for o, i in zip(objects, items, strict=True)])


def outline_objects(outline: SubtaskOutline, found: Sequence[Mention]) -> dict[str, str]:
    """Subtask name -> its object (the inverse of :func:`subtask_name`)."""
    by_name = {subtask_name(n): n for n in movers(found)}
    return {s.name: by_name[s.name] for s in outline.subtasks if s.name in by_name}


def named_variables(found: Sequence[Mention]) -> list[StateVariable]:
    """The named objects as variables, declared from the proposal's words
    (:meth:`~factask.gen.reading.mentions.Mention.as_variable`), on the table."""
    unnamed = unnamed_colour(found)
    return [StateVariable.model_validate(m.as_variable(unnamed=unnamed)) for m in found]


def design_schema(variables: Sequence[StateVariable], obj: str, proposal: str,
                  unused: Sequence[str] = (), remaining: int = 1,
                  narrow: bool = True) -> Schema:
    """Approach 2, step 2, grounded: one subtask's ``{"goal", "description"}``.

    Args:
        variables: The named objects (:func:`named_variables`), all constants.
        obj: The subtask's object: listed first wherever the grammar offers names.
        proposal: The proposal's text (the relations its words name).
        unused: The named objects no goal uses yet (no earlier goal, no later
            subtask's own object).
        remaining: Subtasks left, this one included.
        narrow: Whether the goal must leave the later subtasks able to use every
            named object (:func:`factask.gen.reading.cover.must_use`; the prompt shows
            the plain schema).

    Returns:
        The goal over the named objects (:func:`factask.gen.reading.grounded.goal_answer`),
        narrowed where the subtasks left have no slack.
    """
    ordered = sorted(variables, key=lambda v: v.name != obj)
    schema = grounded.goal_answer(ordered, proposal)
    if not narrow or "goal" not in schema.get("properties", {}):
        return schema
    counts = {v.name: v.count for v in variables}
    movable = [v.name for v in variables if not v.is_fixed]
    goal = must_use(schema["properties"]["goal"], obj, unused, remaining, counts, movable)
    if goal is None:
        return schema
    return {**schema, "properties": {**schema["properties"], "goal": goal}}


def design_problems(goal: dict[str, Any], obj: str, found: Sequence[Mention]) -> list[str]:
    """What a grounded design's goal lacks: its subtask's object, or a group of one.

    Args:
        goal: The goal (JSON).
        obj: The subtask's object.
        found: The proposal's mentions.

    Returns:
        One line per problem (empty: none).
    """
    out = [p.replace("factors.0.", "") for p in grounded.goal_problems([goal], found)
           if p.startswith("factors.")]
    names = {n for v in goal.values() for n in (v if isinstance(v, list) else [v])
             if isinstance(n, str)}
    if obj not in names:
        out.append(f"goal: this subtask is about {obj}; its goal must move {obj} or "
                   "anchor on it")
    return out


def unused_problems(goals: Sequence[dict[str, Any]], found: Sequence[Mention]) -> list[str]:
    """The named objects no goal of the assembled task uses (fed back, as for the
    grounded one-shot)."""
    return [p for p in grounded.goal_problems(list(goals), found)
            if not p.startswith("factors.")]


def ask_outline(runner: StepRunner, task: str, desc: str,
                found: Sequence[Mention]) -> SubtaskOutline:
    """Step 1, grounded: the subtasks, one per movable named object at most.

    Raises:
        Abort: no valid outline.
    """
    schema = outline_schema(found)

    def prompt(lv: PromptLevel) -> str:
        return render("subtask_outline_grounded", task_name=task, task_description=desc,
                      mentions=mentions_text(f"{desc} {task}"), movable=", ".join(movers(found)),
                      schema=schema_skeleton(schema))

    def evaluate(text: str) -> Evaluation:
        return read_outline(read_strict(text, schema), found), "syntax", None

    return runner.ask_or_abort("subtask_outline", prompt, schema, "subtask_outline", evaluate)


def design_fragments(runner: StepRunner, task: str, desc: str,
                     found: Sequence[Mention]) -> list[TaskGraph]:
    """Steps 1 and 2, grounded: the outline, then each subtask's goal over the named
    objects, verified on its own as a one-factor fragment (in the outline's order).

    Raises:
        Abort: no valid outline, or a subtask with no valid design.
    """
    outline = ask_outline(runner, task, desc, found)
    objects = outline_objects(outline, found)
    outline_text = "; ".join(f"`{s.name}`: {s.description}" for s in outline.subtasks)
    variables = named_variables(found)
    pool = {v.name: v for v in variables}
    pieces: list[TaskGraph] = []
    earlier: list[dict[str, Any]] = []
    names = [m.name for m in found]
    used: set[str] = set()
    for i, sub in enumerate(outline.subtasks):
        obj = objects[sub.name]
        later = {objects[s.name] for s in outline.subtasks[i + 1:]}
        unused = [n for n in names if n not in used and n not in later]
        schema = design_schema(variables, obj, desc, unused, len(outline.subtasks) - i)
        shown = schema_skeleton(design_schema(variables, obj, desc, narrow=False))

        def prompt(lv: PromptLevel, sub: Any = sub, shown: str = shown,
                   obj: str = obj) -> str:
            return render(
                "subtask_design_grounded", task_name=task, task_description=desc,
                mentions=mentions_text(f"{desc} {task}"), outline=outline_text,
                subtask_name=sub.name, subtask_description=sub.description, object=obj,
                earlier=earlier_text(earlier),
                examples=runner.examples(f"{sub.name} {sub.description}",
                                         ("memory", "templates"), lv.examples),
                schema=shown)

        def evaluate(text: str, sub: Any = sub, schema: Any = schema,
                     obj: str = obj) -> Evaluation:
            data = read_strict(text, schema)
            problems = design_problems(data["goal"], obj, found)
            if problems:
                raise AnswerError("The goal does not fit the subtask:\n"
                                  + "\n".join(f"- {p}" for p in problems))
            answer = validate_answer(data, GoalAnswer)
            used = [pool[n] for n in answer.goal.variable_names() if n in pool]
            factor = make_factor(sub.name, answer.description or sub.description,
                                 answer.goal, scope=None)
            return checked_fragment(runner, task, factor, closure(used, pool))

        piece, ok = ask_design(runner, task, sub.name, prompt, schema, evaluate)
        pieces.append(piece)
        used |= used_names(piece.factors[0].goal.model_dump(mode="json", exclude_none=True),
                           names)
        earlier.append({"subtask": sub.name, "verified": ok,
                        "goal": piece.factors[0].goal.model_dump(mode="json",
                                                                  exclude_none=True)})
    return pieces


def assembly_problem(graph: TaskGraph, found: Sequence[Mention]) -> str | None:
    """The assembled graph's named objects that no goal uses, as feedback (None: none)."""
    lines = unused_problems([f.goal.model_dump(mode="json", exclude_none=True)
                             for f in graph.factors], found)
    if not lines:
        return None
    return "The goals do not make the proposal's task:\n" + "\n".join(f"- {p}" for p in lines)


__all__ = ["MAX_SEQUENCES", "VERB", "ask_outline", "assembly_problem", "design_fragments",
           "design_problems", "design_schema", "movers", "named_variables", "outline_objects",
           "outline_schema", "read_outline", "subtask_name", "unused_problems"]
