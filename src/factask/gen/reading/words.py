"""The words of a proposal, as the readers read them.

Before anything is read, a proposal's text is normalised into words: phrases that
name one kind are one kind word ("an L-shaped block" is an ``ell``, "a pile of small
blocks" one ``pile``), a box with a hole is a ``holedbox``, "grey" is ``gray``, a
kind word used as a verb or a shape ("three bowls stand in a row", "line them up")
names no object, and "ones" after a colour is the kind named last ("two blue blocks
and three green ones"). :mod:`factask.gen.reading.mentions`,
:mod:`factask.gen.reading.clauses` and :mod:`factask.gen.reading.accounting` read the
same words.
"""

from __future__ import annotations

import re
from collections.abc import Callable

from factask.gen.reading.articulated import LEVEL_WORDS, PART_KINDS, PartKind
from factask.vocabulary.kinds import ASSET_KINDS
from factask.vocabulary.palette import COLOR_NAMES

#: Words that name a kind, singular (a plural ``s``/``es`` is also read).
KIND_WORDS: dict[str, str] = {
    **{kind: kind for kind in ASSET_KINDS},
    "cube": "block", "brick": "block", "sphere": "ball", "marble": "ball",
    "cup": "bowl", "bin": "container", "tray": "container", "area": "zone",
    "region": "zone", "target": "zone", "pillar": "cylinder", "can": "cylinder",
    "basket": "container", "bucket": "container", "crate": "box", "carton": "box",
    "package": "box", "parcel": "box", "disk": "cylinder", "disc": "cylinder",
    "puck": "cylinder", "peg": "cylinder", "rod": "cylinder", "dish": "bowl",
    "pot": "bowl", "orb": "ball", "pad": "zone", "mat": "zone", "platform": "pallet",
    "mug": "cylinder", "button": "switch",
    "plate": "stand", "hole": "fixture", "slot": "fixture", "socket": "fixture",
    "stripe": "line", "strip": "line", "cable": "rope", "cord": "rope", "chain": "rope",
    "heap": "pile", "board": "kit", "silhouette": "fixture",
    # What is laid across a bridge's pillars: a long flat box (:data:`DECK_SIZE`).
    "bar": "box", "plank": "box", "beam": "box", "deck": "box", "slab": "box",
    "lintel": "box",
    # A box with a hole in its side (one word: see HOLED_BOXES).
    "holedbox": "holed_box",
    # Objects of no stated shape are blocks: "pack the objects into the container".
    "object": "block", "item": "block", "piece": "block", "shape": "block",
}


#: Words of a long flat box laid across two pillars, and its size (x, y, z; metres):
#: long enough to span two 4 cm blocks 8 cm apart with room to spare.
DECK_WORDS = frozenset({"bar", "plank", "beam", "deck", "slab", "lintel"})
DECK_SIZE = (0.14, 0.04, 0.02)


#: Count words (a digit string is read too).
NUMBER_WORDS: dict[str, int] = {
    "a": 1, "an": 1, "one": 1, "single": 1, "two": 2, "pair": 2, "three": 3, "four": 4,
    "five": 5, "six": 6, "seven": 7, "eight": 8, "nine": 9, "ten": 10, "eleven": 11,
    "twelve": 12, "dozen": 12, "thirteen": 13, "fourteen": 14, "fifteen": 15,
    "sixteen": 16,
}


#: Phrases read as one kind word before the words are split: an L-shaped piece is an
#: ell (not an ell and a block), a pile of small blocks one pile (its pieces are the
#: pile, not objects of their own).
PHRASES: tuple[tuple[re.Pattern[str], str | Callable[[re.Match[str]], str]], ...] = (
    # An L-shaped marker on the table is a corner; "the corners of the pallet" are places
    # on it, not objects.
    (re.compile(r"\b(?:l|ell)\s*shaped?\s+(?:marker|mark|outline|corner)(s?)\b"), r"corner\1"),
    # ("the corner of the same colour", "of its colour": a corner marker, picked by colour)
    (re.compile(r"\bcorners?\s+of\s+(?=(?:the|a|an|its|their|each)\s)"
                r"(?!\w+\s+(?:same|matching|corresponding|identical|own|colou?r)\b)"),
     "edge of "),
    # "an L shape hole" is a hole (the words say its shape); any other L shape (with
    # or without a noun: block, piece, ...) is an ell.
    (re.compile(r"\b(?:l|ell)\s*shaped?\s+"
                r"(?=(?:hole|slot|fixture|socket|silhouette|cavity)s?\b)"), ""),
    (re.compile(r"\b(?:l|ell)\s*shaped?(?:\s+(?:block|piece|object|part|shape|brick|cube|"
                r"bar))?(s?)\b"), r"ell\1"),
    # A cylinder on its side is a log: "a horizontal cylinder", "the cylinder lying on
    # its side", "balance the cylinder horizontally on the blocks".
    (re.compile(rf"\b(?:horizontal|lying|fallen)\s+((?:{'|'.join(COLOR_NAMES)})\s+)?"
                r"cylinder(s?)\b"), r"\1log\2"),
    (re.compile(r"\bcylinder(s?)\s+(?:(?:lying|laid|placed|put)\s+)?(?:on\s+(?:its|their)\s+"
                r"sides?|horizontally|(?:lying|laid)\s+(?:down|flat))\b"), r"log\1"),
    # "cylindrical blocks", "spherical objects": the adjective says the kind.
    (re.compile(r"\bcylindrical\s+(?:block|object|piece|item|shape)(s?)\b"), r"cylinder\1"),
    (re.compile(r"\bspherical\s+(?:block|object|piece|item|shape)(s?)\b"), r"ball\1"),
    # "ell blocks", "ell pieces": the ell is the shape, the noun the object.
    (re.compile(r"\bell\s+(?:block|piece|object|part|shape|brick|cube|bar)(s?)\b"),
     r"ell\1"),
    # A kitting plate, board or tray holds a kit's shapes: the kit.
    (re.compile(r"\bkitting\s+(?:plate|board|tray|mat|base)(s?)\b"), r"kit\1"),
    (re.compile(r"\b(?:pile|heap)\s+of\s+(?:(?:small|tiny|little)\s+)?"
                rf"(?:({'|'.join(COLOR_NAMES)})\s+)?(?:(?:small|tiny|little)\s+)?[a-z]+"),
     r"\1 pile"),
)


#: "the top and bottom drawers", "the top and the middle drawer": one phrase per level
#: (:mod:`factask.gen.reading.articulated`), as the part readers read them.
_LEVELS = "|".join(LEVEL_WORDS)
_PARTS = "|".join(PART_KINDS)
PHRASES = (*PHRASES, (re.compile(rf"\b({_LEVELS})\s+(and|or)\s+(?:the\s+)?({_LEVELS})\s+"
                                 rf"({_PARTS})s?\b"), r"\1 \4 \2 the \3 \4"))


def _by_host(spec: PartKind) -> tuple[tuple[re.Pattern[str], Callable[[re.Match[str]], str]
                                             | str], ...]:
    """Phrases that name a lone part by its host (:attr:`PartKind.by_host`), read as the
    part of that host: "open the white microwave" -> "open the door of the white
    microwave", "turn the stove on", "the microwave door", "the stove is on" (its start
    words after it: "the switch of the stove is on")."""
    hosts = "|".join(spec.hosts)
    verbs = "|".join(sorted(w for ws in spec.verbs.values() for w in ws) + sorted(spec.neutral))
    particles = "|".join(sorted(w for ws in spec.particles.values() for w in ws))
    colours = "|".join(COLOR_NAMES)
    states = "|".join(spec.states)

    def acted(m: re.Match[str]) -> str:
        said = m.group("mods").split()
        state = " ".join(w for w in said if w in spec.states)
        colour = " ".join(w for w in said if w not in spec.states)
        return " ".join(w for w in (m.group("verb"), m.group("det"), state, spec.part, "of",
                                    "the", colour, m.group("host")) if w)

    return (
        (re.compile(rf"\b((?:(?:{colours})\s+)*)({hosts})\s+{spec.part}\b"),
         rf"{spec.part} of the \1\2"),
        (re.compile(rf"\b(?P<verb>(?:{verbs})(?:\s+(?:{particles}))?)\s+"
                    r"(?P<det>the|its|their|this|that|your)\s+"
                    rf"(?P<mods>(?:(?:{colours}|{states})\s+)*)(?P<host>{hosts})\b"
                    rf"(?!\s*'?\s*s\b)"), acted),
        # "turn on the stove and the lamp": the part of each
        (re.compile(rf"\b({spec.part}\s+of\s+the\s+(?:(?:{colours})\s+)*(?:{hosts}))\s+"
                    rf"(and|or)\s+(the|its)\s+((?:(?:{colours})\s+)*)({hosts})\b"
                    r"(?!\s*'?\s*s\b)"), rf"\1 \2 \3 {spec.part} of the \4\5"),
        (re.compile(rf"\b(the|its)\s+((?:(?:{colours})\s+)*)({hosts})\s+(is|was|starts)\s+"
                    rf"(?=(?:{states})\b)"), rf"\1 {spec.part} of the \2\3 that is "),
    )


#: "switch on the lamp", "switch it off": the verb, not the kind word.
PHRASES = (*PHRASES,
           (re.compile(r"\bswitch(es)?(?=\s+(?:on|off|it|them)\b|\s+(?:the|its)\s+(?:\w+\s+)"
                       r"{0,2}?(?:stove|lamp|microwave)s?\s+(?:on|off)\b)"), r"turn\1"),
           (re.compile(r"\b(?:stove\s*top|cooktop|hob|burner)(s?)\b"), r"stove\1"),
           (re.compile(r"\bstove(s?)\s+stove(s?)\b"), r"stove\1"),
           *(rule for spec in PART_KINDS.values() if spec.by_host for rule in _by_host(spec)))

#: Words that may stand between a count and its kind word without changing what is
#: counted: "four differently colored blocks", "three small matching cubes".
MODIFIERS = frozenset({
    "different", "differently", "colored", "coloured", "color", "colour", "matching",
    "corresponding", "identical", "distinct", "various", "similar", "same", "other",
    "small", "smaller", "little", "tiny", "large", "larger", "big", "bigger", "tall",
    "short", "wooden", "plastic", "solid", "empty", "separate", "individual", "more",
    "random", "randomly", "placed", "scattered", "multicolored", "multicoloured",
})
#: Size word -> its grade: the sizes that tell alike objects apart
#: (:mod:`factask.gen.reading.grades`).
GRADE_WORDS: dict[str, str] = {
    "small": "small", "smaller": "small", "smallest": "small", "little": "small",
    "tiny": "small", "large": "large", "larger": "large", "largest": "large",
    "big": "large", "bigger": "large", "biggest": "large", "huge": "large",
    "tall": "tall", "taller": "tall", "tallest": "tall", "short": "short",
    "shorter": "short", "shortest": "short", "long": "long", "longer": "long",
    "longest": "long"}



#: Words that may stand between a moving verb and its object: "pick up the two red
#: bowls".
OBJECT_LEAD = frozenset({"up", "the", "a", "an", "each", "every", "all", "both", "its",
                         "their", "this", "that", "these", "those", "and", "or"})


#: A word of a proposal (lower case).
WORD = re.compile(r"[a-z0-9]+")


def kind_of(word: str) -> tuple[str | None, bool, str]:
    """(kind, plural, singular word) of a word, or (None, False, word)."""
    if word in KIND_WORDS:
        return KIND_WORDS[word], False, word
    for suffix in ("es", "s"):
        stem = word[: -len(suffix)]
        if word.endswith(suffix) and stem in KIND_WORDS:
            return KIND_WORDS[stem], True, stem
    return None, False, word


def plural_of(stem: str) -> str:
    """``red_block`` -> ``red_blocks``, ``box`` -> ``boxes``."""
    return f"{stem}es" if stem.endswith(("s", "x", "z", "ch", "sh")) else f"{stem}s"


#: "a box with a small hole on one side": that box is a ``holed_box``; "the boxes have a
#: hole in their sides" (a sentence of its own, after the boxes were named): every box.
HOLED_BOXES = re.compile(
    r"\bbox(es)?\s+(?:(?:each|all)\s+)?(?:(with|having)|ha(?:s|ve)|that\s+ha(?:s|ve))\s+"
    r"(?:a|an|one)\s+(?:(?:small|little|round|square|tiny)\s+)*(?:hole|opening)s?"
    r"(?:\s+(?:on|in|at)\s+(?:one\s+of\s+)?(?:its|their|the|a|one)\s+(?:[a-z]+\s+)?sides?)?")
#: "the hole in the red box": the box (its hole is no object of its own).
HOLE_OF_BOX = re.compile(r"\b(?:the\s+)?holes?\s+(?:in|of|on)\s+(?=(?:the|each|its|their|a)\s)")


#: A box the words put something into: "in the brown box", "into the boxes of their colour".
BOX_TO_PUT_IN = re.compile(r"\b(?:in|into|inside|within)\s+(?:(?:the|a|an|its|their|each|"
                           r"every|one|same|matching|brown|large|big|small|open|empty|"
                           + "|".join(COLOR_NAMES) + r")\s+){0,3}box(?:es)?\b")


def words_of(text: str) -> list[str]:
    """The words of ``text``, with :data:`PHRASES` read as their kind words."""
    text = re.sub(r"\bgrey\b", "gray", text.replace("_", " ").replace("-", " "))
    found = list(HOLED_BOXES.finditer(text))
    if found:
        every = any(m.group(2) is None for m in found)
        text = HOLED_BOXES.sub(lambda m: f"holedbox{m.group(1) or ''}", text)
        text = HOLE_OF_BOX.sub("", text)
        if every:
            text = re.sub(r"\bbox(es)?\b", r"holedbox\1", text)
    if BOX_TO_PUT_IN.search(text):
        # "put each ball in the box of its colour": a box things go into is a container,
        # and so is every box the words name (the same boxes, named again).
        text = re.sub(r"\bbox(es)?\b", r"container\1", text)
    for pattern, kind_word in PHRASES:
        text = pattern.sub(kind_word, text)
    return _resolve_ones(_verb_senses(WORD.findall(text)))


#: Kind words that are also verbs or other words ("three bowls stand in a row",
#: "you can put ..."): read as the kind only after a word that starts or qualifies
#: a noun phrase (:data:`NOUN_LEAD`).
VERB_SENSES = frozenset({"stand", "stands", "can", "cans", "target", "targets", "pad",
                         "plate", "line", "lines", "board", "shape", "shapes"})
#: Words after which such a word is the noun: articles, determiners, counts, colours,
#: modifiers ("the stand", "three stands", "a square plate", "differently colored stands").
NOUN_LEAD = frozenset({"the", "a", "an", "each", "every", "its", "their", "this", "that",
                       "these", "those", "one", "own", "same", "another", "other", "any",
                       "both", "all", "square", "round", "circular", "rectangular",
                       "wooden", "marked", "target", "goal", "kitting", "insertion",
                       "straight", "long", "short"}) | MODIFIERS
#: Relative pronouns: "that stands", "which lines" are verbs ("that stand" may be a noun).
_RELATIVE = frozenset({"that", "which", "who"})
#: Words before "a line" that make it a shape of objects: "in a straight line", "form a line".
_ROW_LEAD = frozenset({"in", "into", "form", "forming", "make", "making", "one", "single"})


def _line_is_row(words: list[str], i: int) -> bool:
    """Whether ``words[i]`` (line, lined ...) is a shape, not an object: "line up the
    blocks", "lined up", "in a (straight) line"."""
    if words[i] in ("lined", "lining") or (i + 1 < len(words) and words[i + 1] == "up"):
        return True
    k = i - 1
    while k >= 0 and words[k] in ("a", "straight", "single", "one", "long", "neat"):
        k -= 1
    return k < i - 1 and k >= 0 and words[k] in _ROW_LEAD


def _verb_senses(words: list[str]) -> list[str]:
    """``words`` with the kind words of :data:`VERB_SENSES` used as verbs renamed (so
    they name no object: ``standup`` where it is an order, ``standing`` where it says
    how things are) and "a line" of objects read as a row."""
    out = list(words)
    for i, w in enumerate(words):
        before = words[i - 1] if i else ""
        after = words[i + 1] if i + 1 < len(words) else ""
        if w in ("line", "lines", "lined", "lining") and _line_is_row(words, i):
            out[i] = "row"
            continue
        if w not in VERB_SENSES:
            continue
        noun = before in NOUN_LEAD or before in COLOR_NAMES or bool(count_of(before)) \
            or kind_of(after)[0] is not None
        if before in _RELATIVE and w.endswith("s"):
            noun = False  # "the pallet that stands at the centre": a verb

        if not noun:
            # An order ("stand the box on the pallet", "then stand ...") or a state
            # ("three bowls stand in a row"): the readers tell them apart by these.
            ordered = before in ("", "then", "and", "please", "to", "you", "first", "now")
            stem = w[:-1] if w.endswith("s") else w
            out[i] = f"{stem}up" if ordered else f"{stem}ing"
    return out


#: Prepositions after which a kind word names where objects go, not what moves.
_PLACE_PREPOSITIONS = frozenset({"in", "into", "inside", "within", "on", "onto", "atop",
                                 "upon", "along", "around", "to", "near", "beside"})


def _after_preposition(words: list[str], i: int) -> bool:
    """Whether the kind word ``words[i]`` ends a phrase a place preposition governs."""
    j = i - 1
    while j >= 0 and (words[j] in OBJECT_LEAD or words[j] in COLOR_NAMES
                      or words[j] in MODIFIERS or count_of(words[j]) or words[j] == "top"):
        j -= 1
    return j >= 0 and words[j] in _PLACE_PREPOSITIONS


def _resolve_ones(words: list[str]) -> list[str]:
    return resolve_ones(words)[0]


def resolve_ones(words: list[str], last: str | None = None) -> tuple[list[str], str | None]:
    """"two blue blocks and three green ones": ``ones`` after a colour is the kind last
    named (``blocks``), so the group is read like any other.

    Args:
        words: The words (as :func:`words_of` gives them).
        last: The kind word named last before them (a sentence before), if any.

    Returns:
        The words with such ``one`` / ``ones`` replaced, and the kind word named last.
    """
    out = list(words)
    for i, w in enumerate(words):
        kind, _plural, singular = kind_of(w)
        if kind is not None and not _after_preposition(words, i):
            last = singular  # "the red ones in the red zone": the objects, not the zone
        elif w in ("one", "ones") and last and i and (words[i - 1] in COLOR_NAMES
                                                     or words[i - 1] in GRADE_WORDS) \
                and not (i + 1 < len(words) and kind_of(words[i + 1])[0] is not None):
            out[i] = plural_of(last) if w == "ones" else last
    return out, last


def count_of(word: str) -> int:
    """The count a word says (``3`` for ``three`` or ``3``), else 0."""
    return int(word) if word.isdigit() else NUMBER_WORDS.get(word, 0)


#: Participles that, after "is" / "are", say how the scene is set, not what to do:
#: "the pallets are placed in a row", "the blocks are scattered on the table".
SCENE_PARTICIPLES = frozenset({"placed", "arranged", "scattered", "positioned", "located",
                               "lined", "laid", "spread", "distributed", "situated",
                               "stacked", "set", "put", "kept", "stored", "lying"})
#: Words that make such a phrase a goal after all: "the blocks should be placed ...".
_MODALS = frozenset({"should", "must", "need", "needs", "to", "will", "shall", "has", "have"})


def passive_scene(words: list[str]) -> bool:
    """Whether a part describes the scene in the passive ("the pallets are placed in a
    row"): a state verb right before a scene participle, no modal in the part."""
    if _MODALS & set(words):
        return False
    return any(w in ("is", "are", "was", "were") and k + 1 < len(words)
               and (words[k + 1] in SCENE_PARTICIPLES or (
                   words[k + 1] in ("randomly", "already", "all", "initially")
                   and k + 2 < len(words) and words[k + 2] in SCENE_PARTICIPLES))
               for k, w in enumerate(words))


__all__ = [
    "DECK_SIZE",
    "DECK_WORDS",
    "GRADE_WORDS",
    "KIND_WORDS",
    "MODIFIERS",
    "NUMBER_WORDS",
    "OBJECT_LEAD",
    "PHRASES",
    "WORD",
    "count_of",
    "kind_of",
    "passive_scene",
    "plural_of",
    "resolve_ones",
    "words_of",
]
