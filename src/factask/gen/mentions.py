"""The objects a proposal names, read from its words: a hint for the model.

"put the three red blocks in the green zone" names ``red_blocks`` (3 blocks,
red) and ``green_zone`` (a green zone). The prompts of the steps that declare
variables (``one_shot``, ``variables``, ``subtask_design``) list these mentions
with the names to give them, so a model -- a small one above all, which tends to
copy names from the examples instead -- starts from the objects the proposal
asks for. It is a hint only: the schema and the verification ladder decide.

Only the vocabulary is recognised (the colours of :mod:`factask.model.palette`,
the asset kinds of :mod:`factask.model.kinds` and a few synonyms), so a mention
is always something the graph model can express.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from factask.model.kinds import ASSET_KINDS
from factask.model.palette import COLOR_NAMES

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
    "plate": "stand", "hole": "fixture", "slot": "fixture", "socket": "fixture",
    "stripe": "line", "strip": "line", "cable": "rope", "cord": "rope", "chain": "rope",
    "heap": "pile", "board": "kit", "silhouette": "fixture",
    # Objects of no stated shape are blocks: "pack the objects into the container".
    "object": "block", "item": "block", "piece": "block", "shape": "block",
}
#: Other kinds an everyday word may as well mean: a graph whose coloured object is
#: one of these is still the proposal's ("the red basket" may be a red bowl). The
#: grounded answers use the word's kind in :data:`KIND_WORDS`.
ALSO_KINDS: dict[str, tuple[str, ...]] = {
    "cube": ("box",), "brick": ("box",), "crate": ("container",), "carton": ("container",),
    "package": ("block",), "parcel": ("block",), "basket": ("bowl",), "bucket": ("bowl",),
    "bin": ("bowl",), "tray": ("bowl", "kit"), "dish": ("container",), "pot": ("container",),
    "cup": ("container",), "platform": ("stand",), "plate": ("pallet", "zone", "kit"),
    "board": ("pallet",), "peg": ("block",), "rod": ("block",),
    "object": ("box", "cylinder", "ball", "ell"), "item": ("box", "cylinder", "ball", "ell"),
    "piece": ("box", "cylinder", "ball", "ell"), "shape": ("box", "cylinder", "ball", "ell"),
    "hole": ("kit", "container"), "slot": ("kit",), "silhouette": ("kit",), "area": ("pallet",),
}
#: A proposal that starts with a task name: ``kebab-case-name: description``.
TASK_NAME = re.compile(r"^\s*([a-z0-9]+(?:-[a-z0-9]+)+)\s*:\s*(.*)$", re.DOTALL)
#: A proposal that ends with a task name, as the generator reads one: ``description name``.
TRAILING_NAME = re.compile(r"^(.*\S)\s+([a-z0-9]+(?:-[a-z0-9]+)+)\s*$", re.DOTALL)
#: Phrases read as one kind word before the words are split: an L-shaped piece is an
#: ell (not an ell and a block), a pile of small blocks one pile (its pieces are the
#: pile, not objects of their own).
PHRASES: tuple[tuple[re.Pattern[str], str], ...] = (
    # "an L shape hole" is a hole (the words say its shape); any other L shape (with
    # or without a noun: block, piece, ...) is an ell.
    (re.compile(r"\b(?:l|ell)\s*shaped?\s+"
                r"(?=(?:hole|slot|fixture|socket|silhouette|cavity)s?\b)"), ""),
    (re.compile(r"\b(?:l|ell)\s*shaped?(?:\s+(?:block|piece|object|part|shape|brick|cube|"
                r"bar))?(s?)\b"), r"ell\1"),
    # "ell blocks", "ell pieces": the ell is the shape, the noun the object.
    (re.compile(r"\bell\s+(?:block|piece|object|part|shape|brick|cube|bar)(s?)\b"),
     r"ell\1"),
    (re.compile(r"\b(?:pile|heap)\s+of\s+(?:(?:small|tiny|little)\s+)?"
                rf"(?:({'|'.join(COLOR_NAMES)})\s+)?(?:(?:small|tiny|little)\s+)?[a-z]+"),
     r"\1 pile"),
)
#: Count words (a digit string is read too).
NUMBER_WORDS: dict[str, int] = {
    "a": 1, "an": 1, "one": 1, "single": 1, "two": 2, "pair": 2, "three": 3, "four": 4,
    "five": 5, "six": 6, "seven": 7, "eight": 8, "nine": 9, "ten": 10, "eleven": 11,
    "twelve": 12, "dozen": 12, "thirteen": 13, "fourteen": 14, "fifteen": 15,
    "sixteen": 16,
}
#: Words that may stand between a count and its kind word without changing what is
#: counted: "four differently colored blocks", "three small matching cubes".
MODIFIERS = frozenset({
    "different", "differently", "colored", "coloured", "color", "colour", "matching",
    "corresponding", "identical", "distinct", "various", "similar", "same", "other",
    "small", "smaller", "little", "tiny", "large", "larger", "big", "bigger", "tall",
    "short", "wooden", "plastic", "solid", "empty", "separate", "individual", "more",
    "random", "randomly", "placed", "scattered", "multicolored", "multicoloured",
})
#: Words that may stand between a plural kind word and the list of its colours that
#: counts it: "blocks (red, blue, green)", "cylinders of different colors: red, ...".
COLOUR_LIST_LEAD = frozenset({"of", "in", "with", "different", "differently", "colors",
                              "colours", "color", "colour", "colored", "coloured",
                              "various", "distinct", "the", "following", "namely"})
#: Words that never name what a count counts: "three of the blocks", "two in each
#: bowl". Any other one word between a count and a kind word is a noun used as an
#: adjective ("three insertion fixtures", "four kitting slots"), skipped like
#: :data:`MODIFIERS`.
FUNCTION_WORDS = frozenset({
    "and", "or", "of", "in", "on", "onto", "into", "to", "at", "by", "for", "from", "with",
    "the", "a", "an", "each", "every", "all", "per", "than", "then", "times", "more",
    "less", "them", "it", "is", "are", "be", "as", "so", "its", "their", "other", "next",
    "over", "under", "between", "near", "beside", "behind", "around", "inside", "top",
})
#: Most mentions listed (a proposal is a sentence or two, not an inventory).
MAX_MENTIONS = 8
#: Largest count read from a proposal (the graph model's count limit is larger).
MAX_COUNT = 16

_WORD = re.compile(r"[a-z0-9]+")


@dataclass(frozen=True)
class Mention:
    """One object the proposal names.

    Attributes:
        name: The variable name to give it (``red_block``, ``red_blocks``, ``zone``).
        kind: Its asset kind.
        color: Its colour, or None when the proposal gives none.
        count: How many (1 unless the proposal says).
        also: Other kinds the proposal's word may mean (:data:`ALSO_KINDS`).
    """

    name: str
    kind: str
    color: str | None
    count: int
    also: tuple[str, ...] = ()

    def describe(self) -> str:
        """``red_blocks: kind block, colour red, count 3``."""
        parts = [f"kind {self.kind}"]
        if self.color:
            parts.append(f"colour {self.color}")
        parts.append(f"count {self.count}")
        return f"{self.name}: {', '.join(parts)}"


def _kind_of(word: str) -> tuple[str | None, bool, str]:
    """(kind, plural, singular word) of a word, or (None, False, word)."""
    if word in KIND_WORDS:
        return KIND_WORDS[word], False, word
    for suffix in ("es", "s"):
        stem = word[: -len(suffix)]
        if word.endswith(suffix) and stem in KIND_WORDS:
            return KIND_WORDS[stem], True, stem
    return None, False, word


def _plural(stem: str) -> str:
    """``red_block`` -> ``red_blocks``, ``box`` -> ``boxes``."""
    return f"{stem}es" if stem.endswith(("s", "x", "z", "ch", "sh")) else f"{stem}s"


def mentions(proposal: str) -> list[Mention]:
    """The objects ``proposal`` names, in order, each once.

    A mention is a kind word with the colour words and the count word just
    before it: ``three red blocks``; ``red and green zones`` names a red zone and
    a green zone; ``six red and blue blocks`` three of each. A plural without a
    count counts 2 (per colour). Words of :data:`MODIFIERS` may stand between the
    count and the kind ("four differently colored blocks": 4), and one other word
    that is no function word ("three insertion fixtures": 3); a plural with no
    count followed by a list of its colours is counted by the list ("blocks (red,
    blue, green)": 3).

    A later phrase naming a kind already named refers back, it names no new
    object: an uncoloured one ("a blue sphere ... the sphere"), and a coloured one
    after an uncoloured group of that kind ("six blocks ... a red block at the
    bottom": one of the six). Read as new objects, these would be declared twice and
    every grounded goal would have to use the copy. A task name (kebab-case, before
    the description with a colon, or after it as the generator writes it) adds only
    objects whose words the description does not use: in "block-insertion: put the
    L shape block in the L shape hole" the block is the ell.

    Args:
        proposal: The task proposal (any text; only its words are read).

    Returns:
        At most :data:`MAX_MENTIONS` mentions, first occurrence first.
    """
    text = proposal.lower()[:4000]
    leading, trailing = TASK_NAME.match(text), TRAILING_NAME.match(text)
    if leading:
        desc, name = leading.group(2), leading.group(1)
    elif trailing:
        desc, name = trailing.group(1), trailing.group(2)
    else:
        desc, name = text, ""
    found: dict[str, Mention] = {}
    _scan(_words(desc), found)
    if name:
        said = {_kind_of(w)[2] for w in _WORD.findall(desc.replace("-", " "))}
        _scan([w for w in _words(name) if _kind_of(w)[2] not in said], found)
    return list(found.values())


def _words(text: str) -> list[str]:
    """The words of ``text``, with :data:`PHRASES` read as their kind words."""
    text = text.replace("_", " ").replace("-", " ")
    for pattern, kind_word in PHRASES:
        text = pattern.sub(kind_word, text)
    return _WORD.findall(text)


def _scan(words: list[str], found: dict[str, Mention]) -> None:
    """Add the mentions of ``words`` to ``found`` (see :func:`mentions`)."""
    for i, word in enumerate(words):
        if len(found) >= MAX_MENTIONS:
            return
        kind, plural, singular = _kind_of(word)
        if kind is None:
            continue
        earlier = [m for m in found.values() if m.kind == kind]
        colors: list[str] = []
        j = i - 1
        while j >= 0 and (words[j] in COLOR_NAMES or (words[j] in ("and", "or") and colors)):
            if words[j] in COLOR_NAMES:
                colors.insert(0, words[j])
            j -= 1
        if earlier and (not colors or any(m.color is None and m.count > 1
                                           for m in earlier)):
            continue  # a reference to an object already named (see above)
        while j >= 0 and words[j] in MODIFIERS:  # "four differently colored blocks"
            j -= 1
        before = words[j] if j >= 0 else ""
        total = _count_of(before)
        if not total and j >= 1 and _is_adjunct(words[j]) and _count_of(words[j - 1]):
            total = _count_of(words[j - 1])  # "three insertion fixtures"
        if not total and plural and not colors:
            total = _listed_colours(words, i + 1)  # "blocks (red, blue, green)"
        for color in colors or [None]:
            if total and len(colors) > 1:
                count = max(total // len(colors), 1)
            elif len(colors) > 1:
                count = 1  # "red and green zones": one of each
            else:
                count = total or (2 if plural else 1)
            count = min(count, MAX_COUNT)
            stem = f"{color}_{kind}" if color else kind
            name = _plural(stem) if count > 1 else stem
            if stem in found or _plural(stem) in found:
                continue
            found[name] = Mention(name, kind, color, count, ALSO_KINDS.get(singular, ()))
            if len(found) >= MAX_MENTIONS:
                return


def _count_of(word: str) -> int:
    """The count a word says (``3`` for ``three`` or ``3``), else 0."""
    return int(word) if word.isdigit() else NUMBER_WORDS.get(word, 0)


def _is_adjunct(word: str) -> bool:
    """Whether ``word`` may be a noun used as an adjective before a kind word: not a
    function word, count, colour or kind word itself."""
    return (word not in FUNCTION_WORDS and not _count_of(word) and word not in COLOR_NAMES
            and _kind_of(word)[0] is None and word.isalpha())


def _listed_colours(words: list[str], start: int) -> int:
    """How many colours the list right after a plural kind word names ("blocks of
    different colors (red, blue, green, yellow)": 4), or 0 when none follows or the
    colours are another noun's ("blocks in the red and blue bowls")."""
    k = start
    while k < len(words) and k - start < 4 and words[k] in COLOUR_LIST_LEAD:
        k += 1
    listed = 0
    while k < len(words) and (words[k] in COLOR_NAMES or (words[k] in ("and", "or")
                                                           and listed)):
        listed += words[k] in COLOR_NAMES
        k += 1
    if listed < 2 or (k < len(words) and _kind_of(words[k])[0] is not None):
        return 0
    return listed


def mentions_text(proposal: str) -> str:
    """The prompt's list of mentions, one per line (``(none recognised)`` if none)."""
    found = mentions(proposal)
    if not found:
        return "(none recognised: choose the objects yourself)"
    return "\n".join(f"- {m.describe()}" for m in found)


def missing_mentions(proposal: str, variables: Sequence[Any]) -> list[Mention]:
    """The coloured objects the proposal names that no variable is.

    Only mentions with a colour are checked ("the yellow cylinder" needs a
    yellow cylinder; "the zone" may be any zone): a colour and a kind together
    say which object is meant, and a task without it is another task.

    Args:
        proposal: The task proposal.
        variables: The answer's variables (objects with ``kind`` and ``color``).

    Returns:
        The unmatched mentions (empty: every coloured object is there).
    """
    have = {(getattr(v, "kind", None), getattr(v, "color", None)) for v in variables}
    return [m for m in mentions(proposal) if m.color
            and not any((kind, m.color) in have for kind in (m.kind, *m.also))]


def grounding_feedback(proposal: str, variables: Sequence[Any]) -> str | None:
    """Feedback naming the coloured objects of the proposal the answer lacks
    (None: none lacking)."""
    missing = missing_mentions(proposal, variables)
    if not missing:
        return None
    lines = "\n".join(f"- {m.describe()}" for m in missing)
    return ("The answer does not have every object the proposal names; add a variable "
            f"for each (with this kind and colour):\n{lines}")


__all__ = ["ALSO_KINDS", "KIND_WORDS", "MAX_MENTIONS", "Mention", "grounding_feedback", "mentions",
           "mentions_text", "missing_mentions"]
