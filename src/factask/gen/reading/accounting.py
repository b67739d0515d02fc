"""Every word of a proposal that says what the task is, accounted for against a graph.

A reading of a proposal must not guess silently. :func:`account` goes through the
words that carry meaning -- colours, numbers, ordinals and sequence words, sides of
the table, quantifiers, shape words, relation words, kinds, sizes, measures and
negations -- and, for each, looks for what in the graph uses it: a variable of that
colour, a count or a total of that number, an order between goals, a relation that
makes that shape ... A word nothing in the graph uses is **unread**, with the reason;
a generation that leaves words unread ends at level ``partial``, never
``completion`` (:mod:`factask.gen.strategies`), and ``factask generate --strict``
writes no graph.

The rules are deliberately one-sided: a word counts as read only when the graph has
the structure the word asks for; a word whose meaning factask cannot express (the
left half of the table, "not", "5 cm") is always unread. Words outside these
categories (verbs, articles, nouns of no kind) are not judged.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass

from factask.gen.reading.mentions import ALSO_KINDS
from factask.gen.reading.part_accounting import judge_part_word
from factask.gen.reading.selectors import ORDINAL_RANKS
from factask.gen.reading.words import count_of, kind_of, words_of
from factask.graph.taskgraph import TaskGraph
from factask.vocabulary.kinds import kind_spec
from factask.vocabulary.palette import colour_of_word

#: Word -> its category, for the words judged besides colours, counts and kinds.
ORDINALS = frozenset({"first", "second", "third", "fourth", "fifth", "sixth", "seventh",
                      "eighth", "ninth", "tenth", "last", "final", "finally", "then", "next",
                      "after", "afterwards", "before", "later", "sequence", "sequentially",
                      "order", "ordered", "followed"})
SIDES = frozenset({"left", "right", "front", "back", "rear", "half", "halves", "middle",
                   "center", "centre", "central", "edge", "edges", "side", "sides", "corner",
                   "corners", "bottom", "far", "near", "nearest", "farthest", "closest",
                   "top"})
QUANTIFIERS = frozenset({"each", "every", "all", "both", "another", "other", "others",
                         "remaining", "rest", "same", "matching", "matched", "corresponding",
                         "correspondingly", "respective", "coordinated", "different",
                         "differently", "distinct", "various", "mixed", "alternating",
                         "alternate"})
SHAPES = frozenset({"tower", "column", "stack", "stacked", "pyramid", "layer", "layers",
                    "wall", "ring", "circle", "circular", "around", "row", "rows", "line",
                    "lined", "bridge", "arch", "staircase", "stairs", "steps", "square",
                    "triangle", "triangular", "grid", "checkerboard", "cross", "letter",
                    "zigzag", "spiral", "diagonal", "diagonally", "star", "house", "car",
                    "castle", "building", "structure", "pattern", "shape", "formation"})
RELATIONS = frozenset({"into", "inside", "within", "onto", "atop", "upon", "under",
                       "beneath", "below", "underneath", "beside", "next", "between",
                       "align", "aligned", "aligning", "alignment", "sort", "sorted",
                       "sorting", "group", "grouped", "separate", "separated", "sweep",
                       "swept", "push", "pushed"})
NEGATIONS = frozenset({"not", "no", "never", "without", "except", "avoid", "avoiding",
                       "nothing", "neither", "nor", "dont", "don", "none"})
SIZES = frozenset({"small", "smaller", "smallest", "large", "larger", "largest", "big",
                   "bigger", "biggest", "tall", "taller", "tallest", "short", "shorter",
                   "tiny", "long", "longer", "wide", "wider", "narrow", "thin", "thick",
                   "heavy", "heavier", "light", "lighter", "size", "sizes", "sized",
                   "height", "flat"})
MEASURES = frozenset({"cm", "mm", "m", "meter", "meters", "metre", "metres",
                      "centimeter", "centimeters", "centimetre", "centimetres", "inch",
                      "inches", "degree", "degrees", "deg", "percent", "seconds"})
#: Side words a row of placed objects reads, by the row's axis (y: across the table).
ROW_SIDES = {"y": frozenset({"left", "right", "leftmost", "rightmost"}),
             "x": frozenset({"near", "far", "front", "back", "rear", "nearest", "farthest",
                             "closest", "furthest", "nearer", "farther"})}
#: Kinds a kind word may also mean here, beyond :data:`~factask.gen.reading.mentions.ALSO_KINDS`
#: (GenSim's "box" is often an open container; a "block" may be a box).
ALSO_MEANS: dict[str, tuple[str, ...]] = {"box": ("container",), "block": ("box",),
                                        "container": ("box", "bowl"), "bowl": ("container",),
                                        "cylinder": ("log",)}  # a log: one lying down
#: Shape adjectives before a kind word say the object's shape ("a square base"), which
#: its kind gives: read when an object of that kind is in the graph.
SHAPE_ADJECTIVES = frozenset({"square", "round", "circular", "rectangular", "triangular",
                              "cylindrical", "spherical"})
#: Words that count nothing ("a red block": "a" is an article).
_ARTICLES = frozenset({"a", "an"})
#: Relations that put objects in a region.
_REGION = frozenset({"in_zone", "inside", "pile_in_zone"})
#: Relations that put objects on something.
_ON = frozenset({"on", "stack"})


@dataclass(frozen=True)
class Word:
    """One judged word of the proposal.

    Attributes:
        text: The word as read (lower case).
        index: Its position among the proposal's words.
        category: colour, number, order, side, quantifier, shape, relation, kind,
            size, measure or negation.
        why: What in the graph uses it, or why nothing does.
    """

    text: str
    index: int
    category: str
    why: str

    def __str__(self) -> str:
        return f"{self.text!r} ({self.category}: {self.why})"


@dataclass(frozen=True)
class Accounting:
    """What a graph makes of a proposal's words.

    Attributes:
        read: The judged words the graph uses, each with what uses it.
        unread: The judged words it does not, each with why.
    """

    read: tuple[Word, ...]
    unread: tuple[Word, ...]

    @property
    def complete(self) -> bool:
        """Every judged word is read."""
        return not self.unread

    def unread_words(self) -> list[str]:
        """The unread words, each once, in the proposal's order."""
        return list(dict.fromkeys(w.text for w in self.unread))

    def to_dict(self) -> dict[str, list[dict[str, str]]]:
        return {"read": [{"word": w.text, "category": w.category, "why": w.why}
                         for w in self.read],
                "unread": [{"word": w.text, "category": w.category, "why": w.why}
                           for w in self.unread]}


class _Facts:
    """What the graph offers the words: kinds, colours, counts, relations, orders."""

    def __init__(self, graph: TaskGraph) -> None:
        self.graph = graph
        self.kinds = {v.kind for v in graph.variables}
        self.colours = {str(v.color).lower() for v in graph.variables if v.color}
        per_kind: Counter[str] = Counter()
        per_kind_colour: Counter[tuple[str, str]] = Counter()
        per_colour: Counter[str] = Counter()
        variables_per_kind: Counter[str] = Counter()
        for v in graph.variables:
            per_kind[v.kind] += v.count
            per_kind_colour[(v.kind, str(v.color))] += v.count
            per_colour[str(v.color)] += v.count
            variables_per_kind[v.kind] += 1
        # Alike objects no goal names, counted together ("leave the two blue blocks").
        named = {n for f in graph.factors for n in f.goal.variable_names()}
        idle: Counter[tuple[str, str, bool]] = Counter()
        for v in graph.variables:
            if v.name not in named:
                idle[(v.kind, str(v.color), v.is_fixed)] += v.count  # as describe() counts
        movable = [v for v in graph.variables if not v.is_fixed]
        self.counts = ({v.count for v in graph.variables} | set(per_kind.values())
                       | set(idle.values())
                       | set(per_kind_colour.values()) | set(per_colour.values())
                       | set(variables_per_kind.values())
                       | {sum(v.count for v in movable), len(graph.factors)})
        self.movable_instances = sum(v.count for v in movable)
        self.relations = {f.goal.type for f in graph.factors}
        # An order between goals, or within one (a stack or row "in that order").
        self.ordered = graph.dependency_graph().number_of_edges() > 0 or any(
            f.milestone or (getattr(f.goal, "ordered", False) and len(f.goal.objects) > 1)
            for f in graph.factors)
        self.kind_colours: dict[str, set[str]] = {}
        for v in graph.variables:
            self.kind_colours.setdefault(v.kind, set()).add(str(v.color))
        self.most_of_a_kind = max(per_kind.values(), default=0)
        self.explicit_size = any(
            tuple(v.extents) != tuple(kind_spec(v.kind).default_size) for v in graph.variables)
        self.positions = any(f.goal.type == "at_pose" or getattr(f.goal, "poses", None)
                             for f in graph.factors)
        self.modes = {getattr(f.goal, "mode", None) for f in graph.factors}
        by_name = {v.name: v for v in graph.variables}
        moved_by = {o for f in graph.factors for o in f.goal.objects}
        self.layered = "stack" in self.relations or any(
            a in moved_by for f in graph.factors if f.goal.type in ("on", "row")
            for a in f.goal.anchors())
        self.bridged = any(
            f.goal.type == "on" and sum(by_name[a].count for a in f.goal.anchors()
                                        if a in by_name) > 1 for f in graph.factors)
        self.colour_matched = any(
            by_name[o].color and by_name[o].color == by_name[a].color
            for f in graph.factors for o in f.goal.objects for a in f.goal.anchors()
            if o in by_name and a in by_name)
        self.anchored_in_region = any(
            a in by_name and (kind_spec(by_name[a].kind).region
                              or kind_spec(by_name[a].kind).receptacle)
            for f in graph.factors for a in f.goal.anchors())
        self.circle_centre = any(f.goal.type == "circle" and getattr(f.goal, "center", None)
                                 for f in graph.factors)
        # Alike objects that start at given places in a row ("the second zone from the
        # left", "the near bowl"): the side and ordinal words that pick one of them.
        self.placed_words: set[str] = set()
        posed: dict[tuple[str, str], list[tuple[float, float]]] = {}
        for v in graph.variables:
            if getattr(v.initial, "type", None) == "pose":
                posed.setdefault((v.kind, str(v.color)), []).append(
                    (float(v.initial.x), float(v.initial.y)))
        for places in posed.values():
            if len(places) < 2:
                continue
            self.placed_words |= {w for w, rank in ORDINAL_RANKS.items() if rank < len(places)}
            self.placed_words |= {"last", "middle", "center", "centre"} if len(places) > 2 \
                else {"last"}
            if len({round(y, 3) for _, y in places}) > 1:
                self.placed_words |= ROW_SIDES["y"]
            if len({round(x, 3) for x, _ in places}) > 1:
                self.placed_words |= ROW_SIDES["x"]


def _number(word: str) -> int:
    """The count a word says, as the reader counts (an article counts nothing here)."""
    return 0 if word in _ARTICLES else count_of(word)


def _judge(words: list[str], k: int, facts: _Facts) -> tuple[str, bool, str] | None:
    """(category, read, why) of ``words[k]``, or None when it is not judged."""
    w = words[k]
    nxt = words[k + 1] if k + 1 < len(words) else ""
    part = judge_part_word(words, k, facts.graph)  # "the top drawer", "push it in"
    if part is not None:
        return part
    c = colour_of_word(w)
    if c is not None:
        return ("colour", c in facts.colours,
                f"an object is {c}" if c in facts.colours else f"no object is {c}")
    if w in NEGATIONS:
        return ("negation", False, "a graph's goals cannot say what must not happen")
    if w in MEASURES and k and (_number(words[k - 1]) or words[k - 1].isdigit()):
        return ("measure", False, "distances and angles are not read from words")
    n = _number(w)
    if n:
        if nxt in MEASURES:
            return ("measure", False, "distances and angles are not read from words")
        return ("number", n in facts.counts,
                f"{n} objects of one kind, colour or variable" if n in facts.counts else
                f"no variable, kind or colour counts {n}")
    if w in ORDINALS and w in facts.placed_words:
        return ("order", True, f"the {w} of alike objects placed in a row")
    if w in ORDINALS:
        return ("order", facts.ordered, "the goals or a goal's objects are ordered"
                if facts.ordered else "no goal is ordered, nor a goal's objects")
    if w in SIDES and w in facts.placed_words:
        return ("side", True, f"the {w} one of alike objects placed in a row")
    if w in SIDES:
        if w in ("corner", "corners") and ("corner" in facts.kinds or "corner" in facts.modes):
            return ("side", True, "a corner object or a corner alignment")
        if w in ("center", "centre", "central", "middle") and (
                "center" in facts.modes or facts.circle_centre or facts.positions):
            return ("side", True, "a centred alignment, a circle's centre or a pose")
        if w in ("top", "bottom") and (facts.layered or facts.relations & _ON):
            return ("side", True, "objects rest on others")
        if facts.positions:
            return ("side", True, "goals at given positions")
        return ("side", False, "no goal says where on the table or on an object")
    if w in SHAPE_ADJECTIVES and kind_of(nxt)[0] is not None:
        judged = _judge(words, k + 1, facts)
        if judged is not None and judged[1]:
            return ("shape", True, f"a {nxt} of its kind's shape")
    if w in QUANTIFIERS:
        return ("quantifier", *_quantifier(w, facts))
    if w in SHAPES:
        return ("shape", *_shape(w, facts))
    if w in RELATIONS:
        after = [x for x in words[k + 1:k + 3] if x not in _ARTICLES]
        if w in ("into", "within") and after and after[0] in SHAPES:
            return None  # "into a tower": the shape word says it, and is judged
        return ("relation", *_relation(w, facts))
    if w in SIZES:
        return ("size", facts.explicit_size, "objects of sizes other than their kind's"
                if facts.explicit_size else "every object has its kind's default size")
    kind, _, stem = kind_of(w)
    if kind is not None:
        kinds = {kind, *ALSO_KINDS.get(stem, ()), *ALSO_MEANS.get(kind, ())}
        used = kinds & facts.kinds
        return ("kind", bool(used), f"a {sorted(used)[0]}" if used else
                f"no {' or '.join(sorted(kinds))}")
    return None


def _quantifier(w: str, facts: _Facts) -> tuple[bool, str]:
    if w in ("each", "every", "all", "both"):
        ok = facts.movable_instances >= 2
        return ok, "goals over several objects" if ok else "one object moves"
    if w in ("another", "other", "others", "remaining", "rest"):
        ok = facts.most_of_a_kind >= 2
        return ok, "several objects of a kind" if ok else "no two objects of a kind"
    if w in ("different", "differently", "distinct", "various", "mixed", "alternating",
             "alternate"):
        ok = any(len(c) > 1 for c in facts.kind_colours.values())
        return ok, ("objects of a kind in several colours" if ok else
                    "no kind comes in several colours")
    ok = facts.colour_matched
    return ok, ("goals pair objects of the same colour" if ok else
                "no goal pairs objects by colour")


def _shape(w: str, facts: _Facts) -> tuple[bool, str]:
    r = facts.relations
    if w in ("ring", "circle", "circular", "around"):
        return "circle" in r, "a circle goal" if "circle" in r else "no circle goal"
    if w in ("row", "rows", "line", "lined"):
        ok = "row" in r or (w == "line" and "line" in facts.kinds)
        return ok, "a row goal or a line" if ok else "no row goal"
    if w in ("tower", "column", "stack", "stacked", "pyramid", "layer", "layers", "wall",
             "house", "castle", "building", "structure"):
        return facts.layered, ("objects built on objects" if facts.layered else
                               "nothing is built on a moved object")
    if w in ("bridge", "arch"):
        return facts.bridged, ("an object on two supports" if facts.bridged else
                               "no object rests on two supports")
    return False, "no relation makes this shape"


def _relation(w: str, facts: _Facts) -> tuple[bool, str]:
    r = facts.relations
    if w in ("into", "inside", "within"):
        ok = bool(r & _REGION) or "aligned" in r or facts.anchored_in_region
        return ok, ("a goal into a region, a container or a fixture" if ok else
                    "no goal puts into anything")
    if w in ("onto", "atop", "upon", "under", "beneath", "below", "underneath"):
        ok = bool(r & _ON) or facts.layered
        return ok, "a goal puts objects on others" if ok else "no goal puts on anything"
    if w in ("align", "aligned", "aligning", "alignment"):
        return "aligned" in r, "an aligned goal" if "aligned" in r else "no aligned goal"
    if w in ("sweep", "swept", "push", "pushed"):
        ok = "pile_in_zone" in r
        return ok, "a pile pushed into a zone" if ok else "no pile goal"
    if w in ("sort", "sorted", "sorting", "group", "grouped", "separate", "separated"):
        anchors = {a for f in facts.graph.factors for a in f.goal.anchors()}
        ok = len(anchors) >= 2
        return ok, "goals into several places" if ok else "everything goes to one place"
    if w in ("beside", "next", "between"):
        ok = bool(r & {"row", "aligned"}) or facts.positions
        return ok, "a row, an alignment or poses" if ok else "no goal puts objects side by side"
    return False, "no goal reads this relation"


def account(proposal: str, graph: TaskGraph) -> Accounting:
    """Which of ``proposal``'s meaningful words ``graph`` uses (see the module doc).

    Args:
        proposal: The task proposal (a ``name: description`` prefix is read too).
        graph: The graph generated for it.

    Returns:
        The :class:`Accounting`: read words with what uses them, unread ones with why.
    """
    facts = _Facts(graph)
    words = words_of(proposal.lower()[:4000])
    read: list[Word] = []
    unread: list[Word] = []
    for k in range(len(words)):
        judged = _judge(words, k, facts)
        if judged is None:
            continue
        category, ok, why = judged
        (read if ok else unread).append(Word(words[k], k, category, why))
    return Accounting(tuple(read), tuple(unread))


def unread_summary(words: Iterable[Word]) -> str:
    """``'left' (side: ...), 'four' (number: ...)``: each unread word once."""
    seen: dict[str, Word] = {}
    for w in words:
        seen.setdefault(w.text, w)
    return ", ".join(str(w) for w in seen.values())


__all__ = ["NEGATIONS", "ORDINALS", "QUANTIFIERS", "RELATIONS", "SHAPES", "SIDES",
           "Accounting", "Word", "account", "unread_summary"]
