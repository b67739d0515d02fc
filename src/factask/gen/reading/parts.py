"""Articulated furniture in words: the drawers of a cabinet, named by level, opened
and shut.

A drawer is no free object: it is a *part* seated in a *host* (a cabinet) at a level
(0: the bottom one), and the relations ``open`` / ``closed`` slide it. The words
name it by its level and its host -- "the top drawer of the brown cabinet", "the
middle drawer", "the lower drawer", "the second drawer from the top", "its bottom
drawer" -- say how it starts ("the half-open top drawer", "the drawer that is open")
and what to do with it ("open", "pull out", "close", "shut", "push in", "push ...
closed"; "put the block in the drawer" is ``inside`` it).

Everything here reads one table, :data:`~factask.gen.reading.articulated.PART_KINDS`
(a part kind -> its :class:`~factask.gen.reading.articulated.PartKind`: its host, the
start its variables take, its names by level, its sizes, the verbs and particles of
each relation, its start words). A second articulated kind (a microwave's door, a
stove's switch) is one more entry there: the mentions (:func:`seat_parts`), the
clause reading (:func:`part_referents`, :func:`actuation`), the accounting
(:mod:`factask.gen.reading.part_accounting`) and the description
(:mod:`factask.gen.reading.describe`) read the table, not the kind.

How many parts a host has is read from the words: "a cabinet with three drawers",
else the most any level word asks ("top" or "bottom": two; "middle": three), else
"both drawers" / "the two drawers", else one. A level no host can have ("the fourth
drawer") names no part: the clause reading then states no goal over it, and the
accounting reports the word unread.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any, Protocol

from factask.gen.reading.articulated import (
    DETERMINERS,
    DRAWERS,
    HOST_KINDS,
    LEVEL_WORDS,
    ORDINALS,
    PART_KINDS,
    PHRASE_WORDS,
    SIDE_WORDS,
    PartKind,
    Size,
)
from factask.gen.reading.words import count_of, kind_of
from factask.vocabulary.kinds import kind_spec
from factask.vocabulary.palette import COLOR_NAMES


class Mention(Protocol):
    """What this module reads of a :class:`factask.gen.reading.mentions.Mention` (the
    mentions module calls :func:`seat_parts`, so it is not imported here; new mentions
    are made with the class of those given)."""

    @property
    def name(self) -> str: ...
    @property
    def kind(self) -> str: ...
    @property
    def color(self) -> str | None: ...
    @property
    def size(self) -> Size | None: ...
    @property
    def start(self) -> tuple[tuple[str, Any], ...]: ...


#: Words between a verb and its particle's end: "pull it all the way out".
WAY_WORDS = frozenset({"all", "the", "way", "fully", "completely", "wide", "again", "it", "them"})


@dataclass(frozen=True)
class Phrase:
    """What the words say of one part they name.

    Attributes:
        first: Index of the phrase's first word.
        last: Index of its last word (its host's phrase and a relative clause included).
        level: (counted from "bottom" / "top", rank), or None: no level named.
        fewest: The fewest parts its host must have for the level.
        state: How far it starts open, where the words say (None: not said).
        host: Index of the host's kind word the phrase names ("of the cabinet"), or None.
        plural: The phrase names several parts ("both drawers").
        count: The count it gives ("the two drawers"; 0: none).
        unplaced: A level word no host can have ("the fourth drawer", "the left drawer").
        stated: The phrase only counts a host's parts ("a cabinet with three drawers").
    """

    first: int
    last: int
    level: tuple[str, int] | None = None
    fewest: int = 1
    state: float | None = None
    host: int | None = None
    plural: bool = False
    count: int = 0
    unplaced: bool = False
    stated: bool = False


def is_part(word: str) -> PartKind | None:
    kind = kind_of(word)[0]
    return PART_KINDS.get(kind) if kind else None


def phrase_at(words: Sequence[str], i: int) -> Phrase:
    """The phrase whose part word is ``words[i]`` (see :class:`Phrase`)."""
    spec = is_part(words[i])
    assert spec is not None
    plural = kind_of(words[i])[1]
    j, level, fewest, state, count, unplaced, half = i - 1, None, 1, None, 0, False, False
    while j >= 0 and (words[j] in PHRASE_WORDS or words[j] in COLOR_NAMES
                      or count_of(words[j])):
        w = words[j]
        if w in LEVEL_WORDS:
            end, rank, fewest = LEVEL_WORDS[w]
            level = (end, rank)
        elif w in ORDINALS:
            level, fewest = ("bottom", ORDINALS[w]), max(2, ORDINALS[w] + 1)
        elif w in SIDE_WORDS:
            unplaced = True
        elif w in spec.states:
            half = half or spec.states[w] not in (0.0, 1.0)
            state = spec.states[w] if state is None or half else state
        elif count_of(w) and w not in ("a", "an", "one"):
            count = count_of(w)
        if w in DETERMINERS and j and words[j - 1] not in DETERMINERS:
            break  # "open the drawer": the verb before the article is no start word
        j -= 1
    first = j if j >= 0 and words[j] in DETERMINERS else j + 1
    if half:
        state = 0.5
    if level and fewest > spec.most:
        unplaced = True
    # "a cabinet with three drawers", "the cabinet has two drawers": a count, no part.
    stated = count > 0 and first >= 2 and words[first - 1] in ("with", "has", "have",
                                                                "having", "of") \
        and kind_of(words[first - 2])[0] in spec.hosts
    k = i + 1
    if level and words[k:k + 3] in (["from", "the", "top"], ["from", "the", "bottom"]):
        level = ("top" if words[k + 2] == "top" else "bottom", level[1])
        k += 3
    host = None
    if words[k:k + 1] == ["of"] or words[k:k + 1] == ["in"]:
        h = k + 1
        while h < len(words) and (words[h] in DETERMINERS or words[h] in COLOR_NAMES):
            h += 1
        if h < len(words) and kind_of(words[h])[0] in spec.hosts:
            host, k = h, h + 1
    if first >= 2 and words[first - 1] == "s" and kind_of(words[first - 2])[0] in spec.hosts:
        host = first - 2  # "the cabinet's top drawer": the phrase starts at "the"
        while first - 3 >= 0 and (words[first - 3] in DETERMINERS
                                  or words[first - 3] in COLOR_NAMES):
            first -= 1
        first -= 2
    if words[k:k + 2] in (["that", "is"], ["which", "is"], ["that", "are"]):
        r = k + 2
        half = False
        while r < len(words) and words[r] in spec.states:
            half = half or spec.states[words[r]] not in (0.0, 1.0)
            state = 0.5 if half else spec.states[words[r]]
            r += 1
        k = r if r > k + 2 else k
    return Phrase(first, k - 1, level, fewest, state, host, plural or count > 1,
                  count, unplaced, stated)


def _host_count(words: Sequence[str], h: int, spec: PartKind) -> int:
    """The parts a host's own words give it: "the cabinet with three drawers" (0: none)."""
    rest = words[h + 1:h + 4]
    if len(rest) == 3 and rest[0] in ("with", "has", "having", "of") and count_of(rest[1]) \
            and is_part(rest[2]) is spec:
        return count_of(rest[1])
    return 0


def _host_of(words: Sequence[str], at: int | None, i: int, hosts: list[Mention],
             positions: dict[str, int]) -> Mention:
    """The host a phrase names (its host word's colour), else the one named last before
    it, else the first."""
    if at is not None:
        colour = words[at - 1] if at and words[at - 1] in COLOR_NAMES else None
        same = [m for m in hosts if m.kind == kind_of(words[at])[0]
                and (colour is None or m.color == colour)]
        if same:
            return same[0]
    before = [m for m in hosts if positions.get(m.name, len(words)) < i]
    return max(before, key=lambda m: positions[m.name]) if before else hosts[0]


def _positions(words: Sequence[str], hosts: list[Mention]) -> dict[str, int]:
    out: dict[str, int] = {}
    for m in hosts:
        for k, w in enumerate(words):
            if kind_of(w)[0] == m.kind and (m.color is None or (k and words[k - 1] == m.color)):
                out[m.name] = k
                break
    return out


def seat_parts(words: Sequence[str], found: Sequence[Mention],
               most: int | None = None) -> list[Mention]:
    """``found`` with its parts seated: each host with as many parts as the words ask,
    every part a mention of its own (one per level, named by it: ``top_drawer``) that
    starts in its host at its level, as open as the words say.

    The mentions the scan made of part words ("the two brown drawers") are replaced by
    these; a part named with no host named gets one (uncoloured), and a host named
    with no part gets one.

    Args:
        words: The proposal's words (:func:`factask.gen.reading.words.words_of`).
        found: Its mentions.
        most: The most mentions there may be (None: any number): the hosts named
            last are left out, with their parts, until the rest fit.

    Returns:
        The mentions, each host followed by its parts.
    """
    if not any(m.kind in PART_KINDS or m.kind in HOST_KINDS for m in found):
        return list(found)
    out = list(found)
    for spec in PART_KINDS.values():
        out = _seat(words, out, spec)
    while most is not None and len(out) > most:
        host = next((m for m in reversed(out) if m.kind in HOST_KINDS), None)
        if host is None:
            break
        gone = {host.name} | {m.name for m in out if (s := seated(m)) and s[0] == host.name}
        out = [m if not {v for _, v in m.start} & gone else replace(m, start=())  # type: ignore[type-var]
               for m in out if m.name not in gone]
    return out


def _seat(words: Sequence[str], found: list[Mention], spec: PartKind) -> list[Mention]:
    hosts = [m for m in found if m.kind in spec.hosts]
    phrases = [(i, phrase_at(words, i)) for i, w in enumerate(words) if is_part(w) is spec]
    if not hosts and not phrases:
        return found
    make = type(found[0])  # the mentions' own class
    if not hosts:
        hosts = [make(spec.host, spec.host, None, 1)]
    positions = _positions(words, hosts)
    counts = {m.name: max([_host_count(words, k, spec) for k in range(len(words))
                           if kind_of(words[k])[0] in spec.hosts and _host_of(
                               words, k, k, hosts, positions) is m] or [0]) for m in hosts}
    fewest = dict.fromkeys(counts, 1)
    starts: dict[tuple[str, str, int], float] = {}
    seated = [(p, _host_of(words, p.host, i, hosts, positions)) for i, p in phrases]
    for p, host in seated:
        if p.stated:
            counts[host.name] = max(counts[host.name], p.count)
        elif not p.unplaced:
            fewest[host.name] = max(fewest[host.name], p.fewest, p.count,
                                    2 if p.plural else 1)
    total = {n: min(max(counts[n], fewest[n]), spec.most) for n in counts}
    for p, host in seated:
        if p.state is None or p.stated or p.unplaced:
            continue
        n = total[host.name]
        levels = [resolve(p, n)] if p.level else list(range(n))
        for level in levels:
            if level is not None:
                starts.setdefault((host.name, spec.part, level), p.state)
    acted_on: set[tuple[str, str, int]] = set()
    for p, host in seated:  # "close the top drawer" (its first action): it starts open
        relation = None if p.stated or p.unplaced else actuation(words, p.first, p.last)
        if relation is None:
            continue
        levels = [resolve(p, total[host.name])] if p.level else list(range(total[host.name]))
        for key in ((host.name, spec.part, lv) for lv in levels if lv is not None):
            if key not in acted_on and relation in spec.assumed:
                starts.setdefault(key, spec.assumed[relation])
            acted_on.add(key)
    taken = _taken_out(words, found, seated, total, spec, len(hosts) > 1, starts)
    found = [replace(m, start=taken[m.name]) if m.name in taken else m  # type: ignore[type-var]
             for m in found]
    out: list[Mention] = []
    done: set[str] = set()
    first_part = next((k for k, m in enumerate(found) if m.kind == spec.part), len(found))
    for k, m in enumerate([*found, None]):
        if k == first_part or m is None:
            for host in hosts:
                if host.name not in done:
                    out.extend(_host_and_parts(host, total[host.name], spec, starts,
                                               len(hosts) > 1, make))
                    done.add(host.name)
        if m is None or m.kind == spec.part:
            continue
        if m.kind in spec.hosts:
            if m.name not in done:
                out.extend(_host_and_parts(m, total[m.name], spec, starts, len(hosts) > 1,
                                           make))
                done.add(m.name)
            continue
        out.append(m)
    return out


def _taken_out(words: Sequence[str], found: Sequence[Mention],
               seated: Sequence[tuple[Phrase, Mention]], total: dict[str, int],
               spec: PartKind, prefixed: bool, starts: dict[tuple[str, str, int], float]
               ) -> dict[str, tuple[tuple[str, Any], ...]]:
    """Object -> its start inside the part the words take it out of ("take the red
    block out of the open top drawer", "the ball from the half-open bottom drawer",
    "out of it" after a drawer):
    the object named last before "out of" / "from", where the part starts open (the
    reset puts nothing inside a shut drawer; the words then leave the start open)."""
    out: dict[str, tuple[tuple[str, Any], ...]] = {}
    sources = list(seated)
    for i, w in enumerate(words):  # "pull the drawer open, take the block out of it"
        before = [(p, h) for p, h in seated if p.last < i]
        if w in ("it", "them") and before and (words[i - 1] == "from"
                                               or words[max(i - 2, 0):i] == ["out", "of"]):
            sources.append((replace(before[-1][0], first=i, last=i), before[-1][1]))
    for p, host in sources:
        f = p.first
        if not (f >= 1 and words[f - 1] == "from") and words[max(f - 2, 0):f] != ["out", "of"]:
            continue
        count = total[host.name]
        level = resolve(p, count) if p.level else (0 if count == 1 else None)
        if level is None or not starts.get((host.name, spec.part, level), 0.0):
            continue
        for q in range(f - 2, max(f - 10, -1), -1):
            kind = kind_of(words[q])[0]
            if kind is None or kind in PART_KINDS or kind in HOST_KINDS:
                continue
            colour = words[q - 1] if q and words[q - 1] in COLOR_NAMES else None
            objects = [m for m in found if m.kind == kind and colour in (None, m.color)]
            if len(objects) == 1 and not objects[0].start:
                part = part_name(host, level, count, spec, prefixed)
                out[objects[0].name] = (("type", "inside"), ("container", part))
            break
    return out


def resolve(p: Phrase, count: int) -> int | None:
    """The level (0: the bottom one) a phrase names in a host of ``count`` parts (None:
    no such level, or none named)."""
    if p.level is None or p.unplaced or p.fewest > count:
        return None
    end, rank = p.level
    level = rank if end == "bottom" else count - 1 - rank
    return level if 0 <= level < count else None


def part_name(host: Mention, level: int, count: int, spec: PartKind, prefixed: bool) -> str:
    """``top_drawer``, ``drawer`` (a lone one), ``red_cabinet_top_drawer`` (of several hosts)."""
    base = "_".join(w for w in (spec.level_name(level, count), spec.part) if w)
    return f"{host.name}_{base}" if prefixed else base


def _host_and_parts(host: Mention, count: int, spec: PartKind,
                    starts: dict[tuple[str, str, int], float], prefixed: bool,
                    make: Callable[..., Mention]) -> list[Mention]:
    size = spec.host_sizes.get(count) or host.size or kind_spec(host.kind).default_size
    out = [replace(host, size=spec.host_sizes.get(count) or host.size)]  # type: ignore[type-var]
    for level in range(count):
        start = spec.start_of(host.name, level, starts.get((host.name, spec.part, level), 0.0))
        out.append(make(part_name(host, level, count, spec, prefixed), spec.part,
                        spec.color or host.color, 1,
                        size=spec.part_size(host.kind, size, count), start=start))
    return out


def seated(m: Mention) -> tuple[str, int] | None:
    """(host, level) of a seated part's mention, or None: not a seated part."""
    spec = PART_KINDS.get(m.kind)
    seat = spec.seat_of(dict(m.start)) if spec else None
    return (seat[0], seat[1]) if seat else None


def part_referents(words: Sequence[str], i: int, found: Sequence[Mention]) -> list[Mention]:
    """The seated parts the part word ``words[i]`` names: the one at the level its
    phrase names in its host, or every one of its host (plural, or a lone part); none
    for a count ("a cabinet with three drawers") or a level no host has.

    Args:
        words: The part's words.
        i: The index of its part word.
        found: The mentions (:func:`seat_parts`).
    """
    spec = is_part(words[i])
    p = phrase_at(words, i)
    if spec is None or p.stated or p.unplaced:
        return []
    hosts = [m for m in found if m.kind in spec.hosts]
    if not hosts:
        return []
    host = _host_of(words, p.host, i, hosts, _positions(words, hosts))
    parts = [m for m in found if m.kind == spec.part and (s := seated(m)) and s[0] == host.name]
    if p.level is None:
        return parts if p.plural or len(parts) == 1 else []
    level = resolve(p, len(parts))
    return [m for m in parts if (s := seated(m)) and s[1] == level]


def actuation(words: Sequence[str], first: int, last: int) -> str | None:
    """The relation a verb gives the part(s) named by ``words[first:last + 1]``: "open
    the drawer", "pull out the drawer", "push the drawer in", "slide it shut", "open the
    bottom drawer and the top drawer"; None: no verb acts on it."""
    j, particle = first - 1, None
    if j >= 1 and words[j] in PARTICLES and words[j - 1] in ALL_VERBS | NEUTRAL_VERBS:
        particle, j = words[j], j - 1  # "pull out the drawer", "open up the drawer"
    if j >= 1 and words[j] in ("and", "or"):
        # "open the bottom drawer and the top drawer", "the switch of the stove and ..."
        before = next((k for k in range(j - 1, max(j - 8, -1), -1) if is_part(words[k])
                       and phrase_at(words, k).last == j - 1), None)
        if before is not None:
            p = phrase_at(words, before)
            return actuation(words, p.first, p.last)
    verb = words[j] if j >= 0 else None
    if verb not in ALL_VERBS and verb not in NEUTRAL_VERBS:
        return None
    k = last + 1
    while k < len(words) and words[k] in WAY_WORDS:
        k += 1
    for said in (particle, words[k] if k < len(words) else None):
        for relation, ps in _PARTICLE_OF.items():
            if said in ps:
                return relation
    return next((r for r, verbs in _VERBS_OF.items() if verb in verbs), None)


def _merged(field: str) -> dict[str, frozenset[str]]:
    out: dict[str, frozenset[str]] = {}
    for spec in PART_KINDS.values():
        for relation, ws in getattr(spec, field).items():
            out[relation] = out.get(relation, frozenset()) | ws
    return out


#: Relation -> its verbs / particles, over every part kind.
_VERBS_OF = _merged("verbs")
_PARTICLE_OF = _merged("particles")
ALL_VERBS = frozenset().union(*_VERBS_OF.values())
PARTICLES = frozenset().union(*_PARTICLE_OF.values())
NEUTRAL_VERBS = frozenset().union(*(p.neutral for p in PART_KINDS.values()))


def acted(words: Sequence[str], found: Sequence[Mention] | None = None) -> bool:
    """Whether a verb in ``words`` acts on a part ("open the drawer", "close it": a
    pronoun only where ``found``, if given, has a part)."""
    for i, w in enumerate(words):
        if is_part(w):
            p = phrase_at(words, i)
            if not p.stated and actuation(words, p.first, p.last) is not None:
                return True
        elif w in ("it", "them") and acts_on_pronoun(words, i) and (
                found is None or any(m.kind in PART_KINDS for m in found)):
            return True
    return False


def acts_on_pronoun(words: Sequence[str], i: int) -> bool:
    """Whether a verb of a part's relation governs the pronoun ``words[i]`` ("and close
    it"): it means the part named last, not the object moved last."""
    return actuation(words, i, i) is not None


def bare_inside(words: Sequence[str], i: int) -> bool:
    """Whether ``words[i]`` is "inside" / "in" with no object after it ("open the top
    drawer and put the bowl inside"): into the part named last."""
    if words[i] not in ("inside", "in", "into", "within"):
        return False
    nxt = words[i + 1] if i + 1 < len(words) else None
    return nxt is None or nxt in ("and", "then", "too", "as", "well", "first", "after")


def containers_of(parts: Sequence[Mention], found: Sequence[Mention]) -> list[Mention]:
    """What things are put into where the words put them into ``parts`` (the table's
    ``into``): a drawer itself, a door's microwave; none for a switch."""
    by_name = {m.name: m for m in found}
    out: list[Mention] = []
    for m in parts:
        spec = PART_KINDS.get(m.kind)
        seat = seated(m)
        into = m if spec and spec.into == "part" else \
            by_name.get(seat[0]) if spec and spec.into == "host" and seat else None
        if into is not None and into not in out:
            out.append(into)
    return out


def said_as(parts: Sequence[Mention], found: Sequence[Mention]) -> list[Mention]:
    """What the words named for ``parts``: the host of a part named by it ("turn on
    the stove and put the pot on it": the stove), else the parts."""
    by_name = {m.name: m for m in found}
    out: list[Mention] = []
    for m in parts:
        spec = PART_KINDS.get(m.kind)
        seat = seated(m)
        said = by_name.get(seat[0]) if spec and spec.by_host and seat else m
        if said is not None and said not in out:
            out.append(said)
    return out


def parts_named_by(refs: Sequence[Mention], found: Sequence[Mention]) -> list[Mention]:
    """The parts that hosts named by their part stand for ("put the mug into the
    microwave and close it": its door), or none: ``refs`` are not all such hosts."""
    specs = [HOST_KINDS.get(m.kind) for m in refs]
    if not refs or not all(s is not None and s.by_host for s in specs):
        return []
    names = {m.name for m in refs}
    return [m for m in found if (s := seated(m)) and s[0] in names]


def still_parts(found: Sequence[Mention]) -> set[str]:
    """The hosts and parts: furniture, still wherever no goal names it."""
    return {m.name for m in found if m.kind in PART_KINDS or m.kind in HOST_KINDS}


def with_hosts(used: set[str], found: Sequence[Mention]) -> set[str]:
    """``used`` with the hosts of its parts and all their parts: a part is no variable
    without its host, nor a host without all its parts."""
    names = {m.name for m in found}
    used = used | {v for m in found if m.name in used for _, v in m.start if v in names}
    hosts = {s[0] for m in found if m.name in used and (s := seated(m))}
    hosts |= {m.name for m in found if m.name in used and m.kind in HOST_KINDS}
    return used | hosts | {m.name for m in found if (s := seated(m)) and s[0] in hosts}


__all__ = [
    "ALL_VERBS",
    "DRAWERS",
    "HOST_KINDS",
    "LEVEL_WORDS",
    "NEUTRAL_VERBS",
    "PARTICLES",
    "PART_KINDS",
    "PHRASE_WORDS",
    "WAY_WORDS",
    "PartKind",
    "Phrase",
    "acts_on_pronoun",
    "actuation",
    "bare_inside",
    "containers_of",
    "is_part",
    "part_name",
    "part_referents",
    "parts_named_by",
    "phrase_at",
    "resolve",
    "said_as",
    "seat_parts",
    "seated",
    "still_parts",
    "with_hosts",
]
