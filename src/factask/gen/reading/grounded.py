"""Step schemas grounded in the objects the proposal names.

A grammar-constrained tiny model writes whatever the grammar leaves open, and
left open it loops (the same variable until the token cap) or copies the
examples' objects. When the proposal names objects (:func:`factask.gen.reading.mentions.mentions`:
"the yellow cylinder", "three red blocks"), what it names is not the model's to
choose, so the schemas here fix it:

* the **variables** the proposal names come first, each with its name, kind,
  colour and count as constants and its size ``null`` (the kind's default: the
  proposal gives none); the model writes their descriptions and initial
  placements (``table``, or ``on`` / ``inside`` a named variable whose kind can
  carry it) and may add at most :data:`MAX_EXTRA` objects of its own (an
  ``anyOf`` of tuples, one per number of extra objects: llama.cpp's grammar
  takes ``prefixItems`` but not ``prefixItems`` followed by ``items``);
* a **whole graph** (one-shot) has exactly the named objects, and at most one
  factor per movable one (a goal moves something), its goal's names an enum of
  them; ``after`` is empty when there can be only one factor;
* a **subtask plan** has at most one subtask per movable variable.

The answer stays data checked against the schema, by pydantic and by the
ladder; a proposal that names no movable object gets the ungrounded schemas of
:mod:`factask.gen.answers.step_schemas`.

Each relation's goal schema over the named objects is built in
:mod:`factask.gen.reading.relation_schemas`; whole answers are built here.
"""

from __future__ import annotations

import copy
import re
from collections.abc import Collection, Sequence
from functools import lru_cache
from itertools import product
from typing import Any

import networkx as nx
from pydantic import ValidationError

from factask.gen.answers import step_schemas as ss
from factask.gen.answers.examples import library_task_examples, render_examples
from factask.gen.reading.articulated import HOST_KINDS
from factask.gen.reading.bases import base_order
from factask.gen.reading.capacity import prune
from factask.gen.reading.clauses import read_goals
from factask.gen.reading.cover import (
    GROUP_RELATIONS,
    colour_pins,
    covering_factors,
    paired_in_order,
)
from factask.gen.reading.mentions import Mention, colour_matched, mentions, unnamed_colour
from factask.gen.reading.parts import still_parts
from factask.gen.reading.relation_schemas import (
    COORDINATE_RELATIONS,
    OBJECT_KINDS,
    SPECIAL_KINDS,
    narrow_all_modes,
    relation_over,
)
from factask.gen.reading.stated_goals import (
    after_lists,
    defaults_first,
    fit_sizes,
    matches,
    stated_factors,
)
from factask.graph.factors import SubtaskFactor
from factask.graph.order import dependency_graph, in_listed_order
from factask.graph.taskgraph import TaskGraph
from factask.relations import RELATION_TYPES
from factask.relations.aligned import ALIGNING_KINDS
from factask.vocabulary.errors import FactaskError, InvalidValueError
from factask.vocabulary.kinds import ASSET_KINDS, kind_spec
from factask.vocabulary.names import slugify
from factask.vocabulary.palette import COLOR_NAMES
from factask.vocabulary.variables import StateVariable

Schema = ss.Schema

#: Most objects a model may add to those the proposal names.
MAX_EXTRA = 2
#: Longest description in a grounded answer (a tiny model pads free text).
GROUNDED_TEXT = 60


def _placement(own: str, kinds: dict[str, str], moved: Collection[str] = ()) -> Schema:
    """``table``, or ``on`` a support / ``inside`` a receptacle among ``kinds``
    (only ``table`` for an object that stays fixed: a zone, a bowl not ``moved``)."""
    if own and not kind_spec(kinds[own]).movable and own not in moved:
        return ss.obj({"type": {"const": "table"}})
    supports = [n for n, k in kinds.items() if n != own and kind_spec(k).support]
    receptacles = [n for n, k in kinds.items() if n != own and kind_spec(k).receptacle]
    options: list[Schema] = [ss.obj({"type": {"const": "table"}})]
    if supports:
        options.append(ss.obj({"type": {"const": "on"}, "support": ss.name(supports)}))
    if receptacles:
        options.append(ss.obj({"type": {"const": "inside"},
                               "container": ss.name(receptacles)}))
    return options[0] if len(options) == 1 else {"anyOf": options}


def mention_variable(mention: Mention, kinds: dict[str, str]) -> Schema:
    """One named object as a variable: name, kind, colour, count and size fixed.

    Args:
        mention: The object the proposal names.
        kinds: Every named object's name -> kind (where it may start).

    Returns:
        The variable's schema (the model writes ``description`` and ``initial``).
    """
    color: Schema = {"const": mention.color} if mention.color else \
        {"type": "string", "enum": list(COLOR_NAMES)}
    # A drawer's start and size, and its cabinet's size, follow from the words
    # (factask.gen.reading.parts): constants.
    seated = bool(mention.start) or mention.kind in HOST_KINDS
    return ss.obj({
        "name": {"const": mention.name},
        "description": ss.text(GROUNDED_TEXT),
        "kind": {"const": mention.kind},
        "size": {"const": list(mention.size)} if seated and mention.size else {"type": "null"},
        "color": color,
        "count": {"const": mention.count},
        "initial": ss.obj({k: {"const": v} for k, v in mention.start}) if mention.start
        else _placement(mention.name, kinds, _moved([mention])),
        **({"fixed": {"const": False}} if mention.moved else {}),
    })


def _extra_variable(kinds: dict[str, str]) -> Schema:
    """An object the model adds: free name, kind, colour; size null; count 1..4."""
    return ss.obj({
        "name": ss.name(),
        "description": ss.text(GROUNDED_TEXT),
        "kind": {"type": "string", "enum": list(ASSET_KINDS)},
        "size": {"type": "null"},
        "color": {"type": "string", "enum": list(COLOR_NAMES)},
        "count": {"type": "integer", "enum": [1, 2, 3, 4]},
        "initial": _placement("", kinds) if kinds else ss.placement_schema([]),
    })


def movable(found: Sequence[Mention]) -> list[Mention]:
    """The named objects the robot can move (by kind, or as the words say)."""
    return [m for m in found if m.movable]


def _goal_room(found: Sequence[Mention]) -> int:
    """Most goals over the named objects: one per movable object and per drawer (a
    drawer may be opened, then shut)."""
    return len(movable(found)) + 2 * sum(1 for m in found if m.kind in SPECIAL_KINDS
                                         and not m.movable)


def _moved(found: Sequence[Mention]) -> frozenset[str]:
    """The named objects of a kind fixed by default that the words move."""
    return frozenset(m.name for m in found if m.moved)


def applies(found: Sequence[Mention]) -> bool:
    """Whether grounding applies: the proposal names at least one movable object
    and some goal relation can be written over the named objects alone ("put the
    block in the hole" names one block and nothing a relation can anchor on)."""
    kinds = {m.name: m.kind for m in found}
    acted = any(m.kind in SPECIAL_KINDS for m in found)  # a drawer to open or close
    return bool(movable(found) or acted) and _goal(kinds, None, {m.name: m.count for m in found},
                                          _moved(found)) is not None


def grounded_variables(found: Sequence[Mention], extra: int = MAX_EXTRA) -> Schema:
    """The variables array: the named objects first, then at most ``extra`` others.

    Args:
        found: The proposal's mentions (non-empty).
        extra: Most objects the model may add.

    Returns:
        An array schema (an ``anyOf`` of tuples when ``extra`` > 0).
    """
    kinds = {m.name: m.kind for m in found}
    fixed = [mention_variable(m, kinds) for m in found]
    room = max(0, min(extra, ss.STEP_MAX_VARIABLES - len(fixed)))
    tuples: list[Schema] = []
    for k in range(room + 1):
        items = fixed + [_extra_variable(kinds)] * k
        tuples.append({"type": "array", "prefixItems": items, "items": False,
                       "minItems": len(items), "maxItems": len(items)})
    return tuples[0] if len(tuples) == 1 else {"anyOf": tuples}


def variables_answer(found: Sequence[Mention], extra: int = MAX_EXTRA) -> Schema:
    """Approach 1, step 1, grounded: ``{"variables": [...]}``."""
    return ss.obj({"variables": grounded_variables(found, extra)})


def graph_schema(task_name: str, found: Sequence[Mention]) -> Schema:
    """A whole graph over exactly the named objects (one-shot).

    Args:
        task_name: The task's name (a constant).
        found: The proposal's mentions (with a movable one: :func:`applies`).

    Returns:
        The graph's schema: at most one factor per movable named object.
    """
    kinds = {m.name: m.kind for m in found}
    most = max(1, min(_goal_room(found), ss.STEP_MAX_FACTORS))
    factor = ss.factor_schema(None, kinds)
    factor["properties"]["description"] = ss.text(GROUNDED_TEXT)
    factor["properties"]["initial_setup"] = ss.text(GROUNDED_TEXT)
    factor["properties"]["after"] = ss.array(ss.name(), 0, most - 1)
    return ss.obj({
        "name": {"const": task_name},
        "description": ss.text(GROUNDED_TEXT),
        "variables": grounded_variables(found, extra=0),
        "factors": ss.array(factor, 1, most),
    })


#: Words of a proposal that name a relation (singular; a plural ``s`` is read too).
RELATION_WORDS: dict[str, frozenset[str]] = {
    "in_zone": frozenset(["zone", "area", "region", "target", "pad", "mat"]),
    "on": frozenset(["on", "onto", "top", "atop"]),
    "inside": frozenset(["inside", "into", "bowl", "container", "bin", "tray", "cup",
                         "basket", "bucket", "dish", "pot"]),
    "stack": frozenset(["stack", "tower", "pyramid", "column"]),
    "row": frozenset(["row", "line", "lined"]),
    "circle": frozenset(["circle", "ring", "around", "circular"]),
    "aligned": frozenset(["align", "aligned", "corner", "insert", "inserted", "insertion",
                          "fixture", "hole", "slot", "socket", "fit"]),
    "pile_in_zone": frozenset(["pile", "sweep", "push"]),
    "rope_along": frozenset(["rope"]),
}


def named_relations(proposal: str) -> set[str]:
    """The relation types whose words the proposal uses ("in a row" -> ``row``)."""
    words = {w[:-1] if len(w) > 3 and w.endswith("s") else w
             for w in re.findall(r"[a-z]+", proposal.lower())}
    return {r for r, ws in RELATION_WORDS.items() if words & ws}


#: Nouns naming one arrangement of several objects ("a tower of ...", "in a row"),
#: among the :data:`RELATION_WORDS` of the group relations (not the verb "stack":
#: "stack the blue block on the red one" may be two goals).
GROUP_WORDS = frozenset(["tower", "pyramid", "column", "row", "line", "circle", "ring"])
#: Where a proposal's words pass from one part of the task to the next.
_PARTS = re.compile(r"[.;!?]|,?\s+(?:then|and then|after that|afterwards|next)\s+")


def group_named(proposal: str, found: Sequence[Mention]) -> bool:
    """Whether one part of the proposal (a sentence; "..., then ...") names a group
    arrangement (:data:`GROUP_WORDS`: a tower, a pyramid, a row, a line, a circle)
    and every movable named object: "build a tower of a blue, a red and a green
    block" is one stack of the three, not a goal per block.

    Args:
        proposal: The proposal.
        found: Its mentions (:func:`factask.gen.reading.mentions.mentions`).

    Returns:
        True when such a part exists (the caller offers only the group shapes).
    """
    movers = {m.name for m in movable(found)}
    if len(movers) < 2:
        return False
    for part in _PARTS.split(proposal.lower()):
        words = {w[:-1] if len(w) > 3 and w.endswith("s") else w
                 for w in re.findall(r"[a-z]+", part)}
        if words & GROUP_WORDS and movers <= {m.name for m in mentions(part)}:
            return True
    return False


def _goal(kinds: dict[str, str], wanted: set[str] | None = None,
          counts: dict[str, int] | None = None, moved: Collection[str] = ()) -> Schema | None:
    """The goal's schema over ``kinds``: the ``wanted`` relations that fit, else every
    one that fits; None when none does (an empty ``anyOf`` is no schema: llama.cpp's
    grammar parser fails on it and its server goes down)."""
    options = {r: s for r in RELATION_TYPES if r not in COORDINATE_RELATIONS
               and (s := relation_over(r, kinds, counts, moved)) is not None}
    named = {r: s for r, s in options.items() if r in (wanted or ())}
    # An arrangement the proposal names (a stack, a row, a circle) is its task; "on"
    # or "into" beside it say where: the arrangement's branches come first.
    # Into a fixture, a corner marker or a kit, the words mean alignment: those
    # branches before "inside" / "on" where such an object is named.
    aligning = bool(ALIGNING_KINDS & set(kinds.values()))
    order = sorted(named or options, key=lambda r: (r not in GROUP_RELATIONS,
                                                    not (aligning and r == "aligned")))
    chosen = [b for r in order for b in (named or options)[r].get("anyOf", [(named or options)[r]])
              if "properties" in b]
    if not chosen:
        return None
    return chosen[0] if len(chosen) == 1 else {"anyOf": chosen}


def goal_answer(variables: Sequence[StateVariable], text: str) -> Schema:
    """Approach 1, step 3, grounded: one subtask's goal over its variables.

    Args:
        variables: The subtask's planned variables.
        text: The proposal and the subtask's description: the relations their
            words name are the only goal types allowed (when any is named and fits).

    Returns:
        ``{"goal": ..., "description": ...}`` with the goal as in
        :func:`compact_graph_schema` (no coordinates, no object its own anchor,
        no group of one); the ungrounded goal schema when no such relation fits
        (a lone block: only coordinates can place it).
    """
    kinds = {v.name: v.kind for v in variables}
    counts = {v.name: v.count for v in variables}
    moved = {v.name for v in variables if not v.is_fixed and not kind_spec(v.kind).movable}
    goal = _goal(kinds, named_relations(text), counts, moved)
    if goal is None:
        return ss.goal_answer(kinds)
    return ss.obj({"goal": goal, "description": ss.text(GROUNDED_TEXT)})


def goal_problems(goals: Sequence[dict[str, Any]], found: Sequence[Mention],
                  still: Collection[str] = ()) -> list[str]:
    """What makes a grounded graph's goals another (or no) task: a named object no
    goal uses (but those the words keep still), a row, circle or stack of fewer
    than two objects (but a row of one between a pair or on a layer below).

    Args:
        goals: The answer's goals (JSON).
        found: The proposal's mentions.
        still: The named objects the words keep where they are
            (:func:`factask.gen.reading.clauses.still_objects`).

    Returns:
        One line per problem (empty: none).
    """
    counts = {m.name: m.count for m in found}
    still = {*still, *still_parts(found)}  # a cabinet and drawers no goal names: furniture
    used: set[str] = set()
    out: list[str] = []
    for i, goal in enumerate(goals):
        names = [n for v in goal.values() for n in (v if isinstance(v, list) else [v])
                 if isinstance(n, str) and n in counts]
        used.update(names)
        kind = goal.get("type")
        objects = [n for n in goal.get("objects", []) if n in counts]
        instances = sum(counts[n] for n in objects) + (1 if goal.get("base") else 0)
        # A row of one between a pair ("between the two grey zones") or laid on the
        # layer below (a pyramid's top): a task, as the grammar admits it.
        between = kind == "row" and (counts.get(goal.get("along") or "", 0) == 2
                                     or bool(goal.get("on")))
        if kind in GROUP_RELATIONS and instances < 2 and not between:
            out.append(f"factors.{i}.goal: a {kind} of {instances} object is no task; use "
                       "the relation the proposal asks for, over the objects it names")
    for m in found:
        if m.name not in used and m.name not in still:
            out.append(f"no goal uses {m.name} ({m.describe()}), which the proposal names: "
                       "every named object belongs in a goal (moved, or as the anchor)")
    return out


def graph_mentions(found: Sequence[Mention], proposal: str) -> list[Mention]:
    """The named objects as the graph will have them: where the words state every
    goal, the anchors those goals fill grown to hold what they put there
    (:func:`factask.gen.reading.stated_goals.fit_sizes`)."""
    stated = read_goals(proposal, found) if proposal else None
    return fit_sizes(stated, found) if stated else list(found)


def stated_schema(found: Sequence[Mention], proposal: str) -> Schema | None:
    """The ``factors`` schema of the goals the words state, or None.

    Where the words state every goal (:func:`factask.gen.reading.clauses.read_goals`)
    and each can be written and laid out, the grammar is that reading: a tuple of
    one pinned goal per stated goal, the model writing only the numbers the words
    leave open (the relation's default first).

    Args:
        found: The proposal's mentions.
        proposal: The proposal.

    Returns:
        A tuple schema (``prefixItems``: one ``{"goal": ...}`` per stated goal, in
        the reading's order), or None where there is no such reading.
    """
    return copy.deepcopy(_stated_schema(tuple(found), proposal))  # callers narrow it


@lru_cache(maxsize=64)
def _stated_schema(found: tuple[Mention, ...], proposal: str) -> Schema | None:
    # Cached: the layout checks of prune() take seconds, and each approach asks twice.
    reading = read_goals(proposal, found)
    if not reading:
        return None
    kinds = {m.name: m.kind for m in found}
    factors = stated_factors(reading, kinds, {m.name: m.count for m in found}, _moved(found))
    factors = factors and prune(factors, fit_sizes(reading, found), base_order(found, proposal))
    return factors and defaults_first(factors)


def compact_graph_schema(found: Sequence[Mention], proposal: str = "",
                         cover: bool = True, stated: bool = True) -> Schema:
    """A whole graph's *decisions* only (one-shot with a grounded proposal).

    The named objects' kinds, colours, counts, sizes and descriptions come from
    the proposal (:func:`expand_graph`); the model writes where each starts and
    the factors' goals -- about 70 tokens instead of 300, which on a CPU with a
    grammar is minutes.

    Args:
        found: The proposal's mentions (with a movable one: :func:`applies`).
        proposal: The proposal: where its words name relations
            (:func:`named_relations`), the goals are of those types only.
        cover: Whether the goals must use every named object by construction
            (:func:`factask.gen.reading.cover.covering_factors`: one goal over all movable
            objects, or one per movable object, the fixed ones spread over their
            anchors; relations the words do not name only where the named ones
            cannot); a movable object then starts on the table or on or in
            another movable one, never on a fixed one (every fixed object is an
            anchor: that start could be a goal met at the start). False, or
            where no such shape exists: an array of at most one goal per
            movable object (checked by :func:`goal_problems`).
        stated: Whether goals the words state (:mod:`factask.gen.reading.clauses`)
            are the only answer where the reading accounts for every named object
            (False: the shapes above, whatever the words state).

    Returns:
        ``{"variables": [{name, initial}, ...], "factors": [{goal}, ...]}``
        with the variables a tuple of the named movable objects (a fixed one
        starts on the table: nothing to write), each starting on the table or on
        or in a fixed object or a movable one listed before it.
    """
    kinds = {m.name: m.kind for m in found}
    counts = {m.name: m.count for m in found}
    moved = _moved(found)
    goal = _goal(kinds, named_relations(proposal), counts, moved)
    if goal is None:
        raise InvalidValueError("no goal relation fits the named objects alone "
                                "(check applies() first)")
    order = base_order(found, proposal)  # goals build on earlier objects only: no cycle
    factors = stated_schema(found, proposal) if proposal and stated else None
    if cover and factors is None:
        movers = [m.name for m in movable(found)]
        fixed = [m.name for m in found if m.name not in movers]
        # "each ball in the zone of its colour": the colours pin which goes where.
        pins = colour_pins(movers, fixed, {m.name: m.color for m in found}) \
            if colour_matched(proposal) else {}
        paired = not pins and paired_in_order([m.name in movers for m in found])
        # "a tower of a blue, a red and a green block": only the one arrangement,
        # where one can use every object and be laid out.
        grouped = [True, False] if group_named(proposal, found) else [False]
        for allowed, group_only in product((goal, _goal(kinds, None, counts, moved)),
                                           grouped):
            branches = allowed.get("anyOf", [allowed]) if allowed else []
            factors = covering_factors(branches, movers, fixed, counts, paired, pins,
                                       group_only)
            factors = factors and prune(factors, found, order)  # shapes whose layouts fit
            if factors is not None:
                break
    starts = kinds
    if factors is None:
        most = max(1, min(_goal_room(found), ss.STEP_MAX_FACTORS))
        plain = ss.array(ss.obj({"goal": goal}), 1, most)
        factors = prune(plain, found, order) or plain  # goals whose layout fits only
    else:
        # Every fixed named object is some goal's anchor: an object starting on or in
        # one would start where a goal may put it (a goal met at the start).
        starts = {m.name: m.kind for m in found if m.movable}
    # Only the movable objects' starts are decisions (a fixed one is on the table),
    # each on or in a fixed object or one listed before it: no cycle of starts.
    items, before = [], {m.name: m.kind for m in found if not m.movable and m.name in starts}
    for m in found:
        if m.movable:
            start = ss.obj({k: {"const": v} for k, v in m.start}) if m.start else \
                _placement(m.name, {**before, m.name: m.kind}, moved)  # "out of the drawer"
            items.append(ss.obj({"name": {"const": m.name}, "initial": start}))
            before[m.name] = m.kind
    narrow_all_modes(factors, kinds)
    return ss.obj({
        "variables": {"type": "array", "prefixItems": items, "items": False,
                      "minItems": len(items), "maxItems": len(items)},
        "factors": factors,  # a covering shape pruned above (once: the joint checks cost)
    })


def factor_names(goals: Sequence[dict[str, Any]]) -> list[str]:
    """A name per goal, from its relation and first object (``in_zone_red_block``),
    numbered where two would be the same."""
    out: list[str] = []
    for goal in goals:
        objects = goal.get("objects") or ["objects"]
        base = slugify(f"{goal.get('type', 'goal')} {objects[0]}", "_", 48, "goal")
        name, i = base, 2
        while name in out:
            name, i = f"{base}_{i}", i + 1
        out.append(name)
    return out


def expand_graph(data: dict[str, Any], found: Sequence[Mention], task: str,
                 description: str) -> dict[str, Any]:
    """The whole graph of a :func:`compact_graph_schema` answer.

    Args:
        data: The answer (checked against the compact schema).
        found: The proposal's mentions the schema was built from.
        task: The task's name.
        description: The task's description.

    Returns:
        A task graph's data: the named objects as variables (size null: the
        kind's default), the factors with equal weights, listed in the order
        they are done (a later factor moving an object an earlier one moved goes
        after it, the earlier one a milestone: :func:`factask.graph.order.in_listed_order`).
    """
    initial = {v["name"]: v["initial"] for v in data.get("variables", [])}
    answered = list(data.get("factors", []))
    stated = read_goals(description, found)
    if stated and matches(stated, [f["goal"] for f in answered]):
        found = fit_sizes(stated, found)  # the anchors the stated goals fill, grown
    unnamed = unnamed_colour(found)
    variables = [m.as_variable(initial.get(m.name), unnamed) for m in found]
    names = factor_names([f["goal"] for f in answered])
    factors = [{"name": n, "description": f"{n.replace('_', ' ')}: {description}"[:200],
                "goal": f["goal"], "weight": 1.0 / len(answered)}
               for n, f in zip(names, answered, strict=True)]
    if stated and matches(stated, [f["goal"] for f in answered]):
        # "first ..., then ...": the words' steps are the factors' order.
        for factor, after in zip(factors, after_lists(stated, names) or [], strict=True):
            if after:
                factor["after"] = after
    try:
        listed = [SubtaskFactor.model_validate(f) for f in factors]
        if not nx.is_directed_acyclic_graph(dependency_graph(listed)):
            # The words' steps against the anchors' order ("drop the ball into the bowl,
            # then carry the bowl"): the anchors decide, the steps are dropped.
            listed = [f.model_copy(update={"after": []}) for f in listed]
        ordered = in_listed_order(listed)
        factors = [f.model_dump(mode="json", exclude_none=True) for f in ordered]
    except ValidationError:
        pass  # the syntax check reports it, naming the node and field
    return {"name": task, "description": description, "variables": variables,
            "factors": factors}


def compact_example(graph: TaskGraph) -> dict[str, Any]:
    """A task graph written as a :func:`compact_graph_schema` answer (an example)."""
    def goal(f: SubtaskFactor) -> dict[str, Any]:
        data = f.goal.model_dump(mode="json", exclude_none=True)
        return {k: v for k, v in data.items() if k not in ss.OMITTED_RELATION_FIELDS}
    return {"variables": [{"name": v.name,
                           "initial": v.initial.model_dump(mode="json", exclude_none=True)
                           if v.initial is not None else {"type": "table"}}
                          for v in graph.variables],
            "factors": [{"goal": goal(f)} for f in graph.factors]}


def compact_examples(query: str, k: int, exclude: str | None = None) -> str:
    """The ``k`` library tasks most like ``query``, as compact answers (never the
    task itself, :func:`factask.gen.answers.examples.library_task_examples`)."""
    if k <= 0:
        return "(none)"
    shown = []
    for example in library_task_examples(query, k, exclude=exclude):
        try:
            example.payload = compact_example(TaskGraph.model_validate(example.payload))
        except (ValidationError, FactaskError):
            continue  # never shown in another form than the answer's
        shown.append(example)
    return render_examples(shown)


def plan_bound(variables: Sequence[StateVariable]) -> int:
    """Most subtasks of a plan over ``variables``: one per movable variable (1..8)."""
    n = sum(1 for v in variables if not v.is_fixed or v.kind in SPECIAL_KINDS)
    return max(1, min(n, ss.STEP_MAX_SUBTASKS))


__all__ = ["COORDINATE_RELATIONS", "GROUNDED_TEXT", "GROUP_RELATIONS", "GROUP_WORDS", "MAX_EXTRA",
           "OBJECT_KINDS", "RELATION_WORDS", "applies", "compact_example", "compact_examples",
           "compact_graph_schema", "expand_graph", "factor_names", "goal_answer", "goal_problems",
           "graph_mentions", "graph_schema", "grounded_variables", "group_named",
           "mention_variable", "movable", "named_relations", "plan_bound", "relation_over",
           "stated_schema", "variables_answer"]
