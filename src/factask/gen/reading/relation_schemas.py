"""A grounded goal's JSON Schema, one relation type at a time.

Each relation's goal schema (:func:`factask.gen.answers.step_schemas.relation_schema`)
narrowed to the objects a proposal names: the movers an enum of the movable named
objects (or only those of the kinds the relation moves: a pile, a rope), the anchors an
enum of the named objects that can carry them, an aligned goal's modes those its
references allow, and, where the words allow one goal per anchor, a branch per anchor.
:mod:`factask.gen.reading.grounded` builds whole answers from these.
"""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from factask.gen.answers import step_schemas as ss
from factask.gen.reading.cover import GROUP_RELATIONS, names_of
from factask.relations import RELATION_TYPES
from factask.relations.aligned import modes_for
from factask.vocabulary.kinds import kind_spec

Schema = ss.Schema


#: Relation types a grounded goal leaves out: their fields are coordinates, which
#: the library computes (the system prompt says so) and a tiny model invents.
COORDINATE_RELATIONS = frozenset(["at_pose"])

#: Relation types that move only variables of these kinds (the others never move
#: them): each relation's own :attr:`~factask.relations.base.RelationBase.moves_kinds`.
OBJECT_KINDS: dict[str, frozenset[str]] = {
    kind: cls.moves_kinds for kind, cls in RELATION_TYPES.items() if cls.moves_kinds is not None}

SPECIAL_KINDS = frozenset().union(*OBJECT_KINDS.values())


def _without(field: Schema, name: str) -> Schema | None:
    """An anchor field's schema without ``name`` (None: nothing left, not nullable)."""
    if "enum" in field:
        kept = [n for n in field["enum"] if n != name]
        return {**field, "enum": kept} if kept else None
    if "anyOf" not in field:
        return field  # null only
    options = [o for o in (_without(o, name) if "enum" in o else o
                           for o in field.get("anyOf", [])) if o is not None]
    if not options:
        return None
    return options[0] if len(options) == 1 else {"anyOf": options}


def relation_over(relation: str, kinds: dict[str, str],
                  counts: dict[str, int] | None = None,
                  moved: Collection[str] = ()) -> Schema | None:
    """One relation's goal over the named objects, or None if none can fill it.

    ``objects`` lists only the variables the relation can move (piles for
    ``pile_in_zone``, ropes for ``rope_along``, any other movable kind for the
    rest); with a single such variable, no anchor field may name it (an object
    on itself). With ``counts`` (name -> count) and fewer than two objects to
    move, a row or circle is left out and a stack needs its base.
    """
    wanted = OBJECT_KINDS.get(relation)
    # A relation that moves only its own kinds moves them fixed or not (a drawer slides
    # in its cabinet); any other moves what is free.
    movers = [n for n, k in kinds.items() if ((k in wanted) if wanted else (
        (kind_spec(k).movable or n in moved) and k not in SPECIAL_KINDS))]
    schema = ss.relation_schema(relation, kinds, moved) if movers else None
    if schema is None:
        return None
    props = schema["properties"]
    props["objects"] = ss.array(ss.name(movers), 1, len(movers))
    if relation == "aligned" and "mode" in props:
        _narrow_modes(props, kinds)
    if relation in GROUP_RELATIONS and counts is not None:
        if sum(counts.get(n, 1) for n in movers) < 2:
            if relation == "row" and "along" in props:
                # One object between two regions ("between the two grey zones"): a
                # row from one to the other, along a pair and on nothing.
                pairs = [n for n in names_of(props["along"]) if counts.get(n, 1) == 2]
                if not pairs:
                    return None
                props["along"] = {"type": "string", "enum": pairs}
                if "on" in props:
                    props["on"] = {"type": "null"}
                return schema
            if relation != "stack" or "base" not in props:
                return None
            base = [o for o in props["base"].get("anyOf", [props["base"]]) if "enum" in o]
            if not base:
                return None
            props["base"] = base[0]
        elif relation != "stack" and all(counts.get(n, 1) < 2 for n in movers):
            props["objects"]["minItems"] = 2  # a row of one single object is no row
    if len(movers) == 1:
        for field in RELATION_TYPES[relation].anchor_fields:
            if field in props:
                narrowed = _without(props[field], movers[0])
                if narrowed is None:
                    return None
                props[field] = narrowed
        return schema
    return split_by_anchor(schema, relation, movers)


def _narrow_modes(props: Schema, kinds: dict[str, str]) -> None:
    """An ``aligned`` goal's modes: those its possible references take
    (:func:`~factask.relations.aligned.modes_for`: a holed box only ``hole``)."""
    ref = props.get("reference", {})
    names = [o.get("const") for o in ref.get("anyOf", [ref]) if "const" in o]
    names += [n for o in ref.get("anyOf", [ref]) for n in o.get("enum", [])]
    modes = list(dict.fromkeys(m for n in names if n in kinds for m in modes_for(kinds[n])))
    allowed = [m for m in modes if m in props["mode"].get("enum", [])]  # the kind's first
    if allowed:
        props["mode"] = {"type": "string", "enum": allowed}


def narrow_all_modes(schema: Any, kinds: dict[str, str]) -> None:
    """:func:`_narrow_modes` on every ``aligned`` goal inside ``schema`` (once the
    covering shapes have fixed each goal's reference)."""
    if isinstance(schema, list):
        for item in schema:
            narrow_all_modes(item, kinds)
    elif isinstance(schema, dict):
        props = schema.get("properties", {})
        if props.get("type", {}).get("const") == "aligned" and "mode" in props:
            _narrow_modes(props, kinds)
        for value in schema.values():
            narrow_all_modes(value, kinds)


def split_by_anchor(schema: Schema, relation: str, movers: list[str]) -> Schema | None:
    """The relation as one branch per value of its first anchor that could also be
    moved, that anchor written first and ``objects`` listing the others -- so
    an object is never its own anchor ("the red block on the red block").
    Unchanged when no anchor names a movable variable."""
    props = schema["properties"]
    field = next((f for f in RELATION_TYPES[relation].anchor_fields
                  if f in props and set(names_of(props[f])) & set(movers)), None)
    if field is None:
        return schema
    objects = props["objects"]
    rest = {k: v for k, v in props.items() if k not in ("type", field, "objects")}
    branches: list[Schema] = []
    # Anchors that stay put (a pallet, a zone, a bowl) first, then none, then a movable
    # one: what a proposal's "on the platform" names; a small model tends to take the
    # first branch a grammar offers.
    anchors = sorted(names_of(props[field]), key=lambda a: a in movers)
    for anchor in (a for a in anchors if a not in movers):
        branches.append(ss.obj({"type": props["type"], field: {"const": anchor},
                                "objects": objects, **rest}))
    if any(o.get("type") == "null" for o in props[field].get("anyOf", [])):
        branches.append(ss.obj({"type": props["type"], field: {"type": "null"},
                                "objects": objects, **rest}))
    for anchor in (a for a in anchors if a in movers):
        others = [m for m in movers if m != anchor]
        if len(others) < objects.get("minItems", 1):
            continue
        branches.append(ss.obj({"type": props["type"], field: {"const": anchor},
                                "objects": ss.array(ss.name(others),
                                                    objects.get("minItems", 1), len(others)),
                                **rest}))
    if not branches:
        return None
    return branches[0] if len(branches) == 1 else {"anyOf": branches}
