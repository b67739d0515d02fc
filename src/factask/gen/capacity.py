"""Goals whose layout fits, by construction: a grounded schema's goals pruned by the
relations' own solvers.

A grounded goal list (:mod:`factask.gen.grounded`, :mod:`factask.gen.cover`) pins
which named objects a goal moves and which it anchors on, and the objects' kinds,
counts and (default) sizes are known before the model writes a token. So whether
such a goal can be laid out at reset -- twelve blocks in one 12 cm zone, a stack
of nine blocks under the 0.30 m workspace ceiling, four blocks 0.5 m apart on a
0.3 m line, a row of four on one pallet's object -- is known too. Here each
pinned goal variant is laid out alone by the same code the runtime level runs
(:func:`factask.sim.sampling.sample_layout` then
:func:`factask.sim.solving.solve_targets`: the relations' packing, height and
row-length checks, one definition of each fact), and the variants that cannot be
are left out of the grammar: an anchor that cannot hold the objects, a row's
spacing that does not fit its line, a circle wider than the workspace (such a
length becomes an ``enum`` of the :data:`LENGTHS` that fit). A shape of goals
with a goal left with no variant is dropped; a schema pruned to nothing is kept
as it was (the ladder reports it).

Only a goal alone is checked: two goals sharing an anchor, or a goal met at the
start, are still the runtime level's to find.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from functools import lru_cache
from typing import Any

import numpy as np
from pydantic import ValidationError

from factask.gen.mentions import Mention
from factask.model.errors import FactaskError
from factask.model.graph import TaskGraph
from factask.relations import RELATION_TYPES
from factask.scene.collision import Deadline, LayoutError
from factask.sim.sampling import sample_layout
from factask.sim.solving import solve_targets

Schema = dict[str, Any]

#: Lengths (m) a pinned goal's free length (a row's ``spacing``, a circle's
#: ``radius``) may take: those within the field's bounds whose layout fits are offered.
LENGTHS = (0.05, 0.06, 0.08, 0.1, 0.12, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5)
#: Layouts tried per goal before it is judged not to fit (a retryable failure each).
TRIES = 2
#: CPU seconds (this thread's) one goal's layout may search (a timeout counts as
#: fitting). CPU, not wall time: on a busy machine a wall budget ran out before
#: the search did, so whether a goal was offered depended on the load.
BUDGET_S = 0.25


def _value(field: Schema) -> tuple[bool, Any]:
    """(known, value): a pinned field's value, null where null is allowed, an
    enum's first value, False for a boolean; (False, None) otherwise."""
    if "const" in field:
        return True, field["const"]
    if field.get("type") == "null" or any(o.get("type") == "null"
                                          for o in field.get("anyOf", [])):
        return True, None
    if field.get("enum"):
        return True, field["enum"][0]
    if field.get("type") == "boolean":
        return True, False
    if field.get("type") in ("number", "integer"):  # not a length this check narrows
        lo = field.get("minimum", field.get("exclusiveMinimum", 0))
        return True, (lo + field.get("maximum", lo + 1)) / 2
    return False, None


def _length_field(field: Schema) -> Schema | None:
    """The number option of a nullable length field (``spacing``, ``radius``), else None."""
    options = field.get("anyOf", [])
    numbers = [o for o in options if o.get("type") == "number" and "enum" not in o]
    if len(numbers) == 1 and any(o.get("type") == "null" for o in options):
        return numbers[0]
    return None


def _within(value: float, number: Schema) -> bool:
    return (value > number.get("exclusiveMinimum", -1e9)
            and value >= number.get("minimum", -1e9)
            and value <= number.get("maximum", 1e9))


def _pinned_objects(field: Schema) -> list[str] | None:
    """The names an ``objects`` field must list (a tuple of consts, or an enum all of
    whose names must be used), else None."""
    items = field.get("prefixItems")
    if isinstance(items, list) and all("const" in i for i in items):
        return [i["const"] for i in items]
    names = field.get("items", {}).get("enum") if isinstance(field.get("items"), dict) else None
    if names and field.get("minItems") == len(names):
        return list(names)
    return None


def layout_problem(goal: dict[str, Any], found: Sequence[Mention]) -> str | None:
    """Why ``goal`` over the named objects alone cannot be laid out at reset.

    Args:
        goal: A goal (JSON) over the names of ``found``.
        found: The proposal's mentions (kind, colour, count; kind-default sizes).

    Returns:
        The solver's reason, or None when it can be laid out, when the goal is
        not a valid goal (the syntax level's to report) or when the search ran out
        of time (not proof that it cannot).
    """
    return _problem(_key(goal), tuple(found))


def _key(goal: dict[str, Any]) -> tuple[tuple[str, Any], ...]:
    return tuple(sorted((k, tuple(v) if isinstance(v, list) else v) for k, v in goal.items()))


@lru_cache(maxsize=4096)
def _problem(key: tuple[tuple[str, Any], ...], found: tuple[Mention, ...]) -> str | None:
    goal = {k: list(v) if isinstance(v, tuple) else v for k, v in key}
    used = {n for v in goal.values() for n in (v if isinstance(v, list) else [v])
            if isinstance(n, str)}
    variables = [m.as_variable() for m in found if m.name in used]
    try:
        graph = TaskGraph.model_validate({
            "name": "capacity", "description": "one goal alone", "variables": variables,
            "factors": [{"name": "goal", "description": "goal", "goal": goal, "weight": 1.0}]})
    except (ValidationError, FactaskError, ValueError):
        return None
    rng = np.random.default_rng(0)
    deadline = Deadline.after(BUDGET_S, clock=time.thread_time)
    last = None
    for _ in range(TRIES):
        try:
            layout = sample_layout(graph, rng, deadline=deadline)
            solve_targets(graph, layout, rng, deadline=deadline)
            return None
        except LayoutError as exc:
            if deadline.passed:
                return None  # out of time: no proof that it cannot
            last = str(exc)
            if not exc.retryable:
                return last
        except (FactaskError, ValueError):
            return None  # not a valid goal here: the syntax level's to report
    return last


def fit_variant(branch: Schema, found: Sequence[Mention]) -> Schema | None:
    """A pinned goal branch narrowed to what can be laid out, or None (nothing can).

    Its anchor fields keep the names (and null) whose goal fits, the others set to
    their pinned or null value; a free length (a row's ``spacing``, a circle's
    ``radius``) becomes the :data:`LENGTHS` that fit (and null where the default
    fits). A branch whose ``objects`` are not pinned comes back unchanged.
    """
    props = branch.get("properties", {})
    relation = props.get("type", {}).get("const")
    objects = _pinned_objects(props.get("objects", {}))
    if relation not in RELATION_TYPES or objects is None:
        return branch
    base: dict[str, Any] = {"type": relation, "objects": objects}
    for field, schema in props.items():
        if field not in base:
            known, value = _value(schema)
            if not known:
                return branch  # a field this check cannot fill: leave it to the ladder
            base[field] = value
    fits: Callable[[dict[str, Any]], bool] = \
        lambda g: layout_problem(g, found) is None  # noqa: E731
    new = dict(props)
    for field in RELATION_TYPES[relation].anchor_fields:
        if field not in props or "const" in props[field]:
            continue
        options = props[field].get("anyOf", [props[field]])
        kept: list[Schema] = []
        for option in options:
            if option.get("type") == "null":
                if fits({**base, field: None}):
                    kept.append(option)
            elif option.get("enum"):
                names = [n for n in option["enum"] if fits({**base, field: n})]
                if names:
                    kept.append({**option, "enum": names})
            else:
                kept.append(option)
        if not kept:
            return None
        new[field] = kept[0] if len(kept) == 1 else {"anyOf": kept}
        base[field] = _value(new[field])[1]
    lengths = {f: n for f, schema in props.items() if (n := _length_field(schema)) is not None}
    for field, number in lengths.items():
        values = [x for x in LENGTHS if _within(x, number) and fits({**base, field: x})]
        options = ([{"type": "number", "enum": values}] if values else []) + \
            ([{"type": "null"}] if fits({**base, field: None}) else [])
        if not options:
            return None
        new[field] = options[0] if len(options) == 1 else {"anyOf": options}
    if not lengths and not fits(base):
        return None
    return {**branch, "properties": new}


def prune(schema: Schema, found: Sequence[Mention]) -> Schema | None:
    """``schema`` (a goal, a goal list, an ``anyOf`` of shapes) with every pinned goal
    variant narrowed by :func:`fit_variant`: variants that cannot be laid out
    dropped, a tuple or object left with a part that cannot be, dropped (None:
    nothing is left)."""
    props = schema.get("properties")
    if isinstance(props, dict) and isinstance(props.get("type"), dict) \
            and props["type"].get("const") in RELATION_TYPES:
        return fit_variant(schema, found)
    if "anyOf" in schema:
        kept = [p for o in schema["anyOf"] if (p := prune(o, found)) is not None]
        if not kept:
            return None
        return kept[0] if len(kept) == 1 else {**schema, "anyOf": kept}
    if isinstance(schema.get("prefixItems"), list):
        items = [prune(i, found) for i in schema["prefixItems"]]
        if any(i is None for i in items):
            return None
        return {**schema, "prefixItems": items}
    if isinstance(schema.get("items"), dict):
        item = prune(schema["items"], found)
        return None if item is None else {**schema, "items": item}
    if isinstance(props, dict) and "goal" in props:
        goal = prune(props["goal"], found)
        return None if goal is None else {**schema, "properties": {**props, "goal": goal}}
    return schema
