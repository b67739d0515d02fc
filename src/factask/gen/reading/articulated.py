"""The articulated kinds the reading knows, as one table: a part kind (``drawer``) ->
its :class:`PartKind` (its host, the start its variables take, its level names, its
sizes, the verbs and particles of each relation, its start words).

Every reader of articulated furniture (:mod:`factask.gen.reading.parts`: mentions,
clauses, accounting; :mod:`factask.gen.reading.describe`) reads this table, not a
kind: a second articulated kind is one more entry in :data:`PART_KINDS`. A
microwave's door, say: ``PartKind(part="door", host="microwave", start=<its start
type>, host_field="microwave", most=1, names={1: ("",)}, host_sizes={1: None},
part_size=<its size rule>, verbs={"open": {"open", "swing"}, "closed": {"close",
"shut"}}, particles={"open": {"open"}, "closed": {"shut", "closed"}}, ...)``; a
stove's switch ``verbs={"on": {"turn", "switch"}, ...}`` with the particles "on" /
"off" and the relations its own.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from factask.library.catalog_articulated import THREE_DRAWERS, TWO_DRAWERS
from factask.vocabulary.kinds import MAX_DRAWERS, drawer_size

Size = tuple[float, float, float]


@dataclass(frozen=True)
class PartKind:
    """An articulated kind: parts seated in a host, each at a level.

    Attributes:
        part: The parts' kind (``drawer``).
        host: The host's kind (``cabinet``).
        start: The start type of a part (``in_cabinet``).
        host_field: The start's field naming the host (``cabinet``).
        most: The most parts a host holds.
        names: Number of parts -> their level names, the bottom one first ("" for
            a lone part: "the drawer").
        host_sizes: Number of parts -> the host's size (None: its kind's default).
        part_size: The size of a part, from its host's size and number of parts.
        verbs: Relation -> the verbs that say it ("open", "pull" / "close", "shut",
            "push").
        particles: Relation -> the words after a verb or the part that say it
            ("pull ... out", "push ... in", "slide ... shut").
        neutral: Verbs that say the relation only with a particle ("slide", "move").
        states: Start word -> how far the part starts open (a fraction).
        order: Relation -> the order in which it is done to several parts of one host:
            "up" (the bottom one first) or "down" (a drawer pulled out above a shut one
            covers its handle: open from the bottom up, close from the top down).
        said: Relation -> the verb a description says it with ("open", "close").
        assumed: Relation -> how far a part the words act on so starts where they say
            nothing of its start ("close the drawer": it is open; shut, the goal would
            hold at the start).
    """

    part: str
    host: str
    start: str
    host_field: str
    most: int
    names: dict[int, tuple[str, ...]]
    host_sizes: dict[int, Size | None]
    part_size: Callable[[Size, int], Size]
    verbs: dict[str, frozenset[str]]
    particles: dict[str, frozenset[str]]
    neutral: frozenset[str]
    states: dict[str, float]
    order: dict[str, str]
    said: dict[str, str]
    assumed: dict[str, float]

    def level_name(self, level: int, count: int) -> str:
        """``top``, ``middle``, ``bottom`` ("" for a lone part)."""
        return self.names[count][level]


DRAWERS = PartKind(
    part="drawer", host="cabinet", start="in_cabinet", host_field="cabinet",
    most=MAX_DRAWERS,
    names={1: ("",), 2: ("bottom", "top"), 3: ("bottom", "middle", "top")},
    host_sizes={1: None, 2: TWO_DRAWERS, 3: THREE_DRAWERS},
    part_size=drawer_size,
    verbs={"open": frozenset({"open", "opens", "pull", "pulls", "unshut"}),
           "closed": frozenset({"close", "closes", "shut", "shuts", "push", "pushes"})},
    particles={"open": frozenset({"out", "open", "up"}),
               "closed": frozenset({"in", "shut", "closed", "back"})},
    neutral=frozenset({"slide", "slides", "move", "draw", "get", "leave"}),
    states={"open": 1.0, "opened": 1.0, "ajar": 0.5, "half": 0.5, "partly": 0.5,
            "partially": 0.5, "slightly": 0.5, "closed": 0.0, "shut": 0.0},
    order={"open": "up", "closed": "down"},
    said={"open": "open", "closed": "close"},
    assumed={"closed": 1.0},
)
#: Part kind -> its table entry: the one place an articulated kind is described.
PART_KINDS: dict[str, PartKind] = {DRAWERS.part: DRAWERS}
#: Host kind -> the entry of its parts.
HOST_KINDS: dict[str, PartKind] = {p.host: p for p in PART_KINDS.values()}

#: Level words -> (counted from: "bottom" / "top", rank, fewest parts it asks).
LEVEL_WORDS: dict[str, tuple[str, int, int]] = {
    "top": ("top", 0, 2), "upper": ("top", 0, 2), "uppermost": ("top", 0, 2),
    "highest": ("top", 0, 2), "topmost": ("top", 0, 2),
    "bottom": ("bottom", 0, 2), "lower": ("bottom", 0, 2), "lowest": ("bottom", 0, 2),
    "bottommost": ("bottom", 0, 2), "middle": ("bottom", 1, 3), "center": ("bottom", 1, 3),
    "centre": ("bottom", 1, 3), "central": ("bottom", 1, 3)}
#: Ordinal words -> rank (counted from the bottom unless "from the top" follows).
ORDINALS: dict[str, int] = {"first": 0, "second": 1, "third": 2, "fourth": 3, "fifth": 4,
                            "sixth": 5}
#: Words that say a part stands beside another, which stacked parts never do.
SIDE_WORDS = frozenset({"left", "right", "leftmost", "rightmost", "front", "back", "far",
                        "near"})
#: Words that start a phrase naming a part, or qualify it.
DETERMINERS = frozenset({"the", "a", "an", "its", "their", "this", "that", "each", "every",
                         "both", "all", "one", "these", "those", "his", "her"})
#: Every word that may stand inside a part's phrase, before its kind word.
PHRASE_WORDS = (DETERMINERS | LEVEL_WORDS.keys() | ORDINALS.keys() | SIDE_WORDS
                | {w for p in PART_KINDS.values() for w in p.states})


__all__ = ["DETERMINERS", "DRAWERS", "HOST_KINDS", "LEVEL_WORDS", "ORDINALS", "PART_KINDS",
           "PHRASE_WORDS", "SIDE_WORDS", "PartKind", "Size"]
