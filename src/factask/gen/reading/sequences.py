"""Colour sequences that repeat colours: "stack them in alternating colours", "red at
the base, followed by blue, then green, then red, blue and green at the top".

A stack of "three red and three blue blocks" in alternating colours is not the red
blocks and then the blue ones: each block has its own place. Where the words ask for
such a sequence, each coloured group it runs over becomes its members, one object
each (:func:`sequence_members`: ``red_block_1``, ``red_block_2`` ...), and the
arrangement that moves them all takes them in the sequence
(:func:`colour_sequence`, applied by
:func:`factask.gen.reading.goal_order.in_member_sequence`):

* **alternating** ("alternating", "alternately", "interleaved") over two or more
  coloured groups of one kind, of equal counts (or one more in the first): one of
  each colour in turn, the colours in the order the words give them ("the tower should
  start with a red block at the bottom"), else in the order they are named;
* **a listed sequence**: after an order word, the colours named in order name every
  member ("red at the base, followed by blue, then green, then red, blue and green
  at the top": the two red, two blue and two green blocks) -- a list that repeats a
  colour and names as many of each colour as the groups hold.

Anything else (a list that names fewer, counts that do not match) leaves the groups
whole, and the accounting says what the words asked that the graph does not do.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from dataclasses import replace

from factask.gen.reading.selectors import Mention
from factask.gen.reading.words import words_of

#: Words that ask one of each colour in turn.
ALTERNATING = frozenset({"alternating", "alternate", "alternately", "alternated",
                         "interleaved", "interleaving", "interleave", "alternation"})
#: Words after which the colours named are a sequence.
CUES = frozenset({"order", "sequence", "bottom", "base", "followed", "starting", "start",
                   "first", "top"})


def _listed(words: list[str], colours: set[str]) -> list[str]:
    """The colours of ``colours`` named after the first order word, in order."""
    cue = next((k for k, w in enumerate(words) if w in CUES), None)
    return [] if cue is None else [w for w in words[cue:] if w in colours]


def colour_sequence(words: list[str], groups: Sequence[Mention],
                    first: Sequence[str] = ()) -> list[str] | None:
    """The colour of each place in the sequence the words ask of ``groups`` (coloured
    groups of one kind), or None: no such sequence. ``first``: the colours in the order
    the words put them, where they do ("a red block at the bottom")."""
    counts = {str(m.color): m.count for m in groups}
    listed = _listed(words, set(counts))
    if Counter(listed) == Counter(counts) and len(listed) > len(counts):
        return listed
    if not ALTERNATING & set(words):
        return None
    first = list(dict.fromkeys([*first, *listed, *(str(m.color) for m in groups)]))
    first += [c for c in counts if c not in first]
    most = max(counts.values())
    if any(n not in (most, most - 1) for n in counts.values()) or counts[first[0]] != most:
        return None  # only the first colour may have one more
    return [c for k in range(most) for c in first if k < counts[c]]


def _runs(found: Sequence[Mention], words: list[str]) -> dict[str, list[Mention]]:
    """Kind -> its coloured groups that a sequence runs over (two groups or more, each
    of two objects or more, nothing split already)."""
    out: dict[str, list[Mention]] = {}
    for m in found:
        if m.color and m.group is None and m.count >= 2:
            out.setdefault(m.kind, []).append(m)
    return {k: g for k, g in out.items() if len(g) >= 2 and colour_sequence(words, g)}


def sequence_members(text: str, found: Sequence[Mention], most: int) -> list[Mention]:
    """``found`` with each coloured group a repeating colour sequence runs over split
    into its members (``red_block_1`` ..., ``group`` the group's name, ``rank`` its
    place among them); the others as they are; nothing split past ``most`` mentions.

    Args:
        text: The proposal's description.
        found: Its mentions (frozen dataclasses).
        most: The most mentions in all.

    Returns:
        The mentions, split where the words ask a sequence over members.
    """
    runs = _runs(found, words_of(text))
    split = {m.name for groups in runs.values() for m in groups}
    total = sum(m.count if m.name in split else 1 for m in found)
    if not split or total > most:
        return list(found)
    out: list[Mention] = []
    for m in found:
        if m.name not in split:
            out.append(m)
            continue
        stem = f"{m.color}_{m.kind}"
        out.extend(replace(m, name=f"{stem}_{k + 1}", count=1, group=m.name, rank=k)  # type: ignore[type-var]
                   for k in range(m.count))
    return out


__all__ = ["ALTERNATING", "CUES", "colour_sequence", "sequence_members"]
