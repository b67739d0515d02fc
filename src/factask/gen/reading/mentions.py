"""The objects a proposal names, read from its words: a hint for the model.

"put the three red blocks in the green zone" names ``red_blocks`` (3 blocks,
red) and ``green_zone`` (a green zone). The prompts of the steps that declare
variables (``one_shot``, ``variables``, ``subtask_design``) list these mentions
with the names to give them, so a model -- a small one above all, which tends to
copy names from the examples instead -- starts from the objects the proposal
asks for. It is a hint only: the schema and the verification ladder decide.

Only the vocabulary is recognised (the colours of :mod:`factask.vocabulary.palette`,
the asset kinds of :mod:`factask.vocabulary.kinds` and a few synonyms), so a mention
is always something the graph model can express.

Why one file (past 500 lines): it is one reader of one word list -- the scan,
the counts, the colour lists, the matching phrases and the moving verbs each
look at the words around the same kind word, with the same tables.
"""

from __future__ import annotations

import re
from collections.abc import Collection, Sequence
from dataclasses import dataclass, replace
from typing import Any

from factask.gen.reading.grades import grade_members
from factask.gen.reading.group_counts import (
    MAX_COUNT,
    MAX_SPLIT_MENTIONS,
    count_each,
    count_in_total,
    list_free_colours,
    recount,
    split_per_shape,
)
from factask.gen.reading.selectors import distribute, rest_of_kind, select_members
from factask.gen.reading.sequences import sequence_members
from factask.gen.reading.words import (
    DECK_SIZE,
    DECK_WORDS,
    MODIFIERS,
    NUMBER_WORDS,
    OBJECT_LEAD,
    WORD,
    count_of,
    kind_of,
    plural_of,
    words_of,
)
from factask.vocabulary.kinds import ASSET_KINDS, kind_spec
from factask.vocabulary.palette import COLOR_NAMES

#: Other kinds an everyday word may as well mean: a graph whose coloured object is
#: one of these is still the proposal's ("the red basket" may be a red bowl). The
#: grounded answers use the word's kind in :data:`KIND_WORDS`.
ALSO_KINDS: dict[str, tuple[str, ...]] = {
    "cube": ("box",), "brick": ("box",), "crate": ("container",), "carton": ("container",),
    "package": ("block",), "parcel": ("block",), "basket": ("bowl",), "bucket": ("bowl",),
    "bin": ("bowl",), "tray": ("bowl", "kit"), "dish": ("container",), "pot": ("container",),
    "cup": ("container",), "platform": ("stand",), "plate": ("pallet", "zone", "kit"),
    "board": ("pallet",), "peg": ("block",), "rod": ("block",),
    # a stand objects go into upright is a fixture, one they rest on a pallet
    "stand": ("fixture", "pallet"),
    "object": ("box", "cylinder", "ball", "ell"), "item": ("box", "cylinder", "ball", "ell"),
    "piece": ("box", "cylinder", "ball", "ell"), "shape": ("box", "cylinder", "ball", "ell"),
    "hole": ("kit", "container"), "slot": ("kit",), "silhouette": ("kit",), "area": ("pallet",),
}
#: A proposal that starts with a task name: ``kebab-case-name: description``.
TASK_NAME = re.compile(r"^\s*([a-z0-9]+(?:-[a-z0-9]+)+)\s*:\s*(.*)$", re.DOTALL)
#: A proposal that ends with a task name, as the generator reads one: ``description name``.
TRAILING_NAME = re.compile(r"^(.*\S)\s+([a-z0-9]+(?:-[a-z0-9]+)+)\s*$", re.DOTALL)

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
#: Verbs that move their object: "put the bowl in the zone" moves the bowl, which
#: is fixed by default (:attr:`Mention.moved`).
MOVE_VERBS = frozenset({
    "put", "place", "move", "push", "slide", "carry", "stack", "insert", "drop",
    "transfer", "bring", "set", "lift", "pick", "arrange", "position", "relocate",
    "shift", "take", "lay", "deliver", "rearrange", "align", "pack", "load", "drag",
    "swap", "nest", "raise", "stand", "line",
})
#: Kinds fixed by default that the robot can still carry (not flat markers).
CARRIED_KINDS = frozenset(k for k, spec in ASSET_KINDS.items()
                          if not spec.movable and spec.collides)
#: Words that fix an object of a kind that moves by default, just before its colour or
#: kind word: "the three fixed gray boxes" (an obstacle bolted to the table).
PINNED_WORDS = frozenset({"fixed", "immovable", "static", "bolted", "stationary"})
#: Most mentions listed (a proposal is a sentence or two, not an inventory; six balls
#: into six zones is twelve, the most variables a graph schema takes).
MAX_MENTIONS = 12
#: Words of colour, qualified by a matching word in a matching phrase.
COLOUR_WORDS = frozenset({"color", "colour", "colors", "colours", "colored", "coloured"})
#: Words before a colour word that pair by colour: "of the same colour", "matching
#: colored", "its colour", "sort by colour".
MATCH_BEFORE = frozenset({"same", "matching", "matched", "corresponding", "correspondingly",
                          "its", "their", "own", "respective", "by", "identical",
                          "similar", "similarly"})
#: Words after a colour word that do: "colour-coordinated", "colour-matched", "color
#: coded", "colored correspondingly".
MATCH_AFTER = frozenset({"coordinated", "matched", "matching", "corresponding",
                         "correspondingly", "coded"})
#: How many words back a matching phrase looks for the kind it qualifies ("the
#: containers of the matching color": 4).
MATCH_REACH = 6


@dataclass(frozen=True)
class Mention:
    """One object the proposal names.

    Attributes:
        name: The variable name to give it (``red_block``, ``red_blocks``, ``zone``).
        kind: Its asset kind.
        color: Its colour, or None when the proposal gives none.
        count: How many (1 unless the proposal says).
        also: Other kinds the proposal's word may mean (:data:`ALSO_KINDS`).
        moved: The words move an object whose kind is fixed by default ("then put
            the bowl in the green zone": the bowl is carried, :data:`MOVE_VERBS`).
        counted: The words give its count ("three red blocks", "there are three of
            each"); a plural without one is counted 2.
        size: Its size where the goals the words state need more room than the
            kind's default gives (:func:`factask.gen.reading.stated_goals.fit_sizes`);
            None: the default.
        listed: The colours listed right after an uncoloured group ("blocks of
            different colors (red, blue, green)"), each with its count where the
            list gives one ("(two red, two blue)"; 0: not given).
        pinned: The words fix an object whose kind moves by default ("the three
            fixed gray boxes": obstacles, :data:`PINNED_WORDS`).
        group: The group this object is one member of, where the words pick members
            ("the second zone": :mod:`factask.gen.reading.selectors`); None: none.
        selectors: The words that pick this member ("second", "left").
        rank: Its place in its group's row (0: first, at the left or nearest).
        axis: The row's axis for a fixed group ("y": left to right, "x": near to
            far); None: not placed.
        place: Where it stands on the table (x, y), for a member of a placed row.
        grade: Its size among alike objects the words tell apart by size ("small",
            "large", "tall", "short", "long": :mod:`factask.gen.reading.grades`);
            None: not graded.
        start: Its start as the words fix it, (field, value) pairs (a drawer's level:
            :mod:`factask.gen.reading.parts`).
    """

    name: str
    kind: str
    color: str | None
    count: int
    also: tuple[str, ...] = ()
    listed: tuple[tuple[str, int], ...] = ()
    moved: bool = False
    counted: bool = False
    size: tuple[float, float, float] | None = None
    pinned: bool = False
    group: str | None = None
    selectors: tuple[str, ...] = ()
    rank: int = 0
    axis: str | None = None
    place: tuple[float, float] | None = None
    grade: str | None = None
    start: tuple[tuple[str, Any], ...] = ()

    def describe(self) -> str:
        """``red_blocks: kind block, colour red, count 3`` (``, moved`` for a bowl or
        pallet the words move)."""
        parts = [f"kind {self.kind}"]
        if self.color:
            parts.append(f"colour {self.color}")
        parts.append(f"count {self.count}")
        if self.moved:
            parts.append("moved (not fixed)")
        if self.pinned:
            parts.append("fixed (not moved)")
        if self.grade:
            parts.append(f"the {self.grade} one of its kind")
        if self.group:
            parts.append(f"{' / '.join(self.selectors) or 'member'} of {self.group}")
        if self.place:
            parts.append(f"at x {self.place[0]:g} m, y {self.place[1]:g} m")
        parts += [f"starts {dict(self.start)}"] if self.start else []
        return f"{self.name}: {', '.join(parts)}"

    def as_variable(self, initial: dict[str, Any] | None = None,
                    unnamed: str = "gray") -> dict[str, Any]:
        """The object as a graph variable's data (size null: the kind's default;
        ``fixed`` false where the words move a kind that is fixed by default;
        ``unnamed``: its colour where the words give none, see :func:`unnamed_colour`)."""
        out: dict[str, Any] = {"name": self.name, "description": self.describe(),
                               "kind": self.kind,
                               "size": list(self.size) if self.size else None,
                               "color": self.color or unnamed, "count": self.count,
                               "initial": dict(self.start) or initial or self._placed()}
        if self.moved:
            out["fixed"] = False
        if self.pinned:
            out["fixed"] = True
        return out

    def _placed(self) -> dict[str, Any]:
        if self.place is None:
            return {"type": "table"}
        return {"type": "pose", "x": self.place[0], "y": self.place[1], "yaw_deg": 0.0}

    @property
    def movable(self) -> bool:
        """Whether the robot moves it: its kind moves, or the words move it."""
        return self.moved or (kind_spec(self.kind).movable and not self.pinned)


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
    words = words_of(desc)
    _scan(words, found)
    count_each(words, found)
    count_in_total(words, found)
    split_per_shape(words, found)
    if name:
        said = {kind_of(w)[2] for w in WORD.findall(desc.replace("-", " "))}
        _scan([w for w in words_of(name) if kind_of(w)[2] not in said], found)
    matched = _matched_kinds(words)
    if matched is not None or colour_matched(desc) or colour_matched(name):
        list_free_colours(words, found)
    else:
        list_free_colours(words, found, ordered=True)
    out = list(found.values())
    if matched is not None or colour_matched(name) or any(m.listed for m in found.values()):
        # A group whose colours the words list ("blocks of different colours (red,
        # blue, green)") is one object per colour, paired by colour or not.
        out = _split_by_colour(out, matched or set())
    out = grade_members(desc, out, MAX_SPLIT_MENTIONS)  # "the small ball ... the large ball"
    out = sequence_members(desc, out, MAX_SPLIT_MENTIONS)  # "in alternating colours"
    out = select_members(desc, out, MAX_SPLIT_MENTIONS)  # "the second zone": its members
    out = distribute(desc, out, MAX_SPLIT_MENTIONS)  # "in each zone": a share each
    from factask.gen.reading.parts import seat_parts  # parts reads Mention: no cycle
    return seat_parts(words, out, MAX_SPLIT_MENTIONS)  # "the top drawer": a drawer of three


def colour_matched(text: str) -> bool:
    """Whether ``text`` pairs objects by colour: "the bowl of the same colour",
    "zones correspondingly colored", "colour-coordinated", "sort by colour"."""
    return _matched_kinds(WORD.findall(text.lower().replace("-", " ").replace("_", " "))) \
        is not None


def _matching_at(words: list[str], k: int) -> bool:
    """Whether ``words[k]`` is a colour word that a matching word qualifies."""
    if words[k] not in COLOUR_WORDS:
        return False
    before = words[k - 1] if k else ""
    after = words[k + 1] if k + 1 < len(words) else ""
    return before in MATCH_BEFORE or after in MATCH_AFTER


def _matched_kinds(words: list[str]) -> set[str] | None:
    """The kinds whose objects a matching phrase gives the colours of the others
    ("containers of matching color": container), or None when no phrase pairs by
    colour. The phrase qualifies the nearest kind word before it (at most
    :data:`MATCH_REACH` words back), else the one right after it ("the matching
    colored zone")."""
    out: set[str] | None = None
    for k in range(len(words)):
        if not _matching_at(words, k):
            continue
        out = out if out is not None else set()
        for j in [*range(k - 1, max(k - 1 - MATCH_REACH, -1), -1), k + 1, k + 2]:
            if 0 <= j < len(words) and (kind := kind_of(words[j])[0]) is not None:
                out.add(kind)
                break
    return out


def _split_by_colour(found: list[Mention], matched: set[str]) -> list[Mention]:
    """Under a matching phrase, groups become one object per colour: a group
    whose colours the words list ("balls of different colors (red, blue)") by its
    list, and an uncoloured group of a kind the phrase qualifies ("zones
    correspondingly colored") by the colours named for the others (their
    lists and coloured objects, in order). A group keeps its count spread over
    its colours; one named with fewer objects than colours ("the bowl of the
    same colour") gets one per colour. Nothing is split past
    :data:`MAX_SPLIT_MENTIONS` mentions. An uncoloured object of a kind that
    coloured ones also have is their group ("each ball ... a red ball, a green
    ball"), not one more."""
    palette: list[str] = []
    for m in found:
        for c in ([c for c, _ in m.listed] or ([m.color] if m.color else [])):
            if c not in palette:
                palette.append(c)
    out: list[Mention] = []
    names = {m.name for m in found}
    for idx, m in enumerate(found):
        parts = _colour_parts(m, palette, matched)
        fresh = [p for p in parts if not _named(f"{p.color}_{p.kind}", names)]
        rest = len(found) - idx - 1
        if not parts or len(fresh) != len(parts) or \
                len(out) + len(parts) + rest > MAX_SPLIT_MENTIONS:
            out.append(m)
            continue
        out.extend(parts)
        names.update(p.name for p in parts)
    # "each ball ... a red ball, a green ball": the coloured ones are its members.
    coloured = {m.kind for m in out if m.color}
    return [m for m in out if m.color or m.kind not in coloured]


def _colour_parts(m: Mention, palette: list[str], matched: set[str]) -> list[Mention]:
    """One mention per colour of ``m`` (see :func:`_split_by_colour`), or [] to keep it."""
    if m.color is not None:
        return []
    if m.listed:
        colours = [c for c, _ in m.listed]
        counts = [n or max(m.count // len(colours), 1) for _, n in m.listed]
    elif palette and (m.kind in matched or m.count == len(palette) > 1):
        # A group the phrase qualifies, or one as large as the palette ("four
        # spheres and four boxes of different colors (...)": the list is both's).
        colours = palette
        if m.count < len(colours):
            counts = [1] * len(colours)
        elif m.count % len(colours) == 0:
            counts = [m.count // len(colours)] * len(colours)
        else:
            return []
    else:
        return []
    out = []
    for colour, count in zip(colours, counts, strict=True):
        stem = f"{colour}_{m.kind}"
        out.append(Mention(plural_of(stem) if count > 1 else stem, m.kind, colour,
                           min(count, MAX_COUNT), m.also, moved=m.moved, pinned=m.pinned))
    return out


def _scan(words: list[str], found: dict[str, Mention]) -> None:
    """Add the mentions of ``words`` to ``found`` (see :func:`mentions`)."""
    for i, word in enumerate(words):
        if len(found) >= MAX_MENTIONS:
            return
        kind, plural, singular = kind_of(word)
        if kind is None:
            continue
        earlier = [m for m in found.values() if m.kind == kind]
        colors: list[str] = []
        own_counts: dict[str, int] = {}  # "three red, three blue and three green blocks"
        j = i - 1
        while j >= 0 and (words[j] in COLOR_NAMES or (words[j] in ("and", "or") and colors)):
            if words[j] in COLOR_NAMES:
                colors.insert(0, words[j])
                if j >= 2 and count_of(words[j - 1]) and (
                        words[j - 2] in ("and", "or") or words[j - 2] in COLOR_NAMES):
                    own_counts[words[j]] = count_of(words[j - 1])
                    j -= 1
            j -= 1
        moved = kind in CARRIED_KINDS and _moved_at(words, j)
        pinned = kind_spec(kind).movable and bool(PINNED_WORDS & set(words[max(j - 1, 0):j + 1]))
        others = rest_of_kind(words, i, earlier) if plural and not colors else None
        if others is not None:  # "the two other cylinders", "one of the four balls"
            count, colour = others
            stem = f"other_{colour}_{kind}" if colour else f"other_{kind}"
            name = plural_of(stem) if count > 1 else stem
            if name not in found:
                found[name] = Mention(name, kind, colour, count, ALSO_KINDS.get(singular, ()),
                                      moved=moved, counted=True, group=f"{kind}_group",
                                      selectors=("other",))
            continue
        if earlier and (not colors or any(m.color is None and m.count > 1
                                           for m in earlier)):
            stated = _stated_count(words, j)
            alone = [m for m in earlier if m.color is None]
            if not colors and stated > 1 and len(alone) == 1 and not alone[0].counted:
                recount(found, alone[0].name, stated)  # "a block ... there are three blocks"
                earlier = [found[n] for n in found if found[n].kind == kind]
            if moved:  # "... then put the bowl in the green zone"
                for m in earlier:
                    if not colors or m.color in colors:
                        found[m.name] = replace(m, moved=True)
            continue  # a reference to an object already named (see above)
        while j >= 0 and words[j] in MODIFIERS:  # "four differently colored blocks"
            j -= 1
        before = words[j] if j >= 0 else ""
        total = count_of(before)
        if not total and j >= 1 and _is_adjunct(words[j]) and count_of(words[j - 1]):
            total = count_of(words[j - 1])  # "three insertion fixtures"
        listed: tuple[tuple[str, int], ...] = ()
        if plural and not colors:
            listed = _listed_colours(words, i + 1)  # "blocks (red, blue, green)"
            if not total and listed:
                total = sum(n for _, n in listed) if all(n for _, n in listed) \
                    else len(listed)
        if own_counts and len(own_counts) == len(colors) - 1:
            # The first colour's count is the one read before the list.
            own_counts.update({c: total or 1 for c in colors if c not in own_counts})
        for color in colors or [None]:
            if color in own_counts and len(own_counts) == len(colors):
                count = own_counts[color]
            elif total and len(colors) > 1:
                count = max(total // len(colors), 1)
            elif len(colors) > 1:
                count = 1  # "red and green zones": one of each
            else:
                count = total or (2 if plural else 1)
            count = min(count, MAX_COUNT)
            stem = f"{color}_{kind}" if color else kind
            name = plural_of(stem) if count > 1 else stem
            counted = bool(total) or color in own_counts
            if _named(stem, found):
                again = stem if stem in found else plural_of(stem)
                if moved:
                    found[again] = replace(found[again], moved=True)
                if pinned:
                    found[again] = replace(found[again], pinned=True)
                if counted and not found[again].counted:
                    recount(found, again, count)  # "... there are five yellow balls"
                continue
            found[name] = Mention(name, kind, color, count, ALSO_KINDS.get(singular, ()),
                                  listed, moved, counted, pinned=pinned,
                                  size=DECK_SIZE if singular in DECK_WORDS else None)
            if len(found) >= MAX_MENTIONS:
                return


#: Words that state how many objects there are: "there are three blocks", "... and
#: three blocks" in that list.
_EXISTENTIAL = frozenset({"are", "is", "has", "have", "with"})


def _stated_count(words: list[str], j: int) -> int:
    """The count an existential phrase ending at ``words[j]`` states ("there are three
    cylinders and three blocks": 3 for either), else 0."""
    while j >= 0 and words[j] in MODIFIERS:
        j -= 1
    if j < 0 or not count_of(words[j]) or words[j] in ("a", "an", "one"):
        return 0
    return count_of(words[j]) if _EXISTENTIAL & set(words[max(0, j - 6):j]) else 0


def _named(stem: str, names: Collection[str]) -> bool:  # named already, one or many
    return stem in names or plural_of(stem) in names


def _moved_at(words: list[str], j: int) -> bool:
    """Whether a moving verb (:data:`MOVE_VERBS`) governs the object phrase that ends
    at ``words[j]`` (its colour words already read): "put the ...", "pick up two ..."."""
    k = j
    while k >= 0 and j - k < 6 and (words[k] in OBJECT_LEAD or words[k] in MODIFIERS
                                    or words[k] in COLOR_NAMES or count_of(words[k])):
        k -= 1
    return k >= 0 and words[k] in MOVE_VERBS


def _is_adjunct(word: str) -> bool:
    """Whether ``word`` may be a noun used as an adjective before a kind word: not a
    function word, count, colour or kind word itself."""
    return (word not in FUNCTION_WORDS and not count_of(word) and word not in COLOR_NAMES
            and kind_of(word)[0] is None and word.isalpha())


def _listed_colours(words: list[str], start: int) -> tuple[tuple[str, int], ...]:
    """The colours the list right after a plural kind word names, each with the
    count before it where the list gives one ("blocks of different colors (red,
    blue, green, yellow)": four colours, counts 0; "blocks in two colours (three red
    and three blue)": red 3, blue 3), or () when none follows or the colours are
    another noun's ("blocks in the red and blue bowls")."""
    k = start
    while k < len(words) and k - start < 4 and (words[k] in COLOUR_LIST_LEAD
                                                 or words[k] in NUMBER_WORDS
                                                 or words[k].isdigit()):
        if count_of(words[k]) and k + 1 < len(words) and words[k + 1] in COLOR_NAMES:
            break  # "(three red and three blue)": the list starts at its first count
        k += 1
    listed: list[tuple[str, int]] = []
    while k < len(words):
        if words[k] in COLOR_NAMES:
            listed.append((words[k], 0))
        elif count_of(words[k]) and k + 1 < len(words) and words[k + 1] in COLOR_NAMES:
            listed.append((words[k + 1], min(count_of(words[k]), MAX_COUNT)))
            k += 1
        elif not (words[k] in ("and", "or") and listed):
            break
        k += 1
    if len(listed) < 2 or (k < len(words) and kind_of(words[k])[0] is not None):
        return ()
    if len({c for c, _ in listed}) < len(listed):
        return ()
    return tuple(listed)


def mentions_text(proposal: str) -> str:
    """The prompt's list of mentions, one per line (``(none recognised)`` if none)."""
    found = mentions(proposal)
    if not found:
        return "(none recognised: choose the objects yourself)"
    return "\n".join(f"- {m.describe()}" for m in found)


#: Colours for an object the words give none, the first that no named object has.
NEUTRAL_COLOURS = ("gray", "white", "brown", "black")


def unnamed_colour(found: Sequence[Mention]) -> str:
    """The colour an uncoloured named object gets: not one the words give another
    object ("the grey cylinders into the container": a grey container would be taken
    for one of the grey things the words name)."""
    named = {m.color for m in found} | {c for m in found for c, _ in m.listed}
    return next((c for c in NEUTRAL_COLOURS if c not in named), NEUTRAL_COLOURS[0])


def missing_mentions(proposal: str, variables: Sequence[Any]) -> list[Mention]:
    """The coloured objects the proposal names that no variable is.

    Only mentions with a colour are checked ("the yellow cylinder" needs a
    yellow object that moves as a cylinder does; "the zone" may be any zone): the
    colour says which object is meant, and a task without it is another task; the
    kind word is matched loosely (:func:`_alike_kinds`).

    Args:
        proposal: The task proposal.
        variables: The answer's variables (objects with ``kind`` and ``color``).

    Returns:
        The unmatched mentions (empty: every coloured object is there).
    """
    have = {(getattr(v, "kind", None), getattr(v, "color", None)) for v in variables}
    return [m for m in mentions(proposal) if m.color
            and not any((kind, m.color) in have for kind in _alike_kinds(m))]


def _alike_kinds(m: Mention) -> list[str]:
    """The kinds a variable may have and still be the object ``m`` names: its kind,
    what its word may also mean, and any kind of the same sort (moves or stays by
    default, solid or a marker, holds objects inside or not). A kind word is the
    reading's guess ("cylinders" aligned with a hole lie down as logs, "boxes with a
    slot" are fixtures): the colour and the sort are what the words pin, so a capable
    model's other kind of that sort is not sent back as a missing object (the meaning
    metric still judges it); a zone is never a basket."""
    def sort(kind: str) -> tuple[bool, bool, bool]:
        spec = kind_spec(kind)
        return spec.movable, spec.collides, spec.receptacle

    return [m.kind, *m.also, *(k for k in ASSET_KINDS if sort(k) == sort(m.kind))]


def grounding_feedback(proposal: str, variables: Sequence[Any]) -> str | None:
    """Feedback naming the coloured objects of the proposal the answer lacks
    (None: none lacking)."""
    missing = missing_mentions(proposal, variables)
    if not missing:
        return None
    lines = "\n".join(f"- {m.describe()}" for m in missing)
    return ("The answer does not have every object the proposal names; add a variable "
            f"for each (with this kind and colour):\n{lines}")


__all__ = ["ALSO_KINDS", "MAX_MENTIONS", "MAX_SPLIT_MENTIONS", "PINNED_WORDS", "Mention",
           "colour_matched", "grounding_feedback", "mentions",
           "mentions_text", "missing_mentions", "unnamed_colour"]
