"""The goals a proposal states, read clause by clause: which object goes where, how.

:mod:`factask.gen.reading.mentions` finds the objects a proposal names; this module
reads what the words do with them. A proposal is cut into **parts** (sentences, and
the steps that "then", "after that", "next" or "finally" begin); in each part the
words are read left to right:

* a phrase naming objects (``the red blocks``, ``them``) with no preposition before
  it names objects to **move**;
* a preposition before such a phrase (``in``, ``into``, ``on``, ``on top of``,
  ``along``, ``around``) makes it the **anchor** of the objects named since the last
  anchor: "put the blue blocks in the blue bowl and the green blocks in the green
  bowl" is two goals;
* **shape words** (tower, stack, pyramid / row, line, side by side / circle, ring,
  around) make the objects named near them one arrangement -- one per group where
  the words say so ("two towers", "into another") -- with the anchor as its base,
  line or centre;
* the relation of an anchored goal follows the anchor's kind: a zone ``in_zone``
  (``pile_in_zone`` for a pile), a bowl or container ``inside``, a fixture, kit or
  hole ``aligned``, a pallet, stand or another object ``on``; a rope lies
  ``rope_along`` a line;
* the order of a stack or row of differently coloured objects is the order the
  words give their colours, where they say an order ("in this sequence", "from the
  bottom", "followed by", "in that order"); the goals of a part that "then"
  begins come after those of the parts before.

A reading is returned only when every named object is used by some goal and every
goal is one the relation can hold; otherwise there is none (None), and the grammar
offers the model the shapes of :mod:`factask.gen.reading.cover` instead. What the
reading could not account for is :mod:`factask.gen.reading.accounting`'s to say.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from functools import lru_cache

from factask.gen.reading.goal_order import (
    bridged,
    in_colour_sequence,
    in_member_sequence,
    layered,
    stacked_in_order,
)
from factask.gen.reading.grades import pick_graded
from factask.gen.reading.mentions import MATCH_AFTER, MOVE_VERBS, Mention
from factask.gen.reading.orders import PLACES, ordered_by_words
from factask.gen.reading.part_order import sequence_parts
from factask.gen.reading.parts import (
    LEVEL_WORDS,
    PART_KINDS,
    Phrase,
    acted,
    acts_on_pronoun,
    actuation,
    bare_inside,
    containers_of,
    part_referents,
    parts_named_by,
    phrase_at,
    said_as,
    still_parts,
)
from factask.gen.reading.read_goal import ReadGoal
from factask.gen.reading.selectors import is_selector, selector_before, spell_out, unpicked
from factask.gen.reading.words import count_of, kind_of, passive_scene, resolve_ones, words_of
from factask.vocabulary.kinds import kind_spec
from factask.vocabulary.palette import COLOR_NAMES

#: Where a proposal passes from one part to the next; the second group says the next
#: part comes after (a sequence word), not only beside it.
_SPLIT = re.compile(r"([.;!?])|(,?\s+(?:and\s+)?(?:then|after\s+that|afterwards|"
                    r"next(?!\s+to\b)|finally|lastly|once\s+done)\b,?)")
#: Verbs of an action: a part after "then" without one goes on the list before it.
ACTION_VERBS = MOVE_VERBS | frozenset({
    "build", "make", "form", "create", "construct", "repeat", "do", "sweep", "fill",
    "cover", "rest", "use", "complete", "finish", "sort", "group", "surround",
    "encircle", "balance", "assemble", "organize", "organise", "gather", "collect",
    "return", "hang", "fit", "slot", "center", "centre", "attach", "connect", "lean",
    "standup", "lineup"})
#: Verbs that keep an object where it is: what they govern gets no goal of its own.
STILL_VERBS = frozenset({"leave", "keep", "ignore", "avoid", "skip", "remain", "stay",
                         "stays", "remains", "untouched", "keeping", "leaving", "ignoring"})
#: Verbs that say how things are, not what to do: "the ball is in the left bowl".
STATE_VERBS = frozenset({"is", "are", "sits", "sit", "lies", "lie", "starts", "start",
                         "holds", "hold", "rests", "contains", "standing", "was", "were"})
#: Words that begin a part that comes first: "first put ...".
_FIRST = frozenset({"first", "firstly", "start"})
#: Prepositions that make the phrase after them an anchor, by the relation they ask.
PREPOSITIONS: dict[str, str] = {
    "in": "in", "into": "in", "inside": "in", "within": "in", "to": "in",
    "on": "on", "onto": "on", "atop": "on", "upon": "on", "over": "on", "across": "on",
    "along": "along", "around": "around", "encircling": "around", "surrounding": "around",
    "beside": "beside", "next": "beside", "alongside": "beside",
    "between": "between",
}
#: Words that may stand between a preposition and the kind word it governs (the
#: matching words too: "into four color-coded fixtures", "the colour-matched bowls").
_LEAD = frozenset({"the", "a", "an", "its", "their", "each", "every", "one", "own", "this",
                   "that", "these", "those", "top", "of", "both", "all", "same", "matching",
                   "corresponding", "respective", "other", "another", "colored", "coloured",
                   "color", "colour", "large", "small", "big", "little", "tiny", "larger",
                   "smaller", "square", "round", "brown", "marked", "target", "specified",
                   "designated", "empty", "open", "flat", "tall", "short", "wooden",
                   "middle", "center", "centre", "different", "separate"}) | MATCH_AFTER \
    | LEVEL_WORDS.keys() | {w for p in PART_KINDS.values() if not p.states_after
                           for w in p.states}
#: Words that refer back to the objects moved last.
PRONOUNS = frozenset({"them", "they", "it", "those", "these", "both"})
#: Shape words: the arrangement they name.
SHAPES: dict[str, str] = {
    "tower": "stack", "towers": "stack", "stack": "stack", "stacks": "stack",
    "stacked": "stack", "stacking": "stack", "pyramid": "stack", "column": "stack",
    "columns": "stack",
    "row": "row", "rows": "row", "line": "row",
    "circle": "circle", "circles": "circle", "ring": "circle", "rings": "circle",
    "circular": "circle",
}
#: Shape words that name several arrangements, one per group of objects.
PLURAL_SHAPES = frozenset({"towers", "stacks", "rows", "circles", "rings", "columns"})
#: Words that say a group goes into an arrangement of its own ("and the yellow ones into
#: another", "two separate stacks").
SEPARATE = frozenset({"another", "separate", "two", "three", "four", "each", "own"})
#: Phrases that name a shape with words of relation: "side by side", "on top of each other".
_SHAPE_PHRASES = (
    (re.compile(r"\bside\s+by\s+side\b|\bnext\s+to\s+each\s+other\b|\bin\s+a\s+row\b"),
     " row "),
    (re.compile(r"\bon\s+(?:top\s+of\s+)?(?:each\s+other|one\s+another)\b"), " stacked "),
)


@dataclass
class _Part:
    words: list[str]
    step: int
    goals: list[ReadGoal] = field(default_factory=list)


#: "Before you put A, place B": B's clause comes first.
_BEFORE = re.compile(r"(^|[.;!?]\s*)before\s+([^,.;!?]+),\s*([^.;!?]+)")


#: "Fill the bowl with the balls": the balls go into the bowl.
_FILL = re.compile(r"\b(?:fill|load)\s+((?:the|a|an|each|every)\s+[^,.;!?]*?)\s+with\s+"
                   r"([^,.;!?]+)")


def parts_of(proposal: str) -> list[tuple[str, int]]:
    """The proposal's parts, each with its step (raised by each sequence word)."""
    text = _BEFORE.sub(r"\1\3, then \2", proposal.lower())
    text = _FILL.sub(r"put \2 into \1", text)
    for pattern, repl in _SHAPE_PHRASES:
        text = pattern.sub(repl, text)
    out: list[tuple[str, int]] = []
    step, pos, sequenced = 0, 0, False
    for match in [*_SPLIT.finditer(text), None]:
        end = match.start() if match else len(text)
        piece = text[pos:end]
        if sequenced and out and not (ACTION_VERBS | SHAPES.keys()) & set(words_of(piece)) \
                and not acted(words_of(piece)):
            # "..., followed by a green cylinder, then a red one": a list goes on, no step
            out[-1] = (f"{out[-1][0]}, {piece}", out[-1][1])
        elif piece.strip():
            out.append((piece, step + (1 if sequenced and out else 0)))
            step = out[-1][1]
        if match is None:
            break
        sequenced = bool(match.group(2))
        pos = match.end()
    return out


def _referents(words: list[str], i: int, found: Sequence[Mention]) -> list[Mention]:
    """The mentions the kind word ``words[i]`` names: those of its kind (or a kind it
    may also mean) with the colours just before it, or every one of its kind."""
    kind = kind_of(words[i])[0]
    if kind in PART_KINDS:
        return part_referents(words, i, found)  # "the top drawer": by its level
    colours: list[str] = []
    j = i - 1
    while j >= 0 and (words[j] in COLOR_NAMES or (words[j] in ("and", "or", "then")
                                                   and colours) or (
            colours and count_of(words[j]) and j and words[j - 1] in ("and", "or"))):
        # "three blue and three yellow blocks": both colours, each with its count
        if words[j] in COLOR_NAMES:
            colours.append(words[j])
        j -= 1
    same = [m for m in found if m.kind == kind]
    if not same:
        same = [m for m in found if kind in m.also]
    if colours:
        same = [m for m in same if m.color in colours]
    selector = selector_before(words, i)
    graded = pick_graded(words, i, same, selector in ("other", "another"))
    if graded is not None:
        return graded  # "the small ball", "the other box" after "the small box"
    if kind_of(words[i])[1] and selector not in ("one", "other"):
        selector = None  # "the left zones": not one member ("one of the zones", "the
        # other boxes" are)
    picked = [m for m in same if selector in m.selectors]
    if not picked and selector is None and not kind_of(words[i])[1]:
        # "a brown box ... another brown box": the one named first, not another
        picked = [m for m in same if "one" in m.selectors and any(
            "another" in o.selectors for o in same if o.group == m.group)]
    # "the second zone": that member; "the zones", "a zone": the group, all its members.
    return picked or [m for m in same if not m.selectors or m.group is None
                      or selector is None]


def _anchor_prep(words: list[str], i: int) -> str | None:
    """The preposition that governs the phrase ending at ``words[i]`` (a kind word), if any."""
    j = i - 1
    while j >= 0 and (words[j] in _LEAD or words[j] in COLOR_NAMES or count_of(words[j])
                      or is_selector(words[j])):  # "into the second zone"
        j -= 1
    if j >= 1 and words[j] == "to" and words[j - 1] in ("next", "close"):
        return "beside"  # "next to the blue block"
    if j >= 1 and words[j] == "with" and _ALIGN_VERBS & set(words[:j]):
        return "in"  # "align the red ell with the red fixture": the fixture is the anchor
    return PREPOSITIONS.get(words[j]) if j >= 0 else None


#: Verbs after which "with" names the anchor ("align the ell with the fixture"), not a
#: companion ("fill the bowl with blocks").
_ALIGN_VERBS = frozenset({"align", "aligned", "aligning", "aligns"})


def _relation(prep: str, anchor: Mention, movers: Sequence[Mention], shape: str | None,
              verbs: set[str]) -> str | None:
    """The relation of a goal moving ``movers`` with this anchor."""
    kind = anchor.kind
    spec = kind_spec(kind)
    if all(m.kind == "rope" for m in movers):
        return "rope_along" if kind == "line" else None
    if shape is not None:
        return shape
    if all(m.kind == "pile" for m in movers):
        return "pile_in_zone" if kind == "zone" else None
    if prep == "beside":
        return "row" if anchor.movable else None  # "the red block next to the blue one"
    if prep == "between":
        # "between the two grey zones": in a row that runs from one to the other
        return "row" if anchor.count == 2 and not anchor.movable else None
    if kind == "zone":
        return "in_zone"
    # Into a fixture or a kit: shape into its place; "on the kitting plate": on it.
    if kind == "fixture" or (kind == "kit" and prep != "on") or (
            verbs & ({"insert", "fit"} | _ALIGN_VERBS) and kind != "container"):
        return "aligned"
    if prep == "along":
        return "row"
    if prep == "around":
        return "circle"
    if kind == "corner":
        return "aligned"  # "into the green corner": corner to corner
    if spec.receptacle and (prep == "in" or not spec.support):
        return "inside"
    if spec.support or anchor.movable:
        return "on"
    return None


def _shape_of(words: list[str], lo: int, hi: int) -> list[tuple[int, str, bool]]:
    """The shape words in ``words[lo:hi]``: (position, relation, plural)."""
    out = []
    for k in range(lo, hi):
        w = words[k]
        if w in SHAPES:
            out.append((k, SHAPES[w], w in PLURAL_SHAPES))
    return out


def read_goals(proposal: str, found: Sequence[Mention]) -> list[ReadGoal] | None:
    """The goals the proposal's words state over its mentions, or None.

    Args:
        proposal: The proposal (its description).
        found: Its mentions (:func:`factask.gen.reading.mentions.mentions`).

    Returns:
        The goals, in the words' order, each with its step; None when the words name
        no goal, or the goals leave a named object unused (but those the words keep
        still: :func:`still_objects`), or one has no relation.
    """
    read = _read(proposal, tuple(found))
    return list(read[0]) if read is not None else None


def still_objects(proposal: str, found: Sequence[Mention]) -> frozenset[str]:
    """The named objects the words keep where they are and give no goal: "leave the
    blue cylinder where it is", "ignore the black block", "not on the blue one",
    "the three blue blocks are only distractors", "take the ball out of the bowl".

    Args:
        proposal: The proposal (its description).
        found: Its mentions.

    Returns:
        Their names (empty where the words state no goals).
    """
    read = _read(proposal, tuple(found))
    return read[1] if read is not None else frozenset()


#: Words that keep what follows them still, until the next action: "do not move", "without".
NEGATIONS = frozenset({"not", "don", "dont", "never", "without", "except", "nor", "neither",
                       "distractor", "distractors", "keeping"})
#: Prepositions of where an object comes from: it is no anchor of a goal.
SOURCES = frozenset({"from", "out"})
#: Words that end a negation's reach: "..., just put the yellow block in the zone".
_POSITIVE = frozenset({"just", "only", "instead", "rather", "but", "then"})


@lru_cache(maxsize=256)
def _read(proposal: str, found: tuple[Mention, ...]
          ) -> tuple[tuple[ReadGoal, ...], frozenset[str]] | None:
    if not found:
        return None
    goals: list[ReadGoal] = []
    still: set[str] = set()
    last: list[Mention] = []
    last_part: list[Mention] = []  # the drawer named last: "... and close it"
    sequenced = False
    last_kind: str | None = None
    for text, step in parts_of(spell_out(proposal, found)):
        words, last_kind = resolve_ones(words_of(text), last_kind)  # "... the red ones"
        if words and words[0] in _FIRST:
            sequenced = True
        verbs = set(words)
        pending: list[Mention] = []
        span = 0
        part_goals: list[ReadGoal] = []
        anchored_any = False
        # A part that keeps objects still and moves nothing: "the red and yellow boxes
        # around it are not part of the task", "the other cylinder should stay bare".
        acting = acted(words, found)  # "open the drawer": an action on a part
        idle = bool((NEGATIONS | STILL_VERBS) & verbs) and not ACTION_VERBS & verbs \
            and not acting
        # "The red block sits on top of the yellow cylinder": the scene, no goal.
        described = (bool(STATE_VERBS & verbs) and not (ACTION_VERBS | SHAPES.keys()) & verbs
                     and not acting) or passive_scene(words)
        described_subject = False
        negated = False
        for i, w in enumerate(words):
            if w in NEGATIONS or w in STILL_VERBS:
                negated = True
                continue
            if negated and (w in _POSITIVE or (w in ACTION_VERBS and words[i - 1] not in
                                               NEGATIONS | {"do", "to", "t"})):
                negated = False
            bare = False
            if w in PRONOUNS and not (w == "both" and i + 1 < len(words)
                                      and words[i + 1] in COLOR_NAMES):  # "both red"
                # "... and put them on the pallet", "on top of it"; "and close it": the part
                refs = list(last_part if last_part and acts_on_pronoun(words, i) else last)
            elif kind_of(w)[0] is not None:
                refs = _referents(words, i, found)
            elif pending and last_part and bare_inside(words, i):
                # "open the drawer and put the bowl inside"; a microwave's door: into it
                refs, bare = containers_of(last_part, found), True
            else:
                continue
            if not refs:
                continue
            if named_parts := parts_named_by(refs, found):
                last_part = named_parts  # "put the mug in the microwave and close it"
            prep = "in" if bare else _anchor_prep(words, i)
            if negated or idle or _among(words, i) or (
                    _source(words, i) and not any(m.movable for m in refs)):
                still.update(m.name for m in refs)
                continue
            if all(m.kind in PART_KINDS for m in refs):
                last_part = refs
                p = phrase_at(words, i) if kind_of(w)[0] in PART_KINDS else Phrase(i, i)
                relation = None if described else actuation(words, p.first, p.last)
                if relation is not None:  # "open the top drawer", "and close it"
                    part_goals.append(ReadGoal(relation, tuple(m.name for m in refs), None,
                                               False, step))
                    # "open the drawer (the microwave) and put the block inside it"
                    last = said_as(refs, found)
                    continue
                if described:  # "the microwave is open; put the bowl inside it"
                    last = said_as(refs, found)
            movers = [m for m in pending if m not in refs]
            if described:
                # The scene's objects: kept still unless a goal uses them; what the part
                # is about first is what "it" means next.
                still.update(m.name for m in refs)
                if not described_subject:
                    last = [m for m in refs if m.movable] or last
                    described_subject = True
                continue
            if prep is None or not movers:
                pending.extend(m for m in refs if m not in pending and m.movable)
                continue
            shapes = _shape_of(words, span, i)
            shape = shapes[-1][1] if shapes else None
            below = [m for m in pending if m in refs]
            if below and shapes and shapes[0][0] < i:
                # "three grey blocks side by side ..., and three white blocks laid on each
                # grey block": the anchor was arranged first, by the shape word before.
                made = _grouped(below, shapes[:1], words, step, text)
                part_goals.extend(made or [])
                shape = shapes[-1][1] if len(shapes) > 1 else None
            made = _anchored(prep, refs, movers, shape, verbs, step, text)
            if made is None:
                return None
            part_goals.extend(made)
            anchored_any = True
            last, pending, span = movers, [], i + 1
        # "..., second the purple block": no verb, no place of its own (not "and the
        # green block on the other", whose place the words do not name).
        elliptic = not (ACTION_VERBS | STILL_VERBS | PREPOSITIONS.keys()) & set(words[span:])
        if pending and part_goals and part_goals[-1].anchor and elliptic:
            # "First put the orange block on the pallet, second the purple block": the
            # same goal for each object named after it, in the words' order.
            model = part_goals[-1]
            ordinal = bool(set(words) & PLACES.keys())
            used = {n for g in (*goals, *part_goals) for n in (*g.objects, g.anchor) if n}
            pending = [m for m in pending if m.name not in used]  # named again: no goal
            for k, m in enumerate(pending, start=1):
                part_goals.append(replace(model, objects=(m.name,), ordered=False,
                                          step=model.step + (k if ordinal else 0)))
            last, pending = pending, []
        if pending:
            shapes = _shape_of(words, 0, len(words))
            if shapes:
                made = _grouped(pending, shapes, words, step, text)
                if made is None:
                    return None
                part_goals.extend(made)
                last = pending
            elif not anchored_any and not part_goals:
                last = pending  # "three blocks are on the table": the objects, no goal
        for goal in part_goals:
            _add(goals, goal, {m.name: m for m in found}, text)
    if not goals:
        return None
    if sequenced and len({g.step for g in goals}) == 1 and len(goals) > 1:
        goals = [replace(g, step=k) for k, g in enumerate(goals)]  # "first A, B": as read
    goals = sequence_parts(goals, found)  # "put the block in the drawer and close it"
    goals = in_colour_sequence(goals, proposal, found)
    goals = stacked_in_order(goals, proposal, found)
    goals = [g2 for g in goals for g2 in layered(g, proposal, found)]
    goals = [in_member_sequence(g, proposal, found) for g in goals]
    goals = bridged(goals, found)
    used = {n for g in goals for n in (*g.objects, g.anchor) if n}
    still -= used  # moved or an anchor elsewhere: not still
    still |= unpicked(found, used)  # "the second bowl": the others stay as they are
    still |= still_parts(found) - used  # a cabinet, its drawers no goal names
    if any(m.name not in used | still for m in found):
        return None
    return tuple(goals), frozenset(still)


def _source(words: list[str], i: int) -> bool:
    """Whether the kind word ``words[i]`` ends a phrase "from ..." / "out of ...": where
    an object comes from."""
    j = i - 1
    while j >= 0 and words[j] != "of" and (words[j] in _LEAD or words[j] in COLOR_NAMES
                                           or count_of(words[j]) or is_selector(words[j])):
        j -= 1
    return j >= 0 and (words[j] == "from" or (words[j] == "of" and j and words[j - 1] == "out"))


def _among(words: list[str], i: int) -> bool:
    """Whether the kind word ``words[i]`` ends a phrase "(from) among ...": the group a
    named object is picked out of ("the yellow ball from among the four balls")."""
    j = i - 1
    while j >= 0 and (words[j] in _LEAD or words[j] in COLOR_NAMES or count_of(words[j])):
        j -= 1
    return j >= 0 and words[j] in ("among", "amongst")


def _add(goals: list[ReadGoal], goal: ReadGoal, by_name: dict[str, Mention],
         text: str) -> None:
    """Add ``goal``, or -- where an earlier goal of the same relation moves the same
    objects or more ("stack them in the container. The bottom of the stack is red
    ...") -- refine that one with the order ``text`` (``goal``'s words) gives: the
    words describe one goal twice."""
    for k, old in enumerate(goals):
        if old.relation == goal.relation and set(goal.objects) <= set(old.objects) \
                and goal.anchor in (None, old.anchor):
            if set(goal.objects) == set(old.objects) and goal.ordered:
                goals[k] = replace(old, objects=goal.objects, ordered=True)
            elif not old.ordered and old.relation in ("stack", "row"):
                # "... The bottom of the tower is red, followed by blue, green": the
                # words give the order of the whole goal named before.
                movers, ordered = ordered_by_words([by_name[n] for n in old.objects], text)
                if ordered:
                    goals[k] = replace(old, objects=tuple(m.name for m in movers),
                                       ordered=True)
            return
    goals.append(goal)


def _anchored(prep: str, anchors: list[Mention], movers: list[Mention], shape: str | None,
              verbs: set[str], step: int, text: str) -> list[ReadGoal] | None:
    """The goals that put ``movers`` at ``anchors`` (one anchor: all there; as many
    anchors as movers and paired by colour or order: each with its own)."""
    pairs: list[tuple[list[Mention], Mention]]
    if len(anchors) == 1:
        pairs = [(movers, anchors[0])]
    elif len(anchors) == len(movers):
        by_colour = {a.color: a for a in anchors if a.color}
        if all(m.color in by_colour for m in movers) and len(by_colour) == len(anchors):
            pairs = [([m], by_colour[m.color]) for m in movers]
        else:
            pairs = [([m], a) for m, a in zip(movers, anchors, strict=True)]
    else:
        return None
    out: list[ReadGoal] = []
    for group, anchor in pairs:
        relation = _relation(prep, anchor, group, shape, verbs)
        if relation is None:
            return None
        ordered, field_ = False, None
        if prep == "beside" and relation == "row":
            out.append(ReadGoal("row", (anchor.name, *(m.name for m in group)), None, False,
                                step))
            continue
        if relation == "on" and anchor.movable and anchor.count > 1 \
                and sum(m.count for m in group) > 1:
            relation, field_ = "row", "on"  # "three white blocks, one on each grey block"
        if relation in ("stack", "row"):
            group, ordered = ordered_by_words(group, text)
        if prep == "between":
            field_ = "along"
        out.append(ReadGoal(relation, tuple(m.name for m in group), anchor.name, ordered,
                            step, field_))
    return out


def _grouped(movers: list[Mention], shapes: list[tuple[int, str, bool]], words: list[str],
             step: int, text: str) -> list[ReadGoal] | None:
    """The arrangements of ``movers`` the shape words name, no anchor: one over all,
    one per group where the words say so, or one per shape word ("a row from the
    red blocks and a circle from the blue blocks")."""
    relations = {r for _, r, _ in shapes}
    if len(shapes) > 1:
        positions = {m.name: _position(words, m) for m in movers}
        # The shape word names its group before it ("a row from the red blocks") or
        # after it ("put the red blocks in a circle, and the blue blocks in a circle"):
        # the way the first one does.
        first = min(positions.values(), default=0)
        shape_first = shapes[0][0] < first
        groups: dict[int, list[Mention]] = {}
        for m in movers:
            if shape_first:
                near = [k for k, (p, _, _) in enumerate(shapes) if p <= positions[m.name]]
                k = near[-1] if near else 0
            else:
                near = [k for k, (p, _, _) in enumerate(shapes) if p > positions[m.name]]
                k = near[0] if near else len(shapes) - 1
            groups.setdefault(k, []).append(m)
        # Shape words of one relation name one group each only where each has its own
        # ("the tower ... the tower" may be the same one twice).
        if len(relations) > 1 or len(groups) == len(shapes):
            out = []
            for k, group in sorted(groups.items()):
                out.extend(_grouped(group, [shapes[k]], words, step, text) or [])
            return out or None
    relation = shapes[0][1]
    separate = any(p for _, _, p in shapes) or (bool(SEPARATE & set(words)) \
        and len(movers) > 1 and all(m.count > 1 for m in movers))
    groups_list = [[m] for m in movers] if separate and len(movers) > 1 else [movers]
    out = []
    for group in groups_list:
        ordered = False
        if relation in ("stack", "row"):
            group, ordered = ordered_by_words(group, text)
        out.append(ReadGoal(relation, tuple(m.name for m in group), None, ordered, step))
    return out


def _position(words: list[str], m: Mention) -> int:
    """Where the words first name ``m`` (its kind word after its colour), else 0."""
    for k, w in enumerate(words):
        if kind_of(w)[0] == m.kind and (m.color is None or (k and words[k - 1] == m.color)):
            return k
    return 0


__all__ = ["PREPOSITIONS", "ReadGoal", "parts_of", "read_goals", "still_objects"]
