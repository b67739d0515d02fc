"""The order the words give the objects of a stack or row, by their colours or sizes.

"2 purple blocks at the bottom and 3 yellow cylinders on top", "the bottom of the
tower is red, followed by blue, then green", "the red, green and blue blocks in that
order": a stack's or row's objects of different colours, in the order the words place
them (:func:`ordered_by_words`). Used by :mod:`factask.gen.reading.clauses`.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from factask.gen.reading.mentions import Mention
from factask.gen.reading.words import GRADE_WORDS
from factask.vocabulary.palette import COLOR_NAMES

#: Words that say the objects of an arrangement are listed in their order.
ORDER_WORDS = frozenset({"order", "sequence", "bottom", "followed", "then", "next",
                         "first", "second", "third", "starting", "start", "base",
                         "sequentially", "ordered", "top", "left", "right"})


def ordered_by_words(movers: list[Mention], text: str) -> tuple[list[Mention], bool]:
    """The movers in the order the words give their colours (or, for alike objects
    told apart by size, their sizes: "the large box first", "from the largest at the
    bottom to the smallest"), and whether the words order them (an order word, and
    distinct colours or sizes named after it)."""
    tags = _tags(movers)
    if tags is None:
        return movers, False
    words = re.findall(r"[a-z]+", text.replace("grey", "gray"))
    graded = tags[0] not in COLOR_NAMES
    if graded:  # "largest", "bigger": their grade, named as the movers' are
        words = [GRADE_WORDS.get(w, w) for w in words]
        text = " ".join(words)
    tag_of = {m.name: tag for m, tag in zip(movers, tags, strict=True)}
    if not graded and "rainbow" in words and all(c in RAINBOW for c in tags):
        # "in the order of the colours of the rainbow": red first (the bottom, the
        # start of a line), violet last; "from top to bottom" turns it round
        top_first = "top" in words and "bottom" in words \
            and words.index("top") < words.index("bottom")
        ranked = sorted(movers, key=lambda m: RAINBOW.index(tag_of[m.name]))
        return (ranked[::-1] if top_first else ranked), True
    cue = next((k for k, w in enumerate(words) if w in ORDER_WORDS), None)
    if cue is None:
        return movers, False
    placed = _positions(text, tags)
    if placed is not None:
        return sorted(movers, key=lambda m: placed[tag_of[m.name]]), True
    if words[cue] in ("bottom", "base", "top"):
        # "blue at the bottom, then red, ...": the tag just before the place word
        # is the first of the order
        # ("a yellow block at the bottom": four words back)
        before = [k for k in range(max(cue - 4, 0), cue) if words[k] in tags]
        cue = before[-1] if before else cue
    seen: list[str] = []
    for w in words[cue:]:
        if w in tags and w not in seen:
            seen.append(w)
    if len(seen) < len(tags) - 1 and (_BACK_ORDER.search(text) or graded):
        # "the red, green and blue blocks ... in that order": the tags named before;
        # "the large box and the small box ..., the large box first"
        seen = [w for k, w in enumerate(words) if w in tags and w not in words[:k]]
    if len(seen) < len(tags) - 1:
        return movers, False
    seen += [c for c in tags if c not in seen]  # the one the words leave last
    tail = words[cue:]
    top_first = "top" in tail and ("bottom" not in tail or tail.index("top") < tail.index("bottom"))
    order = list(reversed(seen)) if top_first else seen  # "from the top: red, ..."
    if graded:
        order = _by_size(order)
    return sorted(movers, key=lambda m: order.index(tag_of[m.name])), True


def _by_size(order: list[str]) -> list[str]:
    """Grades in the words' order, the middle size the words leave unnamed between the
    two they name ("from the largest at the bottom to the smallest": large, medium,
    small)."""
    if len(order) == 3 and order[-1] == "medium":
        return [order[0], "medium", order[1]]
    return order


def _tags(movers: list[Mention]) -> list[str] | None:
    """What tells the movers apart in the words: their colours, else their grades
    (sizes); None: neither does, one each."""
    if len(movers) < 2:
        return None
    for tags in ([m.color for m in movers], [m.grade for m in movers]):
        if None not in tags and len(set(tags)) == len(tags):
            return [str(t) for t in tags]
    return None


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


def _positions(text: str, colours: Sequence[str]) -> dict[str, float] | None:
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
