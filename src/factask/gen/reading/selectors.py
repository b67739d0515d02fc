"""Members picked out of a group of alike objects: "the second zone from the left".

"Three bowls stand in a row. Put the red ball in the first bowl and the blue ball in
the third", "the near zone", "the fourth one", "the red block on one cylinder and the
green block on the other": the words name a group of alike objects (three bowls) and
then single members of it by an ordinal, a side or "one ... the other". Read as the
group, every such goal would go into *any* bowl -- a task, but not the one asked. Here
the group becomes its members, one object each (:func:`select_members`):

* an **ordinal** (first ... tenth, last) or a **side** (left, middle, right; near,
  front / far, back) before the kind word of a *fixed* group, or alone after "the"
  ("into the second", "the first one near the robot": :func:`spell_out` adds the
  kind word of the group named last that has that many), names one member, and the
  group is **placed**: its members stand in a row across the table from left to
  right (from near to far where the words say near / far and not left / right),
  first at the left, so that "the second from the left" is the second from the left
  in the scene (:func:`placed`; left is +y, seen from the robot, which looks along
  +x). Of a group the robot moves, "the second block" is a place in what is built
  (a tower's second block), not a member: left whole;
* "one X ... the other" names two members of any group (one and the rest), with no
  places.

The rest of a kind beside a coloured one ("the two other cylinders", "the yellow ball
from among the four balls") is a group of its own, picked by "the other"
(:func:`rest_of_kind`, read by the mention scan).

Sides on two axes at once ("the back-left corner") are a corner of the table, not a
member of a row: left whole (and the words unread).

Members of a group that the goals do not use are the ones not picked: kept still
(:func:`factask.gen.reading.clauses.still_objects`). A group whose count the words
give is never grown past it ("the fourth of three bowls" is left unread).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import replace
from typing import Protocol

from factask.gen.reading.group_counts import MAX_COUNT
from factask.gen.reading.group_counts import Mention as CountedMention
from factask.gen.reading.words import MODIFIERS, count_of, kind_of, plural_of, words_of
from factask.vocabulary.kinds import kind_spec
from factask.vocabulary.palette import COLOR_NAMES

#: Ordinal -> its place in the row (0: the first).
ORDINAL_RANKS: dict[str, int] = {
    "first": 0, "second": 1, "third": 2, "fourth": 3, "fifth": 4, "sixth": 5,
    "seventh": 6, "eighth": 7, "ninth": 8, "tenth": 9}
#: Words of the last member of a row.
LAST_WORDS = frozenset({"last", "final"})
#: Side word -> (axis, end): the row's axis ("y" left to right, "x" near to far) and
#: which end ("low": left or near, "high": right or far, "middle").
SIDE_ENDS: dict[str, tuple[str | None, str]] = {
    "left": ("y", "low"), "leftmost": ("y", "low"), "right": ("y", "high"),
    "rightmost": ("y", "high"), "near": ("x", "low"), "nearest": ("x", "low"),
    "closest": ("x", "low"), "nearer": ("x", "low"), "front": ("x", "low"),
    "far": ("x", "high"), "farthest": ("x", "high"), "furthest": ("x", "high"),
    "farther": ("x", "high"), "back": ("x", "high"), "rear": ("x", "high"),
    "middle": (None, "middle"), "center": (None, "middle"), "centre": (None, "middle"),
    "central": (None, "middle")}
#: Words that pick one member of a pair (or one and the rest): "one cylinder ... the
#: other", "a brown box ... another brown box".
PAIR_WORDS = frozenset({"one", "other", "another"})
#: Words that may stand between a selector and the kind word it qualifies.
_BETWEEN = frozenset({"tall", "short", "small", "large", "big", "little", "empty", "open",
                      "round", "square", "wooden", "flat", "marked", "the", "two", "three",
                      "four", "five", "six"}) | frozenset(COLOR_NAMES)
#: Where on the table a placed row is centred, and the room it may take (metres).
ROW_CENTRE = (0.5, 0.0)
ROW_ROOM = {"y": 0.9, "x": 0.46}
#: Gap between placed neighbours (metres): room to put things between and around them.
ROW_GAP = 0.08
#: Largest group split into members (the schemas take twelve variables in all).
MAX_MEMBERS = 6


class Mention(CountedMention, Protocol):
    """What this module reads of a :class:`factask.gen.reading.mentions.Mention`
    (a frozen dataclass, replaced and never changed; a protocol so this module does
    not import the one that imports it)."""

    @property
    def size(self) -> tuple[float, float, float] | None: ...
    @property
    def group(self) -> str | None: ...
    @property
    def selectors(self) -> tuple[str, ...]: ...
    @property
    def axis(self) -> str | None: ...
    @property
    def rank(self) -> int: ...


def is_selector(word: str) -> bool:
    """Whether ``word`` may pick a member out of a group."""
    return word in ORDINAL_RANKS or word in LAST_WORDS or word in SIDE_ENDS \
        or word in PAIR_WORDS


#: "the second", "the other one", "its third": a selector after "the" with no kind word.
_ELLIPTIC = re.compile(r"\b(the|its)\s+(" + "|".join([*ORDINAL_RANKS, *LAST_WORDS, "other"])
                       + r")(\s+ones?)?\b")
#: Words that may follow a selector standing alone ("into the second and ...", "the
#: other should stay bare"); any other word may be its noun ("the first level").
_AFTER_ALONE = frozenset({"and", "or", "but", "then", "on", "in", "into", "onto", "at",
                          "from", "near", "next", "beside", "with", "to", "is", "are",
                          "should", "stays", "stay", "remains", "remain", "must", "too",
                          "as", "so", "while", "which", "that"})


def spell_out(text: str, found: Sequence[Mention]) -> str:
    """``text`` with each selector that stands for a kind word ("into the second",
    "the first one near the robot", "leave the other") followed by that kind word:
    the kind named last before it whose group is large enough (an ordinal's rank,
    two for "other"); unchanged where no such group is named.

    Args:
        text: The proposal (lower case or not).
        found: Its mentions (groups, or members already split).

    Returns:
        The text, lower case.
    """
    text = text.lower()
    groups: dict[tuple[str, str], int] = {}  # (kind, group) -> objects in it
    for m in found:
        key = (m.kind, m.group or m.name)
        groups[key] = groups.get(key, 0) + m.count
    sizes: dict[str, int] = {}  # kind -> its largest group
    for (kind, _group), n in groups.items():
        sizes[kind] = max(sizes.get(kind, 0), n)
    out, pos = [], 0
    for match in _ELLIPTIC.finditer(text):
        rest = text[match.end():match.end() + 60]
        after = words_of(rest)[:1]
        alone = bool(match.group(3)) or not after or bool(re.match(r"\s*[.,;:!?)]", rest)) \
            or after[0] in _AFTER_ALONE
        if not alone:
            continue  # "the second zone", "the first level": its noun follows
        word = match.group(2)
        need = max(ORDINAL_RANKS.get(word, 1) + 1, 2)  # a group: two or more
        kind_word = None
        for w in reversed(words_of(text[:match.start()])):
            kind, _plural, singular = kind_of(w)
            if kind is not None and sizes.get(kind, 0) >= need:
                kind_word = singular
                break
        if kind_word is None:
            continue
        out.append(text[pos:match.start()])
        out.append(f"{match.group(1)} {word} {kind_word}")
        pos = match.end()
    out.append(text[pos:])
    return "".join(out)


def selector_before(words: list[str], i: int) -> str | None:
    """The selector that qualifies the kind word ``words[i]``: "the second zone", "the
    far gray zone", "on one cylinder", "one of the two tall cylinders"; None: none."""
    j = i - 1
    while j >= 0 and i - j <= 6:
        w = words[j]
        if w == "of":  # "one of the two cylinders"; not "the centre of the zone"
            return "one" if j and words[j - 1] == "one" else None
        if is_selector(w):
            if w in SIDE_ENDS and j and words[j - 1] in SIDE_ENDS \
                    and SIDE_ENDS[words[j - 1]][0] != SIDE_ENDS[w][0]:
                return None  # "the back-left corner": a corner of the table
            return w
        if w not in _BETWEEN:
            return None
        j -= 1
    return None


def _selections(words: list[str], found: Sequence[Mention]) -> dict[str, list[str]]:
    """Group name -> the selector words that pick its members, in the words' order."""
    groups = {m.kind: m for m in found if m.count >= 1 and m.group is None}
    out: dict[str, list[str]] = {}
    for i, w in enumerate(words):
        kind, plural, _singular = kind_of(w)
        if kind is None or kind not in groups:
            continue
        group = groups[kind]
        if sum(1 for m in found if m.kind == kind) > 1:
            continue  # several groups of the kind (by colour): the colour picks
        selector = selector_before(words, i)
        if plural and selector != "one":
            continue  # "the left zones": no one member ("one of the zones" is)
        if selector == "another" and (words[i - 1] if words[i - 1] in COLOR_NAMES
                                      else None) != group.color:
            continue  # "the red block ... another block": of any colour, not a red one
        if selector is not None and selector not in out.get(group.name, []):
            out.setdefault(group.name, []).append(selector)
    return out


def _axis(selectors: list[str], words: list[str]) -> str:
    """The row's axis: near to far where only near / far words place the members."""
    said = {SIDE_ENDS[w][0] for w in [*selectors, *words] if w in SIDE_ENDS} - {None}
    return "x" if said == {"x"} else "y"


def _ranks(selectors: list[str], size: int) -> dict[str, int] | None:
    """Selector -> member rank in a row of ``size``; None where one has no place."""
    out: dict[str, int] = {}
    for w in selectors:
        if w in ORDINAL_RANKS:
            out[w] = ORDINAL_RANKS[w]
        elif w in LAST_WORDS:
            out[w] = size - 1
        else:
            end = SIDE_ENDS[w][1]
            if end == "middle" and size % 2 == 0:
                return None  # the middle of an even row is no member
            out[w] = {"low": 0, "high": size - 1, "middle": size // 2}[end]
    return out if all(r < size for r in out.values()) else None


#: Names of a row's first, middle and last member, by axis.
_END_NAMES = {"y": ("left", "middle", "right"), "x": ("near", "middle", "far")}


def _member_name(stem: str, rank: int, size: int, axis: str, by_side: bool) -> str:
    """``second_zone``; ``left_bowl`` / ``far_zone`` where the words pick by side."""
    low, middle, high = _END_NAMES[axis]
    if by_side and (rank in (0, size - 1) or (size % 2 and rank == size // 2)):
        return f"{low if rank == 0 else high if rank == size - 1 else middle}_{stem}"
    return f"{list(ORDINAL_RANKS)[rank]}_{stem}"


def select_members(text: str, found: Sequence[Mention], most: int) -> list[Mention]:
    """``found`` with each group whose members the words pick split into them.

    Args:
        text: The proposal's description.
        found: Its mentions, before selection.
        most: The most mentions in all (a group is left whole past it).

    Returns:
        The mentions, a selected group replaced in place by its members (each count 1,
        ``group`` its group's name, ``selectors`` the words that pick it, ``rank`` and
        ``axis`` its place in the row of a fixed group: :func:`placed`).
    """
    words = words_of(spell_out(text, found))
    picks = _selections(words, found)
    out: list[Mention] = []
    for k, m in enumerate(found):
        selectors = picks.get(m.name, [])
        members = _split(m, selectors, words) if selectors else None
        if members and len(out) + len(members) + len(found) - k - 1 > most:
            members = None
        out.extend(members or [m])
    return placed(out)


def _split(m: Mention, selectors: list[str], words: list[str]) -> list[Mention] | None:
    stem = f"{m.color}_{m.kind}" if m.color else m.kind
    if set(selectors) <= PAIR_WORDS:
        second = "another" if "another" in selectors else "other"
        if second not in selectors:
            return None  # "one block" alone is a count, not a pick
        rest = max(m.count - 1, 1)  # "one cyan cylinder ... the other": two at least
        return [replace(m, name=f"one_{stem}", count=1, counted=True, group=m.name,
                        selectors=("one",)),
                replace(m, name=f"{second}_{plural_of(stem) if rest > 1 else stem}",
                        count=rest, counted=True, group=m.name, selectors=(second,))]
    selectors = [w for w in selectors if w not in PAIR_WORDS]
    if m.movable:
        return None  # "the second block" of a tower: a place in it, not a member
    if len({SIDE_ENDS[w][0] for w in selectors if w in SIDE_ENDS} - {None}) > 1:
        return None  # "the back-left corner": a corner of the table, not of a row
    highest = max((ORDINAL_RANKS[w] + 1 for w in selectors if w in ORDINAL_RANKS), default=0)
    size = max(m.count, highest, 2) if not m.counted else m.count
    if size > MAX_MEMBERS or size < 2:
        return None  # too many to split; or one object ("one first bowl"), no group
    ranks = _ranks(selectors, size)
    if ranks is None:
        return None
    axis = _axis(selectors, words)
    by_side = any(w in SIDE_ENDS for w in selectors)
    out = []
    for rank in range(size):
        named = tuple(w for w, r in ranks.items() if r == rank)
        out.append(replace(m, name=_member_name(stem, rank, size, axis, by_side), count=1,
                           counted=True, group=m.name, selectors=named, rank=rank,
                           axis=axis))
    return out


#: Words before a group's kind word that give each of its members a share of what is
#: moved there: "in each zone", "on every cylinder", "a different one of the zones".
_EACH = frozenset({"each", "every", "different", "separate", "own"})
#: Words after a count that spread it over the anchors: "12 blocks evenly over the zones".
_EVENLY = frozenset({"evenly", "equally"})


#: Words a shared anchor's phrase may hold between its preposition and its kind word.
_SHARE_LEAD = _BETWEEN | _EACH | {"a", "an", "of", "one", "top"}
#: Prepositions before a shared anchor: "in each zone", "over the three zones".
_SHARE_PREPOSITIONS = frozenset({"in", "into", "on", "onto", "over", "across", "to", "at",
                                 "among", "inside", "between", "per"})


def _shared_kind(words: list[str], found: Sequence[Mention]) -> str | None:
    """The kind of the one group whose members each take a share ("in each zone", "on
    top of every cylinder", "in a different one of the three zones", "evenly over the
    three zones"), or None."""
    kinds: set[str] = set()
    for i, w in enumerate(words):
        kind = kind_of(w)[0]
        if kind is None:
            continue
        j = i - 1
        while j >= 0 and i - j <= 8 and words[j] in _SHARE_LEAD:
            j -= 1
        if j < 0 or words[j] not in _SHARE_PREPOSITIONS:
            continue  # not where things go ("each of the three cylinders": the movers)
        if set(words[j + 1:i]) & _EACH or (j and words[j - 1] in _EVENLY):
            kinds.add(kind)
    groups = [m for m in found if m.kind in kinds and m.count > 1 and m.group is None]
    return groups[0].kind if len(groups) == 1 and len(kinds) == 1 else None


def distribute(text: str, found: Sequence[Mention], most: int) -> list[Mention]:
    """``found`` with a group whose members each take a share of another group split:
    "put each of the three cylinders in a different one of the three zones" (three
    zones, three cylinders: one each), "split 12 blocks evenly over the 3 zones" (four
    each), "a block on every cylinder". The shared group becomes its members
    (``zone_1`` ...), the other -- the one group of another kind whose count they
    divide -- as many parts (``blocks_1`` of four ...), paired in order by the
    reading (:func:`factask.gen.reading.clauses.read_goals`).

    Args:
        text: The proposal's description.
        found: Its mentions (after :func:`select_members`).
        most: The most mentions in all (nothing is split past it).

    Returns:
        The mentions, the two groups replaced in place by their members and parts, or
        ``found`` unchanged where no one pair of groups divides so.
    """
    words = words_of(text.lower())
    kind = _shared_kind(words, found)
    if kind is None:
        return list(found)
    shared = next(m for m in found if m.kind == kind and m.count > 1 and m.group is None)
    k = shared.count
    others = [m for m in found if m is not shared and m.kind != kind and m.group is None
              and m.count >= k and m.count % k == 0 and m.color is None]
    if len(others) != 1 or len(found) - 2 + 2 * k > most or k > MAX_MEMBERS:
        return list(found)
    spread = others[0]
    share = spread.count // k
    stem = f"{shared.color}_{shared.kind}" if shared.color else shared.kind
    spread_stem = spread.kind if share == 1 else plural_of(spread.kind)
    out: list[Mention] = []
    for m in found:
        if m is shared:
            out.extend(replace(m, name=f"{stem}_{i + 1}", count=1, counted=True,
                               group=m.name, rank=i) for i in range(k))
        elif m is spread:
            out.extend(replace(m, name=f"{spread_stem}_{i + 1}", count=share, counted=True,
                               group=m.name, rank=i) for i in range(k))
        else:
            out.append(m)
    return out


def placed(found: Sequence[Mention]) -> list[Mention]:
    """``found`` with the members of each placed group (``axis`` set) given a
    ``place``: a row across the table, first at the left (or nearest), spaced by the
    members' sizes; members of a row the table cannot hold get no place.

    Args:
        found: The mentions (members of a group together, as split).

    Returns:
        The mentions, members with ``place`` (x, y) set or cleared.
    """
    out = list(found)
    rows: dict[str, list[int]] = {}
    for k, m in enumerate(out):
        if m.group is not None and m.axis is not None:
            rows.setdefault(m.group, []).append(k)
    for indices in rows.values():
        axis = out[indices[0]].axis
        # Spaced by the widest footprint whichever way a member turns: room between.
        widest = max(max((out[k].size or kind_spec(out[k].kind).default_size)[:2])
                     for k in indices)
        pitch = widest + ROW_GAP
        length = pitch * (len(indices) - 1)
        fits = length + widest <= ROW_ROOM[str(axis)]
        for slot, k in enumerate(sorted(indices, key=lambda k: out[k].rank)):
            offset = length / 2 - slot * pitch  # first member: left (+y) or near (-x)
            if axis == "y":
                place = (ROW_CENTRE[0], round(ROW_CENTRE[1] + offset, 3))
            else:
                place = (round(ROW_CENTRE[0] - offset, 3), ROW_CENTRE[1])
            out[k] = replace(out[k], place=place if fits else None)
    return out


def unpicked(found: Sequence[Mention], used: set[str]) -> set[str]:
    """The members of groups the words pick from that no goal uses: the others, kept
    where they are."""
    return {m.name for m in found if m.group is not None and m.name not in used}


#: Words that say a counted group is the rest of its kind: "the two other cylinders".
OTHER_WORDS = frozenset({"other", "others", "remaining", "rest"})
#: Words that say a counted group holds the coloured one named before it: "the yellow
#: ball from among the four balls", "one of the three cylinders".
_AMONG = frozenset({"among", "amongst", "of"})


def rest_of_kind(words: list[str], i: int, earlier: Sequence[Mention]
                 ) -> tuple[int, str | None] | None:
    """The count and colour of the rest of a kind that an uncoloured counted plural at
    ``words[i]`` names after coloured ones of that kind (``earlier``): "the two other
    cylinders" (2), "the other two boxes, both red" (2, red), "the yellow ball from
    among the four balls" (3: the four hold the yellow one); None: not such a phrase."""
    if not earlier or any(m.color is None or m.group for m in earlier):
        return None
    k = i - 1
    other = False
    while k >= 0 and (words[k] in OTHER_WORDS or words[k] in MODIFIERS):
        other = other or words[k] in OTHER_WORDS
        k -= 1
    count = count_of(words[k]) if k >= 0 and words[k] not in ("a", "an") else 0
    if count < 1:
        return None
    if not other and k >= 1 and words[k - 1] == "the" and k >= 2 and words[k - 2] in _AMONG:
        count -= sum(m.count for m in earlier)  # the group holds the ones named before
    elif not other and not (k >= 1 and words[k - 1] in OTHER_WORDS):
        return None
    after = words[i + 1:i + 3]
    colour = after[1] if len(after) == 2 and after[0] in ("both", "all", "each") \
        and after[1] in COLOR_NAMES else None
    return (min(count, MAX_COUNT), colour) if count >= 1 else None



__all__ = [
    "LAST_WORDS",
    "ORDINAL_RANKS",
    "OTHER_WORDS",
    "SIDE_ENDS",
    "distribute",
    "is_selector",
    "placed",
    "rest_of_kind",
    "select_members",
    "selector_before",
    "spell_out",
    "unpicked",
]
