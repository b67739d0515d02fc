"""Counts and colours the words state around a group of objects, after the groups
are read (:func:`factask.gen.reading.mentions.mentions`).

A count or colour list often comes apart from the group it is of: "the red blocks
and the blue blocks; there are three of each", "all the grey cylinders, four in
total", "two towers of three cylinders each", "the balls and bowls are red, green
and blue", "in this order: black, white, gold". Each pass here takes the groups read
so far (name -> mention, in order) and the proposal's words, and recounts, splits or
colours the groups those words are of. Split from :mod:`~factask.gen.reading.mentions`
(one concept: what is said about a group after it is named).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Protocol

from factask.gen.reading.words import count_of, kind_of, plural_of
from factask.vocabulary.palette import COLOR_NAMES


class Mention(Protocol):
    """What these passes read of a :class:`factask.gen.reading.mentions.Mention` (a
    frozen dataclass: they replace it, never change it); named by protocol so this
    module does not import the one that imports it."""

    @property
    def name(self) -> str: ...
    @property
    def kind(self) -> str: ...
    @property
    def color(self) -> str | None: ...
    @property
    def count(self) -> int: ...
    @property
    def counted(self) -> bool: ...
    @property
    def listed(self) -> tuple[tuple[str, int], ...]: ...
    @property
    def movable(self) -> bool: ...

#: Largest count read from a proposal (the graph model's count limit is larger).
MAX_COUNT = 16
#: Most mentions after groups are split by colour (six balls into six zones of
#: their colours: twelve; the graph schemas take twelve variables).
MAX_SPLIT_MENTIONS = 12


def recount(found: dict[str, Mention], name: str, count: int) -> None:
    """Give the mention ``name`` the count a later phrase states, renamed to match
    (``yellow_balls`` of 2 read, 5 stated), in its place in the order."""
    old = found[name]
    stem = f"{old.color}_{old.kind}" if old.color else old.kind
    new = replace(old, name=plural_of(stem) if count > 1 else stem, count=count, counted=True)
    items = [(new.name, new) if k == name else (k, m) for k, m in found.items()]
    found.clear()
    found.update(items)


def count_each(words: list[str], found: dict[str, Mention]) -> None:
    """Give the coloured groups whose count the words did not state the count of "N
    of each" ("the red blocks and the blue blocks; there are three of each", "two
    blocks of each colour": only blocks)."""
    for i in range(len(words) - 2):
        if words[i + 1:i + 3] == ["of", "each"]:
            n, kind = count_of(words[i]), None
        elif i + 3 < len(words) and words[i + 2:i + 4] == ["of", "each"]:
            n, kind = count_of(words[i]), kind_of(words[i + 1])[0]
        else:
            continue
        for name, m in list(found.items()):
            if n and m.color and not m.counted and m.count > 1 and kind in (None, m.kind):
                recount(found, name, min(n, MAX_COUNT))


#: Words right before a colour list that make it an order: "in this order: black, ...".
_ORDER_CUES = frozenset({"order", "sequence"})
#: Words after a count that make it the total of a group named before: "four in
#: total", "six in all", "five altogether", "there are three of them".
_TOTAL = (("in", "total"), ("in", "all"), ("altogether",), ("of", "them"))


def count_in_total(words: list[str], found: dict[str, Mention]) -> None:
    """Give an uncounted group the total stated after it ("all the grey cylinders,
    four in total": four)."""
    for i in range(1, len(words)):
        n = count_of(words[i])
        if not n or not any(tuple(words[i + 1:i + 1 + len(t)]) == t for t in _TOTAL):
            continue  # "four in total", "there are three of them"
        j = i - 1
        while j >= 0 and (kind_of(words[j])[0] is None or not kind_of(words[j])[1]):
            j -= 1  # back to the plural kind word the total is of
        if j < 0:
            continue
        kind, colour = kind_of(words[j])[0], words[j - 1] if j else None
        for name, m in list(found.items()):
            if m.kind == kind and not m.counted and (
                    colour not in COLOR_NAMES or m.color == colour):
                recount(found, name, min(n, MAX_COUNT))
                break


#: Plural shape words a group may be built into, several of one size each.
_GROUP_SHAPES = frozenset({"towers", "stacks", "columns", "rows", "lines", "circles", "rings",
                           "piles"})
#: Most groups one phrase splits a mention into ("two towers of three blocks").
_MOST_GROUPS = 4


def split_per_shape(words: list[str], found: dict[str, Mention]) -> None:
    """"Two towers of three cylinders (each)": the cylinders are two groups of three,
    one per tower -- a mention each (``cylinders``, ``cylinders_2``), so each shape
    has objects of its own."""
    for i in range(len(words) - 3):
        k = count_of(words[i])
        if not 2 <= k <= _MOST_GROUPS or words[i + 1] not in _GROUP_SHAPES \
                or words[i + 2] != "of":
            continue
        n = count_of(words[i + 3])
        j = i + 4 if n else i + 3
        colour = words[j] if j < len(words) and words[j] in COLOR_NAMES else None
        j += 1 if colour else 0
        kind = kind_of(words[j])[0] if j < len(words) else None
        group = next((name for name, m in found.items() if m.kind == kind
                      and m.color == colour and (not n or m.count == n)), None)
        if group is None or len(found) + k - 1 > MAX_SPLIT_MENTIONS:
            continue
        first = found[group]
        items: list[tuple[str, Mention]] = []
        for name, m in found.items():
            items.append((name, m))
            if name == group:
                items += [(f"{name}_{g}", replace(first, name=f"{name}_{g}"))
                          for g in range(2, k + 1)]
        found.clear()
        found.update(items)


def list_free_colours(words: list[str], found: dict[str, Mention],
                       ordered: bool = False) -> None:
    """Colours listed on their own, of no kind word ("the balls and bowls are red,
    green and blue", "... matches its colour: yellow, purple and orange"): under a
    matching phrase, the colours of every group named without one; ``ordered``:
    only a list right after an order word ("put the balls in the container in this
    order: black, white, gold"), the colours of the plural movable groups."""
    if any(m.listed for m in found.values()):
        return  # the words list a group's colours already ("blocks (red, blue)")
    free: list[str] = []
    k = 0
    while k < len(words):
        run: list[str] = []
        j = k
        while j < len(words) and (words[j] in COLOR_NAMES or (words[j] in ("and", "or")
                                                              and run)):
            if words[j] in COLOR_NAMES:
                run.append(words[j])
            j += 1
        attached = j < len(words) and kind_of(words[j])[0] is not None
        after_order = k and words[k - 1] in _ORDER_CUES
        if len(set(run)) >= 2 and not attached and (after_order or not ordered):
            free = list(dict.fromkeys(run))
            break
        k = j + 1 if j > k else k + 1
    if not free:
        return
    for name, m in list(found.items()):
        # a group counted fewer than the colours listed is not the one they colour
        # ("nine blocks ... on a pallet. The bottom layer: red, blue, green, ...")
        fits = not m.counted or m.count >= len(free)
        if m.color is None and not m.listed and fits and (not ordered or m.movable):
            found[name] = replace(m, listed=tuple((c, 0) for c in free))


__all__ = ["MAX_COUNT", "MAX_SPLIT_MENTIONS", "count_each", "count_in_total",
           "list_free_colours", "recount", "split_per_shape"]
