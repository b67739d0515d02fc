"""A graph told in words: one templated sentence per goal, in the graph's order.

"put the red block into the green zone, then put the blue block onto the red block".
Every word it writes is one :mod:`factask.gen.reading.accounting` reads back from the
same graph (a property the tests check on every library graph), so a description
written here is what a faithful reading of the graph must account for in full: a
proposal set with reference graphs can be made from graphs, and a reader tested on
words whose meaning is known.
"""

from __future__ import annotations

from factask.gen.reading.parts import HOST_KINDS, LEVEL_WORDS, PART_KINDS
from factask.gen.reading.words import NUMBER_WORDS, plural_of
from factask.graph.taskgraph import TaskGraph
from factask.vocabulary.kinds import kind_spec
from factask.vocabulary.variables import StateVariable

#: Numbers written as words, the reader's own count words (a larger count: digits).
_NUMBERS = {n: w for w, n in NUMBER_WORDS.items()
            if n > 1 and w not in ("pair", "dozen")}
#: Kind names as a proposal writes them (a plural adds ``s``/``es``).
_KIND_WORDS = {"holed_box": "box with a hole"}


def noun(v: StateVariable, definite: bool = True) -> str:
    """``the three red blocks``, ``the green zone``, ``a box with a hole``."""
    kind = _KIND_WORDS.get(v.kind, v.kind)
    head, _, tail = kind.partition(" ")
    colour = f"{v.color} " if v.color else ""
    if v.is_fixed and kind_spec(v.kind).movable:
        colour = f"fixed {colour}"  # an obstacle: "the three fixed gray boxes"
    if v.count > 1:
        count = _NUMBERS.get(v.count, str(v.count))
        words = f"{count} {colour}{plural_of(head)}"
    else:
        words = f"{colour}{head}"
    words = f"{words} {tail}" if tail else words
    return f"the {words}" if definite else words


class _Furniture:
    """How the description names articulated parts and their hosts
    (:mod:`factask.gen.reading.parts`): "the half-open top drawer of the brown cabinet",
    then "the top drawer"; a host's number of parts where its level words do not imply
    it ("the brown cabinet with three drawers")."""

    def __init__(self, graph: TaskGraph) -> None:
        self.graph = graph
        self.said: set[str] = set()
        self.seats: dict[str, tuple[str, int, float]] = {}  # part -> host, level, opening
        for v in graph.variables:
            spec = PART_KINDS.get(v.kind)
            seat = spec.seat_of(v.initial.model_dump()) if spec and v.initial is not None \
                else None
            if seat is not None:
                self.seats[v.name] = seat
        self.counts: dict[str, int] = {}
        for host, _, _ in self.seats.values():
            self.counts[host] = self.counts.get(host, 0) + 1
        # What the words name of each host's parts: its parts in goals or holding movers.
        named = {n for f in graph.factors for n in f.goal.variable_names()}
        named |= {getattr(v.initial, "container", None) for v in graph.variables}
        self.implied = dict.fromkeys(self.counts, 1)
        for part, (host, _, _) in self.seats.items():
            if part in named:
                word = self._level(part)
                self.implied[host] = max(self.implied[host],
                                         LEVEL_WORDS[word][2] if word in LEVEL_WORDS else 1)

    def _level(self, part: str) -> str:
        host, level, _ = self.seats[part]
        spec = PART_KINDS[self.graph.variable(part).kind]
        return spec.level_name(level, self.counts[host]) if self.counts[host] in spec.names \
            else ""

    def noun(self, name: str) -> str:
        """The variable ``name`` as the words name it."""
        v = self.graph.variable(name)
        spec = PART_KINDS.get(v.kind)
        if name in self.seats and spec is not None and spec.by_host:
            # "the open gray microwave", "the gray stove": a lone part by its host
            _, _, opening = self.seats[name]
            state = "" if name in self.said or opening == 0 or spec.states_after else \
                "open " if opening >= 1 else "half-open "
            self.said.add(name)
            return f"the {state}{self.noun(self.seats[name][0]).removeprefix('the ')}"
        if name in self.seats:
            host, _, opening = self.seats[name]
            state = "" if name in self.said or opening == 0 else \
                "open " if opening >= 1 else "half-open "
            level = self._level(name)
            words = f"the {state}{level + ' ' if level else ''}{v.kind}"
            hosts = [u for u in self.graph.variables if u.kind == v.kind and u.name in self.seats]
            several = len({self.seats[u.name][0] for u in hosts}) > 1
            if host not in self.said or several:
                words = f"{words} of {self.noun(host)}"
            self.said.add(name)
            return words
        if v.kind in HOST_KINDS and name in self.counts:
            words = noun(v)
            n = self.counts[name]
            if name not in self.said and n > self.implied[name]:
                words = f"{words} with {_NUMBERS.get(n, str(n))} " \
                        f"{plural_of(HOST_KINDS[v.kind].part)}"
            self.said.add(name)
            return words
        return noun(v)


def _goal_words(graph: TaskGraph, name: str, told: _Furniture | None = None) -> str:
    f = graph.factor(name)
    goal = f.goal
    told = told or _Furniture(graph)
    inside = [(o, c) for o in goal.objects
              if (c := getattr(graph.variable(o).initial, "container", None)) in told.seats
              and c not in goal.variable_names()]
    taken = ""
    if inside and goal.type in ("in_zone", "inside", "on") and len(goal.objects) == 1:
        # "take the red block out of the open top drawer ... and put it into the zone"
        taken = f"take {told.noun(inside[0][0])} out of {told.noun(inside[0][1])} and "
    movers = "it" if taken else " and ".join(told.noun(o) for o in goal.objects)
    anchors = {field: [told.noun(n) for n in goal.anchor_names(field)]
               for field in type(goal).anchor_fields}

    def anchor(field: str) -> str:
        return " and ".join(anchors.get(field, []))

    t = goal.type
    # An order the goal keeps is said, as a proposal would say it.
    in_order = ", in that order" if getattr(goal, "ordered", False) and \
        len(goal.objects) > 1 else ""
    if t in ("in_zone", "inside"):
        return f"{taken}put {movers} into {anchor('zone' if t == 'in_zone' else 'container')}"
    if t == "on":
        return f"{taken}put {movers} onto {anchor('support')}"
    verb = next((p.said[t] for p in PART_KINDS.values() if t in p.said), None)
    if verb is not None:  # "open the top drawer", "close the open middle drawer"
        return f"{verb} {movers}"
    if t == "stack":
        base = f" onto {anchor('base')}" if anchors.get("base") else ""
        bottom = ", from the bottom up" if in_order else ""
        return f"stack {movers} into a tower{base}{bottom}{in_order}"
    if t == "row":
        on = f" onto {anchor('on')}" if anchors.get("on") else ""
        along = f" along {anchor('along')}" if anchors.get("along") else ""
        return f"put {movers} in a row{along}{on}{in_order}"
    if t == "circle":
        centre = f" around {anchor('center')}" if anchors.get("center") else ""
        return f"put {movers} in a circle{centre}"
    if t == "aligned":
        if goal.mode == "hole":
            return f"put {movers} aligned through the hole of {anchor('reference')}"
        if goal.mode == "corner":
            return f"put {movers} into {anchor('reference')}"
        return f"align {movers} with {anchor('reference')}"
    if t == "pile_in_zone":
        return f"sweep {movers} into {anchor('zone')}"
    if t == "rope_along":
        ends = [anchor(x) for x in ("along", "start", "end") if anchors.get(x)]
        return f"lay {movers} along {' and '.join(ends)}" if ends else f"lay {movers} straight"
    if t == "at_pose":
        frame = f" relative to {anchor('frame')}" if anchors.get("frame") else ""
        return f"put {movers} at its given pose{frame}"
    return f"put {movers} where its {t} goal says"


def describe(graph: TaskGraph) -> str:
    """``graph`` as a proposal: its goals in order, joined by ``then`` where the graph
    orders them and ``and`` where it does not; objects no goal names are left where
    they are ("; leave the yellow ball where they are"), so every object is in the
    words.

    Args:
        graph: A valid task graph.

    Returns:
        One sentence.
    """
    order = graph.factor_order()
    before = graph.dependency_graph()
    parts: list[str] = []
    told = _Furniture(graph)
    for k, name in enumerate(order):
        words = _goal_words(graph, name, told)
        if k:
            joined = any(before.has_edge(p, name) for p in order[:k])
            words = (", then " if joined else ", and ") + words
        parts.append(words)
    named = {n for f in graph.factors for n in f.goal.variable_names()}
    # A part is said with its host; a host the goals' words name is said.
    others = _together([v for v in graph.variables if v.name not in named
                        and v.name not in told.seats and v.name not in told.said])
    others = [(told.noun(v.name) if v.kind in HOST_KINDS and v.name in told.counts
               else p, n) for (p, n), v in zip(others, _firsts(graph, named, told), strict=True)]
    where = "where it is" if len(others) == 1 and others[0][1] == 1 else "where they are"
    still = f"; leave {' and '.join(p for p, _ in others)} {where}" if others else ""
    return "".join(parts) + still


def _firsts(graph: TaskGraph, named: set[str], told: _Furniture) -> list[StateVariable]:
    """The first variable of each group :func:`_together` makes of the same variables."""
    alike: dict[tuple[str, str | None, bool], StateVariable] = {}
    for v in graph.variables:
        if v.name not in named and v.name not in told.seats and v.name not in told.said:
            alike.setdefault((v.kind, v.color, v.is_fixed), v)
    return list(alike.values())


def _together(variables: list[StateVariable]) -> list[tuple[str, int]]:
    """Noun phrases of objects no goal names, the alike ones counted together
    ("the three gray boxes", not "the gray box and the gray box and ..."), each with
    how many it names."""
    alike: dict[tuple[str, str | None, bool], list[StateVariable]] = {}
    for v in variables:
        alike.setdefault((v.kind, v.color, v.is_fixed), []).append(v)  # "fixed" is said
    out = []
    for group in alike.values():
        total = sum(v.count for v in group)
        out.append((noun(group[0].model_copy(update={"count": total})), total))
    return out
