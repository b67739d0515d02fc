"""The goals the words state (:mod:`factask.gen.reading.clauses`) as a grammar.

Where the clause reading accounts for every named object, what each goal moves,
where and how is the words' and not a model's to choose: the ``factors`` schema
of a one-shot answer is then one tuple, each goal pinned to its relation, its
objects (in the words' order), its anchor and its order; only the numbers the
words leave open (a row's spacing, a circle's radius) stay the model's. A goal
the relation cannot hold over these objects leaves no schema (None), and the
caller offers the shapes of :mod:`factask.gen.reading.cover` instead.

Where a stated goal puts more in a bowl, container, zone or pallet than its kind's
default size holds ("the three blue blocks in the blue bowl"), that anchor is made
larger until the layout fits (:func:`fit_sizes`): the words ask for the goal, not
for the default size.

The steps of the reading ("first ..., then ...") become the factors' ``after``
lists when the answer is expanded (:func:`after_lists`).
"""

from __future__ import annotations

import re
from collections.abc import Collection, Sequence
from dataclasses import replace
from typing import Any

from factask.gen.reading.capacity import goals_problem, layout_problem
from factask.gen.reading.clauses import ReadGoal
from factask.gen.reading.cover import nullable, pin, tuple_schema
from factask.gen.reading.mentions import Mention
from factask.gen.reading.relation_schemas import relation_over
from factask.gen.reading.selectors import placed
from factask.relations import RELATION_TYPES
from factask.relations.aligned import modes_for
from factask.vocabulary.kinds import kind_spec

Schema = dict[str, Any]


def goal_schema(goal: ReadGoal, kinds: dict[str, str], counts: dict[str, int],
                moved: Collection[str] = ()) -> Schema | None:
    """``{"goal": ...}`` pinned to what ``goal`` states, or None where the relation
    cannot hold it (an anchor field it has not, an object it cannot move).

    Args:
        goal: The goal read from the words.
        kinds: Named object -> kind.
        counts: Named object -> count.
        moved: Named objects of a fixed kind that the words move.
    """
    branches = relation_over(goal.relation, kinds, counts, moved)
    if branches is None:
        return None
    anchors = [goal.anchor] if goal.anchor else []
    fields = RELATION_TYPES[goal.relation].anchor_fields
    variants: list[Schema] = []
    for branch in branches.get("anyOf", [branches]):
        if "properties" not in branch:
            continue
        for variant in pin(branch, list(goal.objects), anchors, counts):
            props = dict(variant["properties"])
            if goal.field and goal.anchor and props.get(goal.field) != {"const": goal.anchor}:
                continue  # the anchor in another field than the words say
            unstated = [f for f in fields if f in props and "const" not in props[f]]
            if any(not nullable(props[f]) for f in unstated):
                continue  # an anchor the words do not give
            for f in unstated:
                props[f] = {"type": "null"}
            if "ordered" in props:
                props["ordered"] = {"const": goal.ordered}
            if "mode" in props and goal.anchor:
                # Into a corner marker: corner to corner; into a box's hole: the hole.
                mode = modes_for(kinds[goal.anchor])[0]
                if mode not in props["mode"].get("enum", [mode]):
                    continue
                props["mode"] = {"const": mode}
            out = {**variant, "properties": props}
            if out not in variants:
                variants.append(out)
    if not variants:
        return None
    chosen = variants[0] if len(variants) == 1 else {"anyOf": variants}
    return {"type": "object", "properties": {"goal": chosen}, "required": ["goal"],
            "additionalProperties": False}


def stated_factors(goals: Sequence[ReadGoal], kinds: dict[str, str], counts: dict[str, int],
                   moved: Collection[str] = ()) -> Schema | None:
    """The ``factors`` schema of exactly the stated goals (a tuple), or None when one
    of them cannot be written (see :func:`goal_schema`)."""
    items = [goal_schema(g, kinds, counts, moved) for g in goals]
    if not items or any(i is None for i in items):
        return None
    return tuple_schema([i for i in items if i is not None])


#: Growth of an anchor's footprint per try, and the most tries.
GROWTH = 1.25
MAX_GROWTH_STEPS = 4
#: Longest shorter side an anchor is grown to (the workspace is 0.5 m deep).
MAX_GROWN_SIDE = 0.4
#: Relations whose anchor holds the objects inside its footprint.
_HOLDING = frozenset({"inside", "in_zone", "on", "stack", "pile_in_zone"})


def fit_sizes(goals: Sequence[ReadGoal], found: Sequence[Mention]) -> list[Mention]:
    """``found`` with each fixed anchor of the stated goals made large enough (in x and
    y, by :data:`GROWTH` per try) for everything those goals put in or on it, together
    ("three red balls and the yellow ball into the green bowl": four balls).

    Args:
        goals: The stated goals.
        found: The proposal's mentions.

    Returns:
        The mentions, those grown with their ``size`` set (the others unchanged).
    """
    out = list(found)
    index = {m.name: i for i, m in enumerate(out)}
    sharing: dict[str, list[dict[str, Any]]] = {}
    for goal in goals:
        if goal.relation in _HOLDING and goal.anchor in index:
            sharing.setdefault(goal.anchor, []).append(
                {"type": goal.relation, "objects": list(goal.objects),
                 _anchor_field(goal.relation): goal.anchor})
    for name, data in sharing.items():
        k = index[name]
        anchor = out[k]
        if anchor.movable or not kind_spec(anchor.kind).region:
            continue
        checks = [data]
        if len({d["type"] for d in data}) == 1:
            # Goals of one relation on one anchor hold all their objects at once: laid
            # out as one goal (the joint search may run out of time, which proves nothing)
            # -- and then as the goals the graph will have, one after the other: "put
            # the red block into the container, then the blue one, ..." places each
            # block where the ones before left room, which needs more than one packing
            # ("no free spot"). The joint search's answer is the one the grammar's
            # check (:func:`factask.gen.reading.capacity.prune`) finds again (cached),
            # so the reading does not hang on whether the search ran out of time.
            checks = [[{**data[0], "objects": [o for d in data for o in d["objects"]]}]] \
                + ([data] if len(data) > 1 else [])
        sx, sy, sz = anchor.size or kind_spec(anchor.kind).default_size
        for _ in range(MAX_GROWTH_STEPS + 1):
            problem = next((p for goals in checks
                            if (p := layout_problem(goals[0], out) if len(goals) == 1
                                else goals_problem(goals, out)) is not None), None)
            if problem is None:
                break
            if not _ROOM.search(problem) or min(sx, sy) * GROWTH > MAX_GROWN_SIDE:
                out[k] = anchor  # another problem, or no size on the table fits
                break
            sx, sy = round(sx * GROWTH, 3), round(sy * GROWTH, 3)
            out[k] = replace(anchor, size=(sx, sy, sz))
        else:
            out[k] = anchor  # no size fits: the default, and the check says why
    return placed(out)  # a grown member of a placed row: the row spaced again


#: The layout problems that more room on the anchor solves.
_ROOM = re.compile(r"do not fit|no free spot|collides")


def _anchor_field(relation: str) -> str:
    return next(iter(RELATION_TYPES[relation].anchor_fields))


def defaults_first(factors: Schema) -> Schema:
    """``factors`` (a tuple of pinned goals) with each number the words leave open
    offering the relation's default (``null``: sized to the objects, a circle's radius
    to how many they are) before the listed lengths -- the first choice of a grammar
    is the default, not the smallest length."""
    for item in factors.get("prefixItems", []):
        goal = item.get("properties", {}).get("goal", {})
        for branch in goal.get("anyOf", [goal]):
            props = branch.get("properties", {})
            relation = props.get("type", {}).get("const")
            anchors = RELATION_TYPES[relation].anchor_fields if relation in RELATION_TYPES \
                else {}
            for name, value in props.items():
                options = value.get("anyOf", []) if isinstance(value, dict) else []
                if name not in anchors and any(o.get("type") == "null" for o in options):
                    props[name] = {"anyOf": sorted(options,
                                                   key=lambda o: o.get("type") != "null")}
    return factors


def after_lists(goals: Sequence[ReadGoal], names: Sequence[str]) -> list[list[str]] | None:
    """Each factor's ``after``: the factors of the steps before its own.

    Args:
        goals: The stated goals, in the answer's order.
        names: The factors' names, one per goal.

    Returns:
        One list per goal (None when the lengths differ).
    """
    if len(goals) != len(names):
        return None
    return [[n for g2, n in zip(goals, names, strict=True) if g2.step < g.step]
            for g in goals]


def matches(goals: Sequence[ReadGoal], answered: Sequence[dict[str, Any]]) -> bool:
    """Whether an answer's goals (JSON) are the stated ones, in order (type, objects)."""
    return len(goals) == len(answered) and all(
        a.get("type") == g.relation and list(a.get("objects", [])) == list(g.objects)
        for g, a in zip(goals, answered, strict=True))


__all__ = ["after_lists", "defaults_first", "fit_sizes", "goal_schema", "matches", "stated_factors"]
