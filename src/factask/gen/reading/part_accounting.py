"""The words about articulated parts, accounted for against a graph
(:mod:`factask.gen.reading.accounting` asks here first).

A level word ("top", "middle", "second ... from the top") is read where the graph
uses a part at that level (a goal names it, something starts in it, or it starts
open); a side word before a part ("the left drawer") never: parts are stacked; an
ordinal past the most a host holds never ("the fourth drawer"); "half" where a
part starts partly open; a verb or particle of a part's relation ("push", "pull",
"back in", "all the way out") where the graph has that relation.
"""

from __future__ import annotations

from collections.abc import Sequence

from factask.gen.reading.articulated import LEVEL_WORDS, ORDINALS, PART_KINDS, SIDE_WORDS
from factask.gen.reading.parts import (
    ALL_VERBS,
    NEUTRAL_VERBS,
    PARTICLES,
    WAY_WORDS,
    Phrase,
    acts_on_pronoun,
    actuation,
    is_part,
    phrase_at,
    resolve,
)
from factask.graph.taskgraph import TaskGraph


def judge_part_word(words: Sequence[str], k: int, graph: TaskGraph
                    ) -> tuple[str, bool, str] | None:
    """(category, read, why) of a word that qualifies a part ("top", "second", "half",
    "left" before "drawer"; "push" of "push the drawer in"), or None: not such a word.

    A level word is read when the graph has a part at that level; a start word when a
    part starts so; a verb when the graph has its relation; a side word never (parts
    are stacked)."""
    w = words[k]
    if k >= 3 and words[k - 2:k] == ["from", "the"] and is_part(words[k - 3]) \
            and w in ("top", "bottom"):  # "the second drawer from the top"
        p = phrase_at(words, k - 3)
        ok = any(resolve(p, n) == level for level, n, _ in _graph_seats(graph))
        return "side", ok, "a part at that level" if ok else "no part at that level"
    t = k - 1
    while t >= 0 and (words[t] in WAY_WORDS or words[t] in PARTICLES) and k - t < 6:
        t -= 1
    end = t  # "pull the drawer of the cabinet all the way open": the phrase ends at its host
    t = next((j for j in range(t, max(t - 8, -1), -1) if is_part(words[j])
              and phrase_at(words, j).last == end), t)
    if t >= 0 and (w in WAY_WORDS or w in PARTICLES) and (
            is_part(words[t]) or (words[t] in ("it", "them") and acts_on_pronoun(words, t))):
        # "push the drawer back in", "pull it all the way out": the verb's particle
        p = phrase_at(words, t) if is_part(words[t]) else Phrase(t, t)
        relation = actuation(words, p.first, p.last) if p.last == end else None
        if relation is not None:
            ok = relation in {f.goal.type for f in graph.factors}
            return "relation", ok, f"how the part slides ({relation})"
    target = next((j for j in range(k + 1, min(k + 8, len(words)))
                   if is_part(words[j]) or (words[j] in ("it", "them")
                                             and acts_on_pronoun(words, j))), None)
    p = None
    if target is not None:
        p = phrase_at(words, target) if is_part(words[target]) else Phrase(target, target)
    relations = {f.goal.type for f in graph.factors}
    if p is not None and (k < p.first or k > p.last) and (
            w in ALL_VERBS | NEUTRAL_VERBS | PARTICLES):
        relation = actuation(words, p.first, p.last)
        if relation is None:
            return None
        ok = relation in relations
        article = "an" if relation[0] in "aeiou" else "a"
        return "relation", ok, f"{article} {relation} goal" if ok else f"no {relation} goal"
    if p is None or not p.first <= k < target:
        return None
    seats = _graph_seats(graph)
    if w in SIDE_WORDS:
        return "side", False, "stacked parts are named by level (top, middle, bottom), not side"
    if w in LEVEL_WORDS or w in ORDINALS:
        ok = any(resolve(p, n) == level for level, n, _ in seats)
        return "side", ok, (f"a part at the {w} level" if ok else f"no part is the {w} one")
    spec = is_part(words[target])
    if spec is not None and w in spec.states and spec.states[w] not in (0.0, 1.0):
        ok = any(0.0 < opening < 1.0 for _, _, opening in seats)
        return "start", ok, "a part starts partly open" if ok else "no part starts partly open"
    if w in ("both", "all", "each", "every"):
        ok = len(seats) >= 2
        return "quantifier", ok, "several parts" if ok else "one part"
    return None


def _graph_seats(graph: TaskGraph) -> list[tuple[int, int, float]]:
    """(level, parts of its host, opening) of every seated part of ``graph`` that the
    words are about: a goal names it, something starts in it, or it starts open."""
    out = []
    named = {n for f in graph.factors for n in f.goal.variable_names()}
    named |= {getattr(v.initial, "container", None) for v in graph.variables}
    seats = {}
    for v in graph.variables:
        spec = PART_KINDS.get(v.kind)
        seat = spec.seat_of(v.initial.model_dump()) if spec and v.initial is not None else None
        if seat is not None:
            seats[v.name] = seat
    for name, (host, level, opening) in seats.items():
        n = sum(1 for h, _, _ in seats.values() if h == host)
        if name in named or opening:
            out.append((level, n, opening))
    return out


__all__ = ["judge_part_word"]
