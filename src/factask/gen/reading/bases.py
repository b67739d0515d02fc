"""Which named objects the words build on: the order in which goals may carry one
another.

Two goals that each may put their object on the other's ("the blue box on the
green box", "the green box on the blue box") make a graph whose factor order has
a cycle, which is not a task. A grammar cannot forbid a combination of choices,
only choices, so the grounded goals take one order of the named objects and a
goal may anchor on an object another goal moves only when that object comes
earlier (:func:`factask.gen.reading.capacity.acyclic_anchors`). The order is the words':
an object named right after a placing word ("on", "onto", "into", "on top of")
is a base, before the object put there ("put the red block on the blue block":
the blue block first); otherwise the order of mention ("a tower of a red, a blue
and a green block": red, blue, green from the bottom).
"""

from __future__ import annotations

from collections.abc import Sequence

import networkx as nx

from factask.gen.reading.mentions import COLOUR_LIST_LEAD, Mention
from factask.gen.reading.parts import PART_KINDS, PHRASE_WORDS, part_referents
from factask.gen.reading.words import MODIFIERS, NUMBER_WORDS, kind_of, words_of
from factask.vocabulary.palette import COLOR_NAMES

#: Words that put what comes before them onto or into what comes after.
PLACE_WORDS = frozenset({"on", "onto", "upon", "atop", "in", "into", "inside", "within",
                         "over", "above"})
#: Words that may stand between a placing word and the object it names: "on top of
#: the two red blocks", "into each of the bowls".
LEAD_WORDS = frozenset({"top", "of", "the", "a", "an", "each", "every", "both", "all", "its",
                        "their", "one", "other", "another", "that", "this"}) \
    | MODIFIERS | COLOUR_LIST_LEAD | frozenset(NUMBER_WORDS) | frozenset(COLOR_NAMES)
#: Most words back from a placing word to the object put there.
REACH = 12


def _occurrences(words: list[str], found: Sequence[Mention]) -> list[tuple[int, str]]:
    """(word index, mention name) of each kind word that names one mention: the
    mention of its kind and of the colour just before it (or the only one of its
    kind)."""
    out = []
    for i, word in enumerate(words):
        kind = kind_of(word)[0]
        if kind is None:
            continue
        if kind in PART_KINDS:  # "the middle drawer": by its level
            parts = part_referents(words, i, found)
            out.extend([(i, parts[0].name)] if len(parts) == 1 else [])
            continue
        colour = words[i - 1] if i and words[i - 1] in COLOR_NAMES else None
        same = [m for m in found if kind in (m.kind, *m.also)]
        named = [m for m in same if colour is not None and m.color == colour]
        if len(named) == 1 or len(same) == 1:
            out.append((i, (named or same)[0].name))
    return out


def base_order(found: Sequence[Mention], proposal: str) -> list[str]:
    """The mentions' names, every base before what the words put on or in it.

    Args:
        found: The proposal's mentions (:func:`factask.gen.reading.mentions.mentions`).
        proposal: The proposal's text.

    Returns:
        Every mention's name once: the order of mention, changed only where the
        words put one object on or in another named later; the order of mention
        where the words' placings go round in a circle.
    """
    names = [m.name for m in found]
    words = words_of(proposal.lower()[:4000])
    seen = _occurrences(words, found)
    order = nx.DiGraph()
    order.add_nodes_from(names)
    for i, base in seen:
        j = i - 1
        # "into the half-open middle drawer": a part's level and start words lead too
        lead = LEAD_WORDS | PHRASE_WORDS if kind_of(words[i])[0] in PART_KINDS else LEAD_WORDS
        while j >= 0 and words[j] in lead and words[j] not in PLACE_WORDS:
            j -= 1
        if j < 0 or words[j] not in PLACE_WORDS:
            continue
        put = [name for k, name in seen if j - REACH <= k < j and name != base]
        if put:
            order.add_edge(base, put[-1])
    if not nx.is_directed_acyclic_graph(order):
        return names
    return list(nx.lexicographical_topological_sort(order, key=names.index))
