"""Does a generated graph mean the reference task? A meaning metric on factor graphs.

Completion says the oracle can solve *a* task; this module says whether it is the task
asked for, by comparing the generated graph with a reference graph (for the 192-list
descriptions: the library's own graph of that task).

Both graphs are first put in a **canonical form**, so that two ways of writing one task
compare equal:

* every variable becomes one node per object instance (``three red blocks`` as one
  variable of count 3 or as three variables of count 1 are the same objects), labelled
  by kind, colour and fixed-ness;
* a relation that holds object by object (``in_zone``, ``inside``, ``on`` without
  per-object poses) becomes one factor per object it moves: "put the red and the blue
  block in the zone" is the same task as one goal each;
* a factor is labelled by its relation type, whether it is a milestone, and its
  categorical parameters (``ordered``, an aligned goal's ``mode``, a rope's ``side``
  ...); an order over objects that no label tells apart (a tower of three red
  blocks) is no order; each edge to an object names the role it plays (``objects`` with its position
  when the relation orders them, or the anchor field: ``support``, ``zone``, ``base``
  ...);
* names, descriptions, weights, tolerances and numeric parameters (spacing, radius,
  target coordinates) are left out: words rarely fix them, and they do not change
  which task it is (they are listed as details, not counted).

**Colours the words leave open.** Given the proposal's words
(:func:`colours_named`), a colour they do not name is no part of the task: "put a
block in the green bowl" is met by a block of any colour, whatever colour the
reference happened to give it. Every such colour, in both graphs, is compared as
"unspecified"; the colours the words name are compared as they are.

**Sizes the words contrast.** Where the words tell objects apart by size ("the small
ball in the small bowl and the large ball in the large bowl", :func:`sizes_named`),
each object is labelled too with its size among the objects of its kind and colour
(smaller / larger by volume, :data:`GRADE_RATIO`): a graph that puts the large ball
in the small bowl, or has two balls of one size, is another task. Without such words
sizes are details.

**Drawers by their place.** A drawer (a variable that starts ``in_cabinet``) is
labelled too with its level among its cabinet's drawers and how it starts (shut,
partly open, open): opening the top drawer is not opening the bottom one.

The graphs are **equivalent** when their canonical forms are isomorphic (networkx's
``DiGraphMatcher`` with node and edge matches) under a mapping that keeps every order
of the reference (A before B, explicit or implied by anchors, transitively) — order is
only asked where the reference orders. Beside that yes / no, partial scores say how
close a graph came: **object F1** (the instances' multisets), **relation F1** (the
canonical factors' signatures: type, milestone, parameters and the labels of the objects
in each role) and **order agreement** (the share of the reference's ordered pairs the
generated graph keeps). :attr:`Comparison.differences` says in words what differs.
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import networkx as nx
import numpy as np
from networkx.algorithms.isomorphism import DiGraphMatcher

from factask.gen.reading.articulated import PART_KINDS
from factask.gen.reading.words import GRADE_WORDS
from factask.graph.taskgraph import TaskGraph, parse_graph
from factask.vocabulary.palette import colour_of_word

#: Relations that hold object by object: a goal over several objects is one per object.
PER_OBJECT_RELATIONS = frozenset(["in_zone", "inside", "on"])
#: Goal fields that never carry meaning of their own (names are compared through roles).
_NOT_PARAMETERS = frozenset(["type", "objects", "tolerances"])
#: Most isomorphisms tried for one that keeps the reference's order (graphs of many
#: identical objects have factorially many; the first ones differ only in those).
MAX_MAPPINGS = 2000

InstanceLabel = tuple[str, str, bool, str]  # kind, colour ("" for none), fixed, grade ("")
#: Two sizes differ when their volumes differ by more than this factor.
GRADE_RATIO = 1.1


@dataclass(frozen=True)
class Comparison:
    """How a generated graph compares with a reference graph.

    Attributes:
        equivalent: The same task (canonical forms isomorphic, the reference's order kept).
        object_f1: F1 of the object instances (kind, colour, fixed), 0..1.
        relation_f1: F1 of the canonical factors' signatures, 0..1.
        order_agreement: Share of the reference's ordered factor pairs kept, 0..1
            (1 when the reference orders nothing).
        differences: What differs, in words (empty when equivalent).
        details: Differences that do not count (numeric parameters), in words.
    """

    equivalent: bool
    object_f1: float
    relation_f1: float
    order_agreement: float
    differences: list[str] = field(default_factory=list)
    details: list[str] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict (rates rounded to 4 places)."""
        return {"equivalent": self.equivalent, "object_f1": round(self.object_f1, 4),
                "relation_f1": round(self.relation_f1, 4),
                "order_agreement": round(self.order_agreement, 4),
                "differences": list(self.differences), "details": list(self.details)}


# ------------------------------------------------------------ canonical form
@dataclass(frozen=True)
class _Factor:
    """One canonical factor: its label, its roles (role -> instance nodes), its origin."""

    origin: str
    label: tuple[Any, ...]
    roles: tuple[tuple[str, str], ...]  # (role, instance node), in role order
    numbers: tuple[tuple[str, Any], ...]  # numeric parameters (details)


@dataclass
class _Canon:
    graph: nx.DiGraph
    instances: dict[str, InstanceLabel]
    factors: dict[str, _Factor]
    before: set[tuple[str, str]]  # (a, b): canonical factor a comes before b


def _colour(value: Any) -> str:
    return str(value or "").strip().lower()


def colours_named(text: str) -> frozenset[str]:
    """The palette colours ``text`` names (``grey`` read as ``gray``)."""
    named = (colour_of_word(w) for w in re.findall(r"[a-z]+", text.lower()))
    return frozenset(c for c in named if c is not None)


def sizes_named(text: str) -> bool:
    """Whether ``text`` tells objects apart by size ("the small ball", "the tall one")."""
    return any(w in GRADE_WORDS for w in re.findall(r"[a-z]+", text.lower()))


def _grades(graph: TaskGraph, colour_of: dict[str, str]) -> dict[str, str]:
    """Variable -> its size among the variables of its kind and colour that differ in
    size ("smaller" / "larger", or "size 2 of 3"); alike ones of one size get none."""
    volume = {v.name: float(np.prod(v.extents)) for v in graph.variables}
    groups: dict[tuple[str, str], list[str]] = {}
    for v in graph.variables:
        groups.setdefault((v.kind, colour_of[v.name]), []).append(v.name)
    out: dict[str, str] = {}
    for names in groups.values():
        levels: list[float] = []
        for vol in sorted(volume[n] for n in names):
            if not levels or vol > levels[-1] * GRADE_RATIO:
                levels.append(vol)
        if len(levels) < 2:
            continue
        for n in names:
            rank = max(k for k, level in enumerate(levels) if volume[n] >= level)
            out[n] = ("smaller", "larger")[rank] if len(levels) == 2 \
                else f"size {rank + 1} of {len(levels)}"
    return out


def _instances(graph: TaskGraph, stated: frozenset[str] | None = None, graded: bool = False,
               ) -> tuple[dict[str, InstanceLabel], dict[str, list[str]]]:
    labels: dict[str, InstanceLabel] = {}
    of: dict[str, list[str]] = {}
    colour_of = {}
    for v in graph.variables:
        colour = _colour(v.color)
        if stated is not None and colour not in stated:
            colour = ""  # the words leave it open
        colour_of[v.name] = colour
    grades = _grades(graph, colour_of) if graded else {}
    seats = _seats(graph)
    for v in graph.variables:
        grade = ", ".join(x for x in (grades.get(v.name, ""), seats.get(v.name, "")) if x)
        label = (v.kind, colour_of[v.name], bool(v.is_fixed), grade)
        of[v.name] = list(v.instances)
        for inst in v.instances:
            labels[inst] = label
    return labels, of


def _seats(graph: TaskGraph) -> dict[str, str]:
    """Articulated part -> its place in its host and how it starts ("level 3 of 3,
    open", "level 1 of 1, on"), read from the part's start type in
    :data:`~factask.gen.reading.articulated.PART_KINDS`: the top drawer is not the
    bottom one, nor an open drawer a shut one, nor a switch on one off."""
    seats: dict[str, tuple[str, int, float, bool]] = {}
    for v in graph.variables:
        spec = PART_KINDS.get(v.kind)
        seat = spec.seat_of(v.initial.model_dump()) if spec and v.initial is not None else None
        if spec is not None and seat is not None:
            seats[v.name] = (*seat, spec.binary)
    counts = Counter(host for host, _, _, _ in seats.values())
    out: dict[str, str] = {}
    for name, (host, level, o, binary) in seats.items():
        state = ("on" if o else "off") if binary else \
            "shut" if o == 0 else "open" if o >= 1 else "partly open"
        out[name] = f"level {level + 1} of {counts[host]}, {state}"
    return out


def _parameters(goal: Any) -> tuple[tuple[tuple[str, Any], ...], tuple[tuple[str, Any], ...]]:
    """A goal's categorical parameters (meaning) and numeric ones (details)."""
    anchors = set(type(goal).anchor_fields)
    cats, nums = [], []
    for name in sorted(type(goal).model_fields):
        if name in _NOT_PARAMETERS or name in anchors:
            continue
        value = getattr(goal, name)
        if isinstance(value, bool | str):
            cats.append((name, value))
        else:
            nums.append((name, _plain(value)))
    return tuple(cats), tuple(nums)


def _plain(value: Any) -> Any:
    if hasattr(value, "model_dump"):
        return value.model_dump()
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    return value


def _ordered(goal: Any) -> bool:
    return bool(getattr(goal, "ordered", False))


def canonical(graph: TaskGraph, stated_colours: frozenset[str] | None = None,
              graded: bool = False) -> _Canon:
    """``graph`` in the canonical form the comparison reads (see the module doc);
    with ``stated_colours``, every other colour is read as unspecified; ``graded``:
    objects are told apart by their sizes among alike ones too."""
    labels, of = _instances(graph, stated_colours, graded)
    g = nx.DiGraph()
    for inst, label in labels.items():
        g.add_node(inst, label=("object", *label))
    factors: dict[str, _Factor] = {}
    split_of: dict[str, list[str]] = {}
    for f in graph.factors:
        goal = f.goal
        cats, nums = _parameters(goal)
        anchor_roles = [(field_, inst) for field_ in type(goal).anchor_fields
                        for var in goal.anchor_names(field_) for inst in of.get(var, [])]
        movers = [inst for var in goal.objects for inst in of.get(var, [])]
        ordered = _ordered(goal) and len({labels[m] for m in movers}) > 1
        if not ordered:
            # An order over objects no label tells apart (three red blocks, or
            # blocks whose colours the words leave open) asks nothing: the same task.
            cats = tuple((k, False if k == "ordered" else v) for k, v in cats)
        label = (goal.type, bool(f.milestone), cats)
        per_object = goal.type in PER_OBJECT_RELATIONS and not getattr(goal, "poses", None)
        groups = [[m] for m in movers] if per_object and len(movers) > 1 else [movers]
        split_of[f.name] = []
        for k, group in enumerate(groups):
            node = f.name if len(groups) == 1 else f"{f.name}#{k}"
            if ordered and len(group) > 1:
                roles = [(f"objects@{i}", m) for i, m in enumerate(group)]
            else:
                roles = [("objects", m) for m in group]
            roles += anchor_roles
            factors[node] = _Factor(f.name, label, tuple(roles), nums)
            split_of[f.name].append(node)
            g.add_node(node, label=("factor", *label))
            for role, inst in roles:
                if g.has_edge(node, inst):
                    g[node][inst]["roles"] = g[node][inst]["roles"] | {role}
                else:
                    g.add_edge(node, inst, roles=frozenset([role]))
    closure = nx.transitive_closure_dag(graph.dependency_graph()) \
        if nx.is_directed_acyclic_graph(graph.dependency_graph()) else graph.dependency_graph()
    before = {(a2, b2) for a, b in closure.edges for a2 in split_of.get(a, [])
              for b2 in split_of.get(b, [])}
    return _Canon(g, labels, factors, before)


# ------------------------------------------------------------------- scores
def _f1(got: Counter, want: Counter) -> float:
    if not got and not want:
        return 1.0
    common = sum((got & want).values())
    if common == 0:
        return 0.0
    precision, recall = common / sum(got.values()), common / sum(want.values())
    return 2 * precision * recall / (precision + recall)


def _signature(c: _Canon, node: str) -> tuple[Any, ...]:
    f = c.factors[node]
    return (f.label, tuple(sorted((role, c.instances[inst]) for role, inst in f.roles)))


def _describe_object(label: InstanceLabel) -> str:
    kind, colour, fixed, grade = label
    return " ".join(x for x in (grade, colour, kind, "(fixed)" if fixed else "") if x)


def _describe_factor(sig: tuple[Any, ...]) -> str:
    (rtype, milestone, cats), roles = sig
    parts: dict[str, list[str]] = {}
    for role, label in roles:
        parts.setdefault(role.split("@")[0], []).append(_describe_object(label))
    body = "; ".join(f"{role}: {', '.join(names)}" for role, names in parts.items())
    extra = "".join(f", {k}={v}" for k, v in cats) + (", milestone" if milestone else "")
    return f"{rtype}({body}{extra})"


def _count_lines(prefix: str, counts: Counter, describe: Any) -> list[str]:
    return [f"{prefix}: {n} x {describe(key)}" if n > 1 else f"{prefix}: {describe(key)}"
            for key, n in sorted(counts.items(), key=lambda kv: repr(kv[0]))]


def _mappings(gen: _Canon, ref: _Canon) -> Iterator[dict[str, str]]:
    matcher = DiGraphMatcher(
        ref.graph, gen.graph, node_match=lambda a, b: a["label"] == b["label"],
        edge_match=lambda a, b: a["roles"] == b["roles"])
    for k, mapping in enumerate(matcher.isomorphisms_iter()):
        if k >= MAX_MAPPINGS:
            return
        yield mapping  # reference node -> generated node


def _order_kept(gen: _Canon, ref: _Canon, mapping: dict[str, str]) -> bool:
    return all((mapping[a], mapping[b]) in gen.before for a, b in ref.before)


def _order_agreement(gen: _Canon, ref: _Canon) -> tuple[float, list[str]]:
    """The share of the reference's ordered pairs (A before B) that the generated graph
    keeps between goals of the same signatures (any such pair: goals of one signature are
    interchangeable), and the pairs it does not keep."""
    if not ref.before:
        return 1.0, []
    pool: dict[tuple[Any, ...], list[str]] = {}
    for node in gen.factors:
        pool.setdefault(_signature(gen, node), []).append(node)
    kept, lost = 0, []
    for a, b in sorted(ref.before):
        firsts = pool.get(_signature(ref, a), [])
        thens = pool.get(_signature(ref, b), [])
        if any((x, y) in gen.before for x in firsts for y in thens if x != y):
            kept += 1
        else:
            lost.append(f"{ref.factors[a].origin} before {ref.factors[b].origin}")
    return kept / len(ref.before), sorted(set(lost))


def compare(generated: TaskGraph | dict[str, Any] | str,
            reference: TaskGraph | dict[str, Any] | str,
            proposal: str | None = None) -> Comparison:
    """Compare a generated graph with a reference graph (see the module doc).

    Args:
        generated: The graph to judge (a graph, its dict or its JSON).
        reference: The task it should be.
        proposal: The words both graphs are readings of; colours they do not name
            match any colour. None: every colour counts.

    Returns:
        The :class:`Comparison`.

    Raises:
        GraphValidationError: either graph is not a valid task graph.
    """
    stated = None if proposal is None else colours_named(proposal)
    graded = proposal is not None and sizes_named(proposal)
    gen = canonical(parse_graph(generated), stated, graded)
    ref = canonical(parse_graph(reference), stated, graded)
    objects_got, objects_want = Counter(gen.instances.values()), Counter(ref.instances.values())
    sig_got = Counter(_signature(gen, n) for n in gen.factors)
    sig_want = Counter(_signature(ref, n) for n in ref.factors)
    order, lost = _order_agreement(gen, ref)
    equivalent = False
    if objects_got == objects_want and sig_got == sig_want:
        equivalent = any(_order_kept(gen, ref, m) for m in _mappings(gen, ref))
    differences: list[str] = []
    if not equivalent:
        differences += _count_lines("missing object", objects_want - objects_got,
                                    _describe_object)
        differences += _count_lines("extra object", objects_got - objects_want, _describe_object)
        differences += _count_lines("missing goal", sig_want - sig_got, _describe_factor)
        differences += _count_lines("extra goal", sig_got - sig_want, _describe_factor)
        differences += [f"order not kept: {line}" for line in lost]
        if not differences:
            differences.append("the same objects and goals, joined differently (which object "
                               "plays which role)")
    details = _details(gen, ref)
    return Comparison(equivalent, _f1(objects_got, objects_want), _f1(sig_got, sig_want),
                      order, differences, details)


def _details(gen: _Canon, ref: _Canon) -> list[str]:
    """Numeric parameters that differ between goals of the same signature."""
    numbers: dict[tuple[Any, ...], list[Any]] = {}
    for node in gen.factors:
        numbers.setdefault(_signature(gen, node), []).append(gen.factors[node].numbers)
    out = []
    for node in ref.factors:
        theirs = numbers.get(_signature(ref, node))
        if not theirs:
            continue
        mine = theirs.pop(0)
        if mine != ref.factors[node].numbers:
            want = {k: v for k, v in ref.factors[node].numbers if v is not None}
            got = {k: v for k, v in mine if v is not None}
            if want != got:
                out.append(f"{ref.factors[node].origin}: parameters {got} (reference {want})")
    return out
