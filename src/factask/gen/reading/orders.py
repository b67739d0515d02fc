"""The order the words give the objects of a stack or row, by their colours.

"2 purple blocks at the bottom and 3 yellow cylinders on top", "the bottom of the
tower is red, followed by blue, then green", "the red, green and blue blocks in that
order": a stack's or row's objects of different colours, in the order the words place
them (:func:`ordered_by_words`). Used by :mod:`factask.gen.reading.clauses`.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from factask.gen.reading.mentions import Mention

#: Words that say the objects of an arrangement are listed in their order.
ORDER_WORDS = frozenset({"order", "sequence", "bottom", "followed", "then", "next",
                         "first", "second", "third", "starting", "start", "base",
                         "sequentially", "ordered", "top", "left", "right"})


def ordered_by_words(movers: list[Mention], text: str) -> tuple[list[Mention], bool]:
    """The movers in the order the words give their colours, and whether the words
    order them (an order word, and distinct colours named after it)."""
    colours = [m.color for m in movers]
    if len(movers) < 2 or None in colours or len(set(colours)) < len(colours):
        return movers, False
    words = re.findall(r"[a-z]+", text.replace("grey", "gray"))
    if "rainbow" in words and all(c in RAINBOW for c in colours):
        # "in the order of the colours of the rainbow": red first (the bottom, the
        # start of a line), violet last; "from top to bottom" turns it round
        top_first = "top" in words and "bottom" in words \
            and words.index("top") < words.index("bottom")
        ranked = sorted(movers, key=lambda m: RAINBOW.index(str(m.color)))
        return (ranked[::-1] if top_first else ranked), True
    cue = next((k for k, w in enumerate(words) if w in ORDER_WORDS), None)
    if cue is None:
        return movers, False
    placed = _positions(text, colours)
    if placed is not None:
        return sorted(movers, key=lambda m: placed[str(m.color)]), True
    if words[cue] in ("bottom", "base", "top"):
        # "blue at the bottom, then red, ...": the colour just before the place word
        # is the first of the order
        before = [k for k in range(max(cue - 3, 0), cue) if words[k] in colours]
        cue = before[-1] if before else cue
    seen: list[str] = []
    for w in words[cue:]:
        if w in colours and w not in seen:
            seen.append(w)
    if len(seen) < len(colours) - 1 and _BACK_ORDER.search(text):
        # "the red, green and blue blocks ... in that order": the colours named before
        seen = [w for k, w in enumerate(words) if w in colours and w not in words[:k]]
    if len(seen) < len(colours) - 1:
        return movers, False
    seen += [c for c in colours if c not in seen]  # the one the words leave last
    tail = words[cue:]
    top_first = "top" in tail and ("bottom" not in tail or tail.index("top") < tail.index("bottom"))
    order = list(reversed(seen)) if top_first else seen  # "from the top: red, ..."
    return sorted(movers, key=lambda m: order.index(str(m.color))), True


#: The colours of the rainbow in its order (and those a palette names between them).
RAINBOW = ("red", "orange", "yellow", "green", "cyan", "blue", "indigo", "purple", "violet")
#: An order word that points back at the colours named before it.
_BACK_ORDER = re.compile(r"\b(?:in\s+(?:that|this|the\s+same|the\s+given)\s+order|"
                         r"respectively|in\s+the\s+order\s+(?:given|named|listed))\b")
#: Words that give a place in an order: the bottom (first) to the top (last).
PLACES: dict[str, float] = {
    "bottom": 0, "base": 0, "lowest": 0, "first": 0, "start": 0, "starting": 0,
    "begin": 0, "beginning": 0, "leftmost": 0, "second": 1, "middle": 1.5, "third": 2,
    "fourth": 3, "fifth": 4, "top": 99, "last": 99, "highest": 99, "final": 99,
    "rightmost": 99, "end": 99, "uppermost": 99,
}


def _positions(text: str, colours: Sequence[str | None]) -> dict[str, float] | None:
    """Each colour's place where every colour is named in a phrase that gives one
    ("2 purple blocks at the bottom and 3 yellow cylinders on top"), else None."""
    out: dict[str, float] = {}
    for chunk in re.split(r"[,;:.!?()]|\band\b|\bthen\b|\bfollowed\b",
                          text.replace("grey", "gray")):
        words = re.findall(r"[a-z]+", chunk)
        places = [PLACES[w] for w in words if w in PLACES]
        named = [w for w in words if w in colours]
        if len(places) == 1 and len(set(named)) == 1 and named[0] not in out:
            out[named[0]] = places[0]
    if set(out) != {c for c in colours if c}:
        return None
    return out if len(set(out.values())) == len(out) else None


__all__ = ["ORDER_WORDS", "PLACES", "RAINBOW", "ordered_by_words"]
