"""The articulated kinds the reading knows, as one table: a part kind (``drawer``) ->
its :class:`PartKind` (its host, the start its variables take, its level names, its
sizes, the verbs and particles of each relation, its start words).

Every reader of articulated furniture (:mod:`factask.gen.reading.parts`: mentions,
clauses, accounting; :mod:`factask.gen.reading.describe`) reads this table, not a
kind: an articulated kind is one entry in :data:`PART_KINDS` -- a cabinet's drawers
(:data:`DRAWERS`: stacked by level, slid ``open`` / ``closed``), a microwave's door
(:data:`DOORS`: a lone part the words name by its host, "open the microwave"; what
goes "into the microwave" goes in behind it) and a stove's or lamp's switch
(:data:`SWITCHES`: ``mounted_on`` its host, ``on`` or off, ``switched_on`` /
``switched_off``: "turn on the stove", "press the lamp's switch").
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from factask.library.catalog_articulated import THREE_DRAWERS, TWO_DRAWERS
from factask.vocabulary.kinds import MAX_DRAWERS, door_size, drawer_size, switch_size

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
        part_size: The size of a part, from its host's kind, size and number of parts.
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
        also: Other host kinds with such a part (a lamp's switch, as a stove's).
        state_field: The start's field saying how far it starts open (``opening``,
            ``on``).
        level_field: The start's field giving the level (None: a lone part).
        binary: The state is a yes / no (a switch on or off), not a fraction.
        by_host: The words name the part by its host ("open the microwave", "turn on
            the stove": its lone part is meant).
        into: What a put "into" the part goes into: ``part`` (a drawer), ``host`` (a
            microwave, behind its door), or None (nothing goes into a switch).
        admits: (the relation that lets things in, the one that shuts them out), or
            None: a part that starts shut is opened before anything goes in.
        states_after: Its start words stand only after it ("the stove is on", never
            "the on stove").
        color: The parts' own colour (a switch's button is red), or None: its host's.
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
    also: tuple[str, ...] = ()
    state_field: str = "opening"
    level_field: str | None = "level"
    binary: bool = False
    by_host: bool = False
    into: str | None = "part"
    admits: tuple[str, str] | None = ("open", "closed")
    states_after: bool = False
    color: str | None = None

    @property
    def hosts(self) -> tuple[str, ...]:
        """Every host kind with such parts, the one made where none is named first."""
        return (self.host, *self.also)

    def start_of(self, host: str, level: int, state: float) -> tuple[tuple[str, Any], ...]:
        """A part's start as (field, value) pairs: in ``host`` at ``level``, ``state``
        open (a fraction; a binary state is on where it is above 0)."""
        out: list[tuple[str, Any]] = [("type", self.start), (self.host_field, host)]
        if self.level_field:
            out.append((self.level_field, level))
        out.append((self.state_field, state > 0 if self.binary else state))
        return tuple(out)

    def seat_of(self, start: dict[str, Any]) -> tuple[str, int, float] | None:
        """(host, level, how far open) of a part's start (``model_dump`` or pairs), or
        None: not such a start."""
        if start.get("type") != self.start or self.host_field not in start:
            return None
        level = int(start.get(self.level_field, 0)) if self.level_field else 0
        return str(start[self.host_field]), level, float(start.get(self.state_field, 0.0))

    def level_name(self, level: int, count: int) -> str:
        """``top``, ``middle``, ``bottom`` ("" for a lone part)."""
        return self.names[count][level]


DRAWERS = PartKind(
    part="drawer", host="cabinet", start="in_cabinet", host_field="cabinet",
    most=MAX_DRAWERS,
    names={1: ("",), 2: ("bottom", "top"), 3: ("bottom", "middle", "top")},
    host_sizes={1: None, 2: TWO_DRAWERS, 3: THREE_DRAWERS},
    part_size=lambda _kind, size, count: drawer_size(size, count),
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
#: A microwave's hinged door: one per microwave, named by it ("open the microwave");
#: what is put "into the microwave" goes in behind it.
DOORS = PartKind(
    part="door", host="microwave", start="in_cabinet", host_field="cabinet", most=1,
    names={1: ("",)}, host_sizes={1: None},
    part_size=lambda _kind, size, _count: door_size(size),
    verbs={"open": frozenset({"open", "opens", "unshut"}),
           "closed": frozenset({"close", "closes", "shut", "shuts"})},
    particles={"open": frozenset({"open"}), "closed": frozenset({"shut", "closed"})},
    neutral=frozenset({"swing", "swings"}),
    states={"open": 1.0, "opened": 1.0, "ajar": 0.5, "half": 0.5, "partly": 0.5,
            "closed": 0.0, "shut": 0.0},
    order={}, said={"open": "open", "closed": "close"}, assumed={"closed": 1.0},
    by_host=True, into="host")
#: A switchable fixture's switch (a stove's, a lamp's): one per host, named by it
#: ("turn on the stove", "switch off the lamp") or itself ("press the lamp's switch").
SWITCHES = PartKind(
    part="switch", host="stove", also=("lamp",), start="mounted_on", host_field="host",
    most=1, names={1: ("",)}, host_sizes={1: None},
    part_size=lambda kind, _size, _count: switch_size(kind),
    verbs={"switched_on": frozenset({"press", "presses", "activate", "ignite"}),
           "switched_off": frozenset({"deactivate", "extinguish"})},
    particles={"switched_on": frozenset({"on"}), "switched_off": frozenset({"off"})},
    neutral=frozenset({"turn", "turns", "flip", "flips"}),
    states={"on": 1.0, "off": 0.0},
    order={}, said={"switched_on": "turn on", "switched_off": "turn off"},
    assumed={"switched_off": 1.0}, state_field="on", level_field=None, binary=True,
    by_host=True, into=None, admits=None, states_after=True, color="red")
#: Part kind -> its table entry: the one place an articulated kind is described.
PART_KINDS: dict[str, PartKind] = {p.part: p for p in (DRAWERS, DOORS, SWITCHES)}
#: Host kind -> the entry of its parts.
HOST_KINDS: dict[str, PartKind] = {h: p for p in PART_KINDS.values() for h in p.hosts}

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
                | {w for p in PART_KINDS.values() if not p.states_after for w in p.states})


__all__ = ["DETERMINERS", "DOORS", "DRAWERS", "HOST_KINDS", "LEVEL_WORDS", "ORDINALS", "PART_KINDS",
           "PHRASE_WORDS", "SIDE_WORDS", "SWITCHES", "PartKind", "Size"]
