"""Goals whose layout fits, by construction: a grounded schema's goals pruned by the
relations' own solvers.

A grounded goal list (:mod:`factask.gen.reading.grounded`, :mod:`factask.gen.reading.cover`) pins
which named objects a goal moves and which it anchors on, and the objects' kinds,
counts and (default) sizes are known before the model writes a token. So whether
such a goal can be laid out at reset -- twelve blocks in one 12 cm zone, a stack
of nine blocks under the 0.30 m workspace ceiling, four blocks 0.5 m apart on a
0.3 m line, a row of four on one pallet's object -- is known too. Here each
pinned goal variant is laid out alone by the same code the runtime level runs
(:func:`factask.sim.layout.sampling.sample_layout` then
:func:`factask.sim.layout.solving.solve_targets`: the relations' packing, height and
row-length checks, one definition of each fact), and the variants that cannot be
are left out of the grammar: an anchor that cannot hold the objects, a row's
spacing that does not fit its line, a circle wider than the workspace (such a
length becomes an ``enum`` of the :data:`LENGTHS` that fit). A shape of goals
with a goal left with no variant is dropped; a schema pruned to nothing is kept
as it was (the ladder reports it).

Goals that may share an anchor are then checked together, by the same code
(:func:`share_anchors`, per tuple of goals: :func:`goals_problem` lays them out
as one graph): for each named object that two or more goals of a shape may
anchor on, every way they can all anchor on it is laid out -- three cylinders
aligned with one fixture, a stack on the fixture another goal fills, blocks
put on the block other goals use. Where one way cannot be laid out, or the ways
are more than :data:`JOINT_COMBOS`, or the shape's :data:`JOINT_BUDGET_S` of
CPU time is spent, the anchor is left to one goal (the one pinned to it, else
the object's own goal, else the first), unless that would leave another goal
with no variant; two goals pinned to an anchor that cannot hold both drop their
shape. A grammar cannot say "at most two of these goals use the bowl", so an
anchor is shared by all that may name it or by one: a shareable pair within an
unshareable trio is not offered.

Goals that could anchor on one another in a circle (the blue box on the green
one and the green box on the blue one: "factor order has a cycle") build only on
objects that come earlier in the words' order (:func:`acyclic_anchors`,
:func:`factask.gen.reading.bases.base_order`).

Still the runtime level's: a goal met at the start, goals that must share an
anchor when that was not shown either way (more ways than :data:`JOINT_COMBOS`
all fitting, or the budget spent), a search that ran out of time (counted
as fitting, alone or together), goals that interact without sharing an anchor
(an object moved onto another that a later goal moves away; a row beside a
zone), and the plain goal list sent where no shape covers the named objects
(its ``objects`` are not pinned, so nothing here applies).
"""

from __future__ import annotations

import re
import time
from collections.abc import Collection, Sequence
from dataclasses import replace
from functools import lru_cache
from itertools import islice, product
from math import prod
from typing import Any

import numpy as np
from pydantic import ValidationError

from factask.gen.reading.cover import names_of, without_names
from factask.gen.reading.mentions import Mention
from factask.gen.reading.parts import with_hosts
from factask.graph.factors import SubtaskFactor
from factask.graph.order import in_listed_order
from factask.graph.taskgraph import TaskGraph
from factask.relations import RELATION_TYPES
from factask.scene.collision import Deadline, LayoutError
from factask.sim.layout.sampling import sample_layout
from factask.sim.layout.solving import solve_targets
from factask.vocabulary.errors import FactaskError

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
#: Most ways (combinations of the goals' variants) that the goals which may share an
#: anchor are laid out together; beyond, only the first are tried (one that does
#: not fit still shows they cannot share it) and the anchor is left to one goal.
JOINT_COMBOS = 16
#: CPU seconds (this thread's) all the joint checks of one :func:`prune` may take;
#: an anchor not shown shareable by then is left to one goal.
JOINT_BUDGET_S = 3.0


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
    return _canonical_problem([goal], found)


def goals_problem(goals: Sequence[dict[str, Any]], found: Sequence[Mention]) -> str | None:
    """Why ``goals`` together (one graph, done in the listed order) cannot be laid
    out at reset: as :func:`layout_problem`, for goals that share an anchor.

    Args:
        goals: Goals (JSON) over the names of ``found``.
        found: The proposal's mentions.

    Returns:
        The solver's reason, or None (fits, not a valid graph, or out of time).
    """
    return _canonical_problem(goals, found)


def _canonical_problem(goals: Sequence[dict[str, Any]], found: Sequence[Mention]) -> str | None:
    """:func:`_problem` with the names of ``found`` replaced by placeholders that sort
    as they do and the colours left out: a layout depends on kinds, counts and what
    moves, not on what things are called or their colour, so proposals alike in those
    share one cached search (the reason is given back in the proposal's own names)."""
    names = sorted({m.name for m in found})
    width = len(str(len(names)))
    to = {n: f"v{i:0{width}d}" for i, n in enumerate(names)}
    back = {c: n for n, c in to.items()}

    def rename(value: Any) -> Any:
        if isinstance(value, list):
            return [rename(v) for v in value]
        return to.get(value, value) if isinstance(value, str) else value

    canon = tuple(_key({k: rename(v) for k, v in g.items()}) for g in goals)
    mentions = tuple(replace(m, name=to[m.name], color=None,  # a drawer's cabinet renamed too
                             start=tuple((k, rename(v)) for k, v in m.start)) for m in found)
    reason = _problem(canon, mentions)
    if reason is None:
        return None
    return re.sub(r"\bv\d+(?=\b|__)", lambda m: back.get(m.group(0), m.group(0)), reason)


def _key(goal: dict[str, Any]) -> tuple[tuple[str, Any], ...]:
    return tuple(sorted((k, tuple(v) if isinstance(v, list) else v) for k, v in goal.items()))


@lru_cache(maxsize=4096)
def _problem(keys: tuple[tuple[tuple[str, Any], ...], ...],
             found: tuple[Mention, ...]) -> str | None:
    goals = [{k: list(v) if isinstance(v, tuple) else v for k, v in key} for key in keys]
    used = with_hosts({n for goal in goals for v in goal.values()  # a drawer's cabinet too
                       for n in (v if isinstance(v, list) else [v]) if isinstance(n, str)}, found)
    variables = [m.as_variable() for m in found if m.name in used]
    try:
        factors = in_listed_order([SubtaskFactor.model_validate(
            {"name": f"goal_{i}", "description": "goal", "goal": goal, "weight": 1 / len(goals)})
            for i, goal in enumerate(goals)])
        graph = TaskGraph.model_validate({  # + whole-graph checks: an unanchored rope_along
            "name": "capacity", "description": "goals sharing an anchor", "variables": variables,
            "factors": [f.model_dump(mode="json", exclude_none=True) for f in factors]}
        ).ensure_valid()
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


def moving_anchors(goal: dict[str, Any], earlier: Sequence[dict[str, Any]]
                   ) -> list[dict[str, Any]]:
    """The goals of ``earlier`` (JSON) that move an object ``goal`` anchors on: "the
    two blocks in a row" before "the log across the two blocks"."""
    fields = RELATION_TYPES[goal["type"]].anchor_fields if goal.get("type") in \
        RELATION_TYPES else ()
    anchors = {n for f in fields for n in (goal.get(f) if isinstance(goal.get(f), list)
                                           else [goal.get(f)]) if isinstance(n, str)}
    return [g for g in earlier if anchors & set(g.get("objects") or [])]


def fit_variant(branch: Schema, found: Sequence[Mention],
                before: Sequence[dict[str, Any]] = ()) -> Schema | None:
    """A pinned goal branch narrowed to what can be laid out, or None (nothing can).

    Its anchor fields keep the names (and null) whose goal fits, the others set to
    their pinned or null value; a free length (a row's ``spacing``, a circle's
    ``radius``) becomes the :data:`LENGTHS` that fit (and null where the default
    fits). A branch whose ``objects`` are not pinned comes back unchanged. ``before``:
    goals done first that move what this one anchors on ("the log across the two
    blocks" after "the two blocks in a row"): laid out with them, in order.
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
    def fits(goal: dict[str, Any]) -> bool:
        if layout_problem(goal, found) is None:
            return True
        earlier = moving_anchors(goal, before)
        return bool(earlier) and goals_problem([*earlier, goal], found) is None
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
    # Other choices (an aligned goal's mode): the values whose layout fits, not the first.
    anchors = RELATION_TYPES[relation].anchor_fields
    for field in [f for f in base if f not in anchors and f not in ("type", "objects")]:
        if len(values := props[field].get("enum", [])) > 1:
            if not (ok := [v for v in values if fits({**base, field: v})]):
                return None
            new[field], base[field] = {**props[field], "enum": ok}, ok[0]
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


def prune(schema: Schema, found: Sequence[Mention],
          order: Sequence[str] | None = None) -> Schema | None:
    """``schema`` (a goal, a goal list, an ``anyOf`` of shapes) with every pinned goal
    variant narrowed by :func:`fit_variant` and every tuple of goals by
    :func:`share_anchors`: variants that cannot be laid out dropped, an anchor
    that goals cannot share left to one of them, a tuple or object left with a
    part that cannot be, dropped (None: nothing is left).

    Args:
        schema: The schema (JSON Schema as a dict).
        found: The proposal's mentions.
        order: The order in which goals may build on objects other goals move
            (:func:`acyclic_anchors`; default: the order of mention).

    Returns:
        The narrowed schema, or None when nothing is left.
    """
    return _prune(schema, found, Deadline.after(JOINT_BUDGET_S, clock=time.thread_time), order)


def _prune(schema: Schema, found: Sequence[Mention], budget: Deadline,
           order: Sequence[str] | None = None,
           before: Sequence[dict[str, Any]] = ()) -> Schema | None:
    props = schema.get("properties")
    if isinstance(props, dict) and isinstance(props.get("type"), dict) \
            and props["type"].get("const") in RELATION_TYPES:
        return fit_variant(schema, found, before)
    if "anyOf" in schema:
        kept = [p for o in schema["anyOf"]
                if (p := _prune(o, found, budget, order, before)) is not None]
        if not kept:
            return None
        return kept[0] if len(kept) == 1 else {**schema, "anyOf": kept}
    if isinstance(schema.get("prefixItems"), list):
        items: list[Schema | None] = []
        for item in schema["prefixItems"]:
            # A goal anchored on what earlier goals move may be laid out after them.
            earlier = [g for i in items if i is not None for g in _first_goal(i)]
            items.append(_prune(item, found, budget, order, earlier))
        if any(i is None for i in items):
            return None
        ordered = acyclic_anchors([i for i in items if i is not None],
                                  order if order is not None else [m.name for m in found])
        shared = None if ordered is None else share_anchors(ordered, found, budget)
        return None if shared is None else {**schema, "prefixItems": shared}
    if isinstance(schema.get("items"), dict):
        item = _prune(schema["items"], found, budget, order)
        return None if item is None else {**schema, "items": item}
    if isinstance(props, dict) and "goal" in props:
        goal = _prune(props["goal"], found, budget, order, before)
        return None if goal is None else {**schema, "properties": {**props, "goal": goal}}
    return schema


def _at_values(variant: Schema) -> dict[str, Any] | None:
    """A goal variant as a goal (JSON): its pinned objects, every other field at its
    pinned (or first, or null) value; None where a field has none."""
    props = variant["properties"]
    goal: dict[str, Any] = {"objects": _pinned_objects(props["objects"])}
    for field, schema in props.items():
        if field != "objects":
            known, value = _value(schema)
            if not known:
                return None
            goal[field] = value
    return goal


def _first_goal(item: Schema) -> list[dict[str, Any]]:
    """A tuple item's first goal variant as a goal (:func:`_at_values`); [] where it
    has none or is not a pinned goal."""
    variants = _variants(item)
    goal = _at_values(variants[0]) if variants else None
    return [goal] if goal is not None else []


def _variants(item: Schema) -> list[Schema] | None:
    """A tuple item's (``{"goal": ...}``) goal variants, each a relation with its
    ``objects`` pinned; None when it is not such an item."""
    goal = item.get("properties", {}).get("goal") if isinstance(item, dict) else None
    if not isinstance(goal, dict):
        return None
    variants = goal.get("anyOf", [goal])
    for v in variants:
        props = v.get("properties", {})
        if props.get("type", {}).get("const") not in RELATION_TYPES \
                or _pinned_objects(props.get("objects", {})) is None:
            return None
    return variants


def _anchor_fields(variant: Schema) -> list[str]:
    props = variant["properties"]
    return [f for f in RELATION_TYPES[props["type"]["const"]].anchor_fields if f in props]


def _on(variant: Schema, anchor: str) -> list[dict[str, Any]]:
    """The goals (JSON) of ``variant`` that name ``anchor`` in an anchor field: one
    per such field, the other fields at their pinned (or first, or null) values."""
    props = variant["properties"]
    base = _at_values(variant)
    if base is None:
        return []
    out = []
    for field in _anchor_fields(variant):
        if anchor in names_of(props[field]):
            out.append({**base, **{f: None for f in _anchor_fields(variant)
                                   if base.get(f) == anchor}, field: anchor})
    return out


def _pinned_on(variant: Schema, anchor: str) -> bool:
    """Whether ``variant`` names ``anchor`` whatever the model writes (a const field)."""
    return any(variant["properties"][f].get("const") == anchor for f in _anchor_fields(variant))


def _uses(variant: Schema, anchor: str) -> bool:
    """Whether ``variant`` moves ``anchor`` or names it as a constant anchor."""
    return anchor in (_pinned_objects(variant["properties"]["objects"]) or []) \
        or _pinned_on(variant, anchor)


def _off(variant: Schema, banned: Collection[str]) -> Schema | None:
    """``variant`` with the ``banned`` names left out of its anchor fields (None: a
    field is left with nothing)."""
    props = dict(variant["properties"])
    for field in _anchor_fields(variant):
        if not set(banned) & set(names_of(props[field])):
            continue
        narrowed = without_names(props[field], banned)
        if narrowed is None:
            return None
        props[field] = narrowed
    return {**variant, "properties": props}


def _shareable(goals: dict[int, list[Schema]], sharers: Sequence[int], anchor: str,
               found: Sequence[Mention], budget: Deadline) -> bool | None:
    """Whether every way the ``sharers`` positions can name ``anchor`` together lays
    out: True, False (one way cannot), None (not shown: the ways are more than
    :data:`JOINT_COMBOS`, or the budget is spent)."""
    ways: list[list[dict[str, Any]]] = []
    for i in sharers:
        mine: list[dict[str, Any]] = []
        for variant in goals[i]:
            mine.extend(g for g in _on(variant, anchor) if g not in mine)
        if not mine:
            return None
        ways.append(mine)
    # Beyond JOINT_COMBOS ways only the first are tried: one that cannot be laid out
    # still proves the anchor unshareable; all that can prove nothing.
    complete = prod(len(w) for w in ways) <= JOINT_COMBOS
    for combo in islice(product(*ways), JOINT_COMBOS):
        if budget.passed:
            return None
        if goals_problem(combo, found) is not None:
            return False
    return True if complete else None


def share_anchors(items: Sequence[Schema], found: Sequence[Mention],
                  budget: Deadline | None = None) -> list[Schema] | None:
    """A tuple of goals (``{"goal": ...}`` items) with each anchor that its goals
    cannot share left to one of them.

    For each named object that two or more goals may anchor on, every way they can
    all anchor on it is laid out together (:func:`goals_problem`: the runtime's own
    ``sample_layout`` and ``solve_targets``). Where one cannot -- or the ways are
    more than :data:`JOINT_COMBOS`, or the ``budget`` is spent (no proof that they
    fit) -- the anchor is one goal's: the goal pinned to it ("the red ell in the
    red fixture"), else the goal of that object itself (every variant moves it
    or puts another object on it), else the first that owns no anchor yet, else
    the first; the others lose it (a variant with it as a constant is dropped).
    Where that would leave goals with no variant (they can only name this
    anchor), those goals (and any pinned to it) keep the anchor and the others
    lose it; the shape is dropped if they cannot be laid out on it together.

    Args:
        items: The tuple's items (after :func:`fit_variant`).
        found: The proposal's mentions.
        budget: CPU time for the joint checks (default :data:`JOINT_BUDGET_S`).

    Returns:
        The items (unchanged where no anchor is shared, or items that are not
        pinned goals), or None: goals that must all name one anchor (pinned to
        it, or left nothing else) and cannot share it.
    """
    budget = budget or Deadline.after(JOINT_BUDGET_S, clock=time.thread_time)
    goals = {i: vs for i, item in enumerate(items) if (vs := _variants(item)) is not None}
    if len(goals) < 2:
        return list(items)
    changed: set[int] = set()
    owned: set[int] = set()
    for anchor in (m.name for m in found):
        sharers = [i for i, vs in goals.items() if any(_on(v, anchor) for v in vs)]
        if len(sharers) < 2 or _shareable(goals, sharers, anchor, found, budget):
            continue
        owners = [i for i in sharers if all(_pinned_on(v, anchor) for v in goals[i])]
        if len(owners) > 1 and _shareable(goals, owners, anchor, found, budget) is False:
            return None
        if not owners:
            own = [i for i in sharers if all(_uses(v, anchor) for v in goals[i])]
            idle = [i for i in sharers if i not in owned]
            owners = (own or idle or sharers)[:1]
        narrowed = {i: [w for v in goals[i] if (w := _off(v, {anchor})) is not None]
                    for i in sharers if i not in owners}
        forced = [i for i, kept in narrowed.items() if not kept]  # only ``anchor`` left
        if forced:
            # Goals that can only name the anchor keep it (with any pinned to it); the
            # others lose it. Every answer of the shape puts those on it together.
            pinned = [i for i in owners if all(_pinned_on(v, anchor) for v in goals[i])]
            keep = sorted({*pinned, *forced})
            if len(keep) > 1 and _shareable(goals, keep, anchor, found, budget) is False:
                return None
            owners = keep
            narrowed = {i: kept for i, kept in narrowed.items() if i not in keep}
        owned.update(owners)
        goals.update(narrowed)
        changed.update(narrowed)
    out = list(items)
    for i in changed:
        out[i] = _with_variants(out[i], goals[i])
    return out


def _with_variants(item: Schema, variants: list[Schema]) -> Schema:
    """A tuple item (``{"goal": ...}``) with its goal narrowed to ``variants``."""
    props = item["properties"]
    goal = variants[0] if len(variants) == 1 else {"anyOf": variants}
    return {**item, "properties": {**props, "goal": goal}}


def acyclic_anchors(items: Sequence[Schema], order: Sequence[str]) -> list[Schema] | None:
    """A tuple of goals whose answers cannot anchor in a circle.

    A goal may anchor on an object that another goal of the tuple may move only
    when that object comes before every object the goal moves in ``order``
    (:func:`factask.gen.reading.bases.base_order`: the words' bases first). Then each goal
    anchors only on goals whose objects come earlier, and no answer can put the
    blue box on the green one in one goal and the green box on the blue one in
    another ("factor order has a cycle": the graph is not a task). Anchors no
    other goal moves (a zone, a fixed bowl, a block only stood on) are not
    restricted.

    Args:
        items: The tuple's items (goal items with pinned objects; others pass).
        order: Names in the order objects may carry one another (a name not in it
            comes after every one that is).

    Returns:
        The items, narrowed where needed; None when a goal is left with no variant
        (every answer of this shape would anchor in a circle, or against the
        words' order).
    """
    goals = {i: vs for i, item in enumerate(items) if (vs := _variants(item)) is not None}
    movers = {i: {n for v in vs for n in _pinned_objects(v["properties"]["objects"]) or []}
              for i, vs in goals.items()}
    rank = {name: k for k, name in enumerate(order)}

    def place(name: str) -> int:
        return rank.get(name, len(rank))

    out = list(items)
    for i, variants in goals.items():
        others = {n for k, ns in movers.items() if k != i for n in ns}
        kept = []
        for v in variants:
            own = min((place(n) for n in _pinned_objects(v["properties"]["objects"]) or []),
                      default=len(rank))
            named = {n for f in _anchor_fields(v) for n in names_of(v["properties"][f])}
            later = {n for n in named & others if place(n) >= own}
            if (w := _off(v, later) if later else v) is not None:
                kept.append(w)
        if not kept:
            return None
        if kept != variants:
            out[i] = _with_variants(out[i], kept)
    return out
