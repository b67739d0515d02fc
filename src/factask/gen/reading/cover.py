"""Goal lists that use every object the proposal names, by construction.

A grounded answer (:mod:`factask.gen.reading.grounded`) may only write goals over the
objects the proposal names, but an array of goals can still leave one out: the
one goal a tiny model writes for "the red block in the red bowl and the blue
block in the blue bowl" moves the red block and never mentions the blue bowl.
Checking that afterwards (``goal_problems``) only feeds it back. Here the
grammar holds it instead: the goal list is an ``anyOf`` of a few *shapes*,
tuples whose goals pin which named object each one moves and which fixed object
it anchors on, so that every shape uses every named object:

* **group**: one goal moving every movable named object (a row, a stack, all of
  them in the zone), its anchor fields naming every fixed object; with no fixed
  object, also a goal over all but one movable object anchored on that one
  (the stack's base);
* **each**: one goal per movable object, in the proposal's order, that moves
  that object alone or (in a goal no fixed object is pinned to) anchors another
  one on it; the fixed objects spread over the goals' anchors: an ``anyOf``
  over the ways to give each fixed object a goal of its own (at most
  :data:`MAX_PATTERNS`; the other goals anchor on any other named object, or on
  none) -- only the proposal's own pairing where its words alternate "X in A
  and Y in B" (:func:`paired_in_order`), and a fixed object pinned to the
  movable one of its colour where the words pair by colour (:func:`colour_pins`);
* **per anchor**: with one movable object and more fixed objects than that, one
  goal per fixed object, each moving the movable one.

Which relation each goal is, and which shape, is still the model's (the grammar
keeps every shape alive until its tokens tell them apart). A shape is built
from the relation branches the caller allows (the relations the proposal's
words name); where none covers every named object the caller falls back to a
plain array, and the check afterwards.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Sequence
from itertools import permutations
from typing import Any

from factask.relations import RELATION_TYPES

Schema = dict[str, Any]

#: Relations that arrange several objects: with fewer than two, the goal is trivial.
GROUP_RELATIONS = frozenset(["row", "circle", "stack"])
#: Most ways of spreading the fixed objects over one-goal-per-object lists
#: (4 movable and 4 fixed objects: 24); beyond it the fixed objects are not pinned.
MAX_PATTERNS = 24


def names_of(field: Schema) -> list[str]:
    """The names an anchor field's schema allows (``const``, ``enum``, or through a
    nullable ``anyOf``)."""
    if "const" in field:
        return [field["const"]] if isinstance(field["const"], str) else []
    out = [n for n in field.get("enum", []) if isinstance(n, str)]
    for option in field.get("anyOf", []):
        out.extend(n for n in names_of(option) if n not in out)
    return out


def nullable(field: Schema) -> bool:
    """Whether an anchor field's schema allows ``null``."""
    return field.get("type") == "null" or any(nullable(o) for o in field.get("anyOf", []))


def without_names(field: Schema, banned: Collection[str]) -> Schema | None:
    """An anchor field's schema without the ``banned`` names (None: nothing left)."""
    names = [n for n in names_of(field) if n not in banned]
    options: list[Schema] = [{"type": "string", "enum": names}] if names else []
    if nullable(field):
        options.append({"type": "null"})
    if not options:
        return None
    return options[0] if len(options) == 1 else {"anyOf": options}


def tuple_schema(items: Sequence[Schema]) -> Schema:
    """An array of exactly ``items``, in order (a JSON Schema tuple)."""
    return {"type": "array", "prefixItems": list(items), "items": False,
            "minItems": len(items), "maxItems": len(items)}


def pin(branch: Schema, objects: Sequence[str], anchors: Sequence[str],
        counts: dict[str, int]) -> list[Schema]:
    """One relation branch with its ``objects`` exactly ``objects`` and each of
    ``anchors`` in an anchor field of its own.

    Args:
        branch: A goal branch (an object schema with ``type`` const, ``objects``
            an array of an enum, its anchor fields as ``const``, enum or nullable).
        objects: The names it must move, in this order (non-empty).
        anchors: The names its anchor fields must name (distinct fields).
        counts: Name -> count (a row or circle needs two objects, a stack two
            with its base).

    Returns:
        The variants (one per way of giving the anchors fields), possibly none.
    """
    props = branch.get("properties", {})
    relation = props.get("type", {}).get("const")
    spec = RELATION_TYPES.get(relation) if isinstance(relation, str) else None
    field_objects = props.get("objects", {})
    allowed = names_of(field_objects.get("items", {}))
    if spec is None or not objects or not set(objects) <= set(allowed) \
            or len(set(objects)) != len(objects) \
            or not field_objects.get("minItems", 1) <= len(objects) \
            <= field_objects.get("maxItems", len(objects)):
        return []
    fields = [f for f in spec.anchor_fields if f in props]
    instances = sum(counts.get(o, 1) for o in objects)
    out: list[Schema] = []
    for chosen in permutations(fields, len(anchors)):
        between = relation == "row" and "along" in chosen \
            and counts.get(anchors[chosen.index("along")], 1) == 2
        if relation in GROUP_RELATIONS - {"stack"} and instances < 2 \
                and not (relation == "row" and "on" in chosen) and not between:
            continue  # a row of one is no row, but for the top of a pyramid (on others)
            # or one object between two regions (a row from one to the other)
        new = dict(props)
        new["objects"] = tuple_schema([{"const": o} for o in objects])
        ok = True
        for field, anchor in zip(chosen, anchors, strict=True):
            if anchor in objects or anchor not in names_of(props[field]):
                ok = False
                break
            new[field] = {"const": anchor}
        for field in (f for f in fields if f not in chosen):
            free = without_names(props[field], set(objects))
            if free is None:
                ok = False
                break
            new[field] = free
        if ok and relation == "stack" and instances < 2:
            base = without_names(new["base"], set()) if "base" in new else None
            if base is None or (nullable(base) and not names_of(base)):
                ok = False  # a stack of one needs its base
            elif nullable(base):
                new["base"] = {"type": "string", "enum": names_of(base)}
        if ok and relation == "aligned" and "reference" in new:
            # Each object is aligned with an instance of its own (the model's rule).
            refs = [n for n in names_of(new["reference"]) if counts.get(n, 1) >= instances]
            ok = bool(refs)
            if ok and "const" not in new["reference"]:
                new["reference"] = {"type": "string", "enum": refs}
        if ok:
            variant = {**branch, "properties": new}
            if variant not in out:
                out.append(variant)
    return out


def _goal(branches: Iterable[Schema], uses: Sequence[tuple[Sequence[str], Sequence[str]]],
          counts: dict[str, int]) -> Schema | None:
    """``{"goal": ...}`` over every branch's variants pinned to one of ``uses``
    (objects, anchors) (None: none)."""
    variants: list[Schema] = []
    for branch in branches:
        for objects, anchors in uses:
            variants.extend(v for v in pin(branch, objects, anchors, counts)
                            if v not in variants)
    if not variants:
        return None
    goal = variants[0] if len(variants) == 1 else {"anyOf": variants}
    return {"type": "object", "properties": {"goal": goal}, "required": ["goal"],
            "additionalProperties": False}


def group_shapes(branches: Sequence[Schema], movers: Sequence[str], fixed: Sequence[str],
                 counts: dict[str, int]) -> list[Schema]:
    """One goal over every movable object, anchored on every fixed one (with no
    fixed object, also all but one movable object on that one)."""
    out: list[Schema] = []
    bases: list[str | None] = [None, *(movers if not fixed else [])]
    for base in bases:
        objects = [m for m in movers if m != base]
        anchors = [*fixed, *([base] if base else [])]
        goal = _goal(branches, [(objects, anchors)], counts) if objects else None
        if goal is not None:
            out.append(tuple_schema([goal]))
    return out


def each_shapes(branches: Sequence[Schema], movers: Sequence[str], fixed: Sequence[str],
                counts: dict[str, int], paired: bool = False,
                pins: dict[str, str] | None = None) -> list[Schema]:
    """One goal per movable object, in the proposal's order, that uses it: moves it
    (anchored on any other named object, or on none), or -- where no fixed object
    is pinned to the goal -- moves another movable object onto it ("the red block
    in the zone, then on the blue block"). Every fixed object is the anchor of a
    goal of its own, that goal moving the goal's object: each way of choosing
    which, up to :data:`MAX_PATTERNS`; with ``paired`` (the words name each
    fixed object right after its own movable one: "X in A and Y in B") only the
    i-th fixed object with the i-th movable one; with ``pins`` (fixed -> movable,
    :func:`colour_pins`) each pinned fixed object only with its movable one."""
    if len(movers) < 2 or len(fixed) > len(movers):
        return []
    if paired and len(fixed) == len(movers):
        patterns = [tuple(range(len(fixed)))]
    else:
        patterns = _patterns(movers, fixed, pins or {})
        if patterns is None:
            return []
    out: list[Schema] = []
    cache: dict[tuple[int, str | None], Schema | None] = {}
    for pattern in patterns:
        anchor_at = {i: fixed[j] for j, i in enumerate(pattern)}
        items = []
        for i, mover in enumerate(movers):
            key = (i, anchor_at.get(i))
            if key not in cache:
                if i in anchor_at:
                    uses = [([mover], [anchor_at[i]])]
                else:
                    uses = [([mover], []), *(([other], [mover]) for other in movers
                                              if other != mover)]
                cache[key] = _goal(branches, uses, counts)
            items.append(cache[key])
        if all(item is not None for item in items):
            out.append(tuple_schema([i for i in items if i is not None]))
    return out


def _patterns(movers: Sequence[str], fixed: Sequence[str],
              pins: dict[str, str]) -> list[tuple[int, ...]] | None:
    """Every way to give each fixed object its own movable one (pattern[j]: the
    index of the movable object anchored on ``fixed[j]``), pinned ones kept; None
    when there are none or more than :data:`MAX_PATTERNS`."""
    at = {j: movers.index(pins[f]) for j, f in enumerate(fixed) if pins.get(f) in movers}
    free_fixed = [j for j in range(len(fixed)) if j not in at]
    free_movers = [i for i in range(len(movers)) if i not in at.values()]
    out: list[tuple[int, ...]] = []
    for chosen in permutations(free_movers, len(free_fixed)):
        pattern = dict(at) | dict(zip(free_fixed, chosen, strict=True))
        out.append(tuple(pattern[j] for j in range(len(fixed))))
        if len(out) > MAX_PATTERNS:
            return None
    return out or None


def per_anchor_shapes(branches: Sequence[Schema], movers: Sequence[str],
                      fixed: Sequence[str], counts: dict[str, int]) -> list[Schema]:
    """With one movable object and more fixed ones: one goal per fixed object,
    each moving that object (the earlier ones milestones on its way)."""
    if len(movers) != 1 or len(fixed) < 2:
        return []
    items = [_goal(branches, [(movers, [f])], counts) for f in fixed]
    if any(item is None for item in items):
        return []
    return [tuple_schema([i for i in items if i is not None])]


def covering_factors(branches: Sequence[Schema], movers: Sequence[str],
                     fixed: Sequence[str], counts: dict[str, int],
                     paired: bool = False,
                     pins: dict[str, str] | None = None,
                     group_only: bool = False) -> Schema | None:
    """The ``factors`` schema whose every answer uses every named object.

    Args:
        branches: The goal branches allowed (each an object schema, see :func:`pin`).
        movers: The movable named objects, in the proposal's order.
        fixed: The named objects that stay put (zones, bowls, pallets, ...).
        counts: Name -> count.
        paired: Whether the proposal pairs them in its order (see :func:`each_shapes`).
        pins: Fixed object -> the movable one it must anchor (:func:`colour_pins`).
        group_only: Only the group shapes (the words name one arrangement of
            every movable object: :func:`grounded.group_named`); None when there
            are none.

    Returns:
        An ``anyOf`` of tuples of ``{"goal": ...}`` (group, each, per anchor),
        or None when no shape can use every named object.
    """
    shapes = group_shapes(branches, movers, fixed, counts)
    if not group_only:
        shapes += [*each_shapes(branches, movers, fixed, counts, paired, pins),
                   *per_anchor_shapes(branches, movers, fixed, counts)]
    if not shapes:
        return None
    return shapes[0] if len(shapes) == 1 else {"anyOf": shapes}


def must_use(goal: Schema, obj: str, unused: Sequence[str], remaining: int,
             counts: dict[str, int], movable: Sequence[str]) -> Schema | None:
    """One subtask's goal narrowed so that the subtasks left can still use every
    named object (subtasks-first: each subtask writes its goal on its own).

    Each subtask's goal must use its own object ``obj``. Where the named objects
    no goal uses yet (``unused``: neither an earlier goal's nor a later
    subtask's own object) are as many as the subtasks left (``remaining``, this
    one included) or more, this goal must use one of them too -- moved beside
    ``obj``, moved onto ``obj``, or as ``obj``'s anchor; the last subtask must
    use all of them.

    Args:
        goal: The goal's schema (branches as :func:`pin` reads them).
        obj: The subtask's object.
        unused: The named objects no goal uses yet.
        remaining: Subtasks left, this one included (>= 1).
        counts: Name -> count.
        movable: The movable named objects.

    Returns:
        The narrowed goal (an ``anyOf`` of pinned branches), or None where there
        is nothing to narrow (slack left) or no branch fits (the check
        afterwards reports it).
    """
    todo = [u for u in unused if u != obj]
    if not todo or len(todo) < remaining:
        return None
    uses: list[tuple[list[str], list[str]]] = []
    if remaining == 1:
        for k in range(min(2, len(todo)) + 1):
            for anchors in permutations(todo, k):
                rest = [u for u in todo if u not in anchors]
                if all(u in movable for u in rest):
                    uses.append(([obj, *rest], list(anchors)))
                    if rest:
                        uses.append((rest, [*anchors, obj]))
    else:
        for u in todo:
            uses.append(([obj], [u]))
            if u in movable:
                uses += [([obj, u], []), ([u], [obj])]
    pinned = _goal(goal.get("anyOf", [goal]), uses, counts)
    return None if pinned is None else pinned["properties"]["goal"]


def paired_in_order(movable: Sequence[bool]) -> bool:
    """Whether named objects read in this order (True: movable) pair up as the
    words say "X in A and Y in B": movable, fixed, movable, fixed, ..."""
    return len(movable) >= 4 and len(movable) % 2 == 0 and \
        all(m == (i % 2 == 0) for i, m in enumerate(movable))


def colour_pins(movers: Sequence[str], fixed: Sequence[str],
                colours: dict[str, str | None]) -> dict[str, str]:
    """Fixed object -> the movable object of its colour, for each fixed object whose
    colour exactly one movable object and no other fixed object has ("each ball in
    the zone of its colour"); the others stay free.

    Args:
        movers: The movable named objects.
        fixed: The fixed named objects.
        colours: Name -> colour (None: uncoloured).
    """
    def by(names: Sequence[str]) -> dict[str, list[str]]:
        out: dict[str, list[str]] = {}
        for n in names:
            if colours.get(n):
                out.setdefault(str(colours[n]), []).append(n)
        return out

    movers_of, fixed_of = by(movers), by(fixed)
    return {fs[0]: movers_of[c][0] for c, fs in fixed_of.items()
            if len(fs) == 1 and len(movers_of.get(c, [])) == 1}


def used_names(goal: dict[str, Any], names: Iterable[str]) -> set[str]:
    """The ``names`` a goal (JSON) uses, moved or as an anchor."""
    known = set(names)
    return {n for v in goal.values() for n in (v if isinstance(v, list) else [v])
            if isinstance(n, str) and n in known}


__all__ = [
    "GROUP_RELATIONS",
    "MAX_PATTERNS",
    "colour_pins",
    "covering_factors",
    "each_shapes",
    "group_shapes",
    "must_use",
    "names_of",
    "nullable",
    "paired_in_order",
    "per_anchor_shapes",
    "pin",
    "tuple_schema",
    "used_names",
]
