"""Passes over the goals the clause reading found (:mod:`factask.gen.reading.clauses`)
that order or regroup them by what the whole proposal says: goals done in a colour
sequence (:func:`in_colour_sequence`), the members of coloured groups in a sequence
that repeats colours (:func:`in_member_sequence`), a pair standing apart under a
bridge (:func:`bridged`), objects put one by one where the words say
what is at the bottom and the top as one stack (:func:`stacked_in_order`), a stack
built in layers as one row per layer (:func:`layered`). Split from the clause reading
(one concept: the order the words give goals already read).
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Sequence
from dataclasses import replace

from factask.gen.reading.mentions import Mention
from factask.gen.reading.orders import ordered_by_words
from factask.gen.reading.read_goal import ReadGoal
from factask.gen.reading.sequences import CUES, colour_sequence

#: Relations whose objects may be placed one at a time, each a goal of its own.
_ONE_BY_ONE = frozenset({"inside", "in_zone", "on", "aligned"})
#: Words that say the goals are done in an order the words then list.
_SEQUENCE_WORDS = frozenset({"sequence", "order", "sequentially", "sequential"})


def in_colour_sequence(goals: list[ReadGoal], proposal: str,
                        found: Sequence[Mention]) -> list[ReadGoal]:
    """Goals of one step, each moving one colour, put in the colour order the words
    list after a sequence word ("... in a specific color sequence: red, blue, green")."""
    colour = {m.name: m.color for m in found}
    if len(goals) == 1 and goals[0].relation in _ONE_BY_ONE and len(goals[0].objects) > 1:
        # "put the balls in the container in this order: black, white, gold": one goal
        # per object, ordered below (where the words list their colours).
        goals = [replace(goals[0], objects=(o,)) for o in goals[0].objects]
        split = in_colour_sequence(goals, proposal, found)
        return split if len({g.step for g in split}) == len(split) else \
            [replace(goals[0], objects=tuple(o for g in goals for o in g.objects))]
    mine = [colour.get(g.objects[0]) if len(g.objects) == 1 else None for g in goals]
    if len(goals) < 2 or len({g.step for g in goals}) > 1 or None in mine \
            or len(set(mine)) < len(mine):
        return goals
    words = re.findall(r"[a-z]+", proposal.lower().replace("grey", "gray"))
    cue = next((k for k, w in enumerate(words) if w in _SEQUENCE_WORDS), None)
    if cue is None:
        return goals
    listed: list[str] = []
    for w in words[cue:]:
        if w in mine and w not in listed:
            listed.append(w)
    if len(listed) < len(mine) - 1:
        return goals
    listed += [c for c in mine if c not in listed and c is not None]
    return [replace(g, step=listed.index(str(c))) for g, c in zip(goals, mine, strict=True)]


#: Words that place objects one above another: "red at the bottom, ... yellow at the top".
_LAYER_PLACES = frozenset({"bottom", "top", "base"})


def stacked_in_order(goals: list[ReadGoal], proposal: str,
                      found: Sequence[Mention]) -> list[ReadGoal]:
    """Objects put one by one onto (or into) one fixed object, or onto each other
    there, the words saying which is at the bottom and which at the top ("place it
    into the pallet in a specific colour sequence: red at the bottom, then blue, ...
    yellow at the top"): one stack on that object in the words' order, the order
    read from the whole proposal (a later sentence may give it: "the sequence from
    bottom to top should be orange, blue, ..."); any other goals as they are."""
    by_name = {m.name: m for m in found}
    words = set(re.findall(r"[a-z]+", proposal.lower()))
    if not _LAYER_PLACES & words or any(g.relation not in ("on", "inside", "stack")
                                        for g in goals):
        return goals
    steps: dict[str, set[int]] = {}
    for g in goals:
        for o in g.objects:
            steps.setdefault(o, set()).add(g.step)
    if sum(g.relation == "stack" for g in goals) > 1 or any(len(v) > 1 for v in steps.values()):
        return goals  # two towers; or put on the pallet, *then* stacked: steps of their own
    movers = list(dict.fromkeys(o for g in sorted(goals, key=lambda g: g.step)
                                for o in g.objects))
    bases = {g.anchor for g in goals} - set(movers)
    if len(bases) != 1 or any(by_name[o].count != 1 for o in movers if o in by_name):
        return goals
    (base,) = bases
    if base is not None and (base not in by_name or by_name[base].movable):
        return goals
    if len(movers) < 2 or (len(goals) == 1 and goals[0].ordered):
        return goals  # one object, or one goal ordered already
    ordered, known = ordered_by_words([by_name[o] for o in movers], proposal.lower())
    if not known:
        return goals
    return [ReadGoal("stack", tuple(m.name for m in ordered), base, True,
                     min(g.step for g in goals))]


#: Words of a build in layers: each group of objects is a layer on the one below.
LAYER_WORDS = frozenset({"pyramid", "wall", "layer", "layers", "course", "courses", "level",
                         "levels", "tier", "tiers"})


def layered(goal: ReadGoal, proposal: str, found: Sequence[Mention]) -> list[ReadGoal]:
    """A stack of groups the words build in layers ("a pyramid: the three green blocks
    at the bottom, the two red blocks in the middle and the blue block on top") as one
    row per group, each on the one below (the first along the anchor); any other goal
    as it is."""
    by_name = {m.name: m for m in found}
    groups = [by_name[n] for n in goal.objects if n in by_name]
    words = set(re.findall(r"[a-z]+", proposal.lower()))
    if goal.relation != "stack" or len(groups) < 2 or not LAYER_WORDS & words \
            or all(m.count == 1 for m in groups):
        return [goal]
    if not goal.ordered:
        groups, ordered = ordered_by_words(groups, proposal.lower())
        if not ordered:
            return [goal]
    out = [ReadGoal("row", (groups[0].name,), goal.anchor, False, goal.step, "along")]
    out += [ReadGoal("row", (upper.name,), lower.name, False, goal.step, "on")
            for lower, upper in itertools.pairwise(groups)]
    return out


#: Arrangements whose objects can take a sequence.
_ARRANGEMENTS = frozenset({"stack", "row", "circle"})


def in_member_sequence(goal: ReadGoal, proposal: str,
                       found: Sequence[Mention]) -> ReadGoal:
    """``goal`` with its objects in the sequence the words ask, where it is an
    arrangement of every member of the groups the sequence runs over; else as it is."""
    by_name = {m.name: m for m in found}
    movers = [by_name.get(n) for n in goal.objects]
    if goal.relation not in _ARRANGEMENTS or None in movers:
        return goal
    groups = {m.group for m in movers if m is not None}
    members = {m.name for m in found if m.group in groups}
    if None in groups or members != set(goal.objects):
        return goal
    whole = [replace(m, name=str(m.group), count=sum(1 for o in found if o.group == m.group),  # type: ignore[type-var]
                     group=None) for m in found if m.group in groups and m.rank == 0]
    words = re.findall(r"[a-z]+", proposal.lower().replace("grey", "gray"))
    ranked, known = ordered_by_words(list(whole), proposal.lower())
    sequence = colour_sequence(words, whole, [str(m.color) for m in ranked] if known else ())
    if sequence is None:
        return goal
    tail = words[next((k for k, w in enumerate(words) if w in CUES), 0):]
    if "top" in tail and "bottom" in tail and tail.index("top") < tail.index("bottom"):
        sequence = sequence[::-1]  # "from the top: ..."
    queues = {str(m.color): sorted((o for o in found if o.group == m.name),
                                   key=lambda o: o.rank) for m in whole}
    objects = tuple(queues[c].pop(0).name for c in sequence)
    return replace(goal, objects=objects, ordered=True)


def bridged(goals: list[ReadGoal], found: Sequence[Mention]) -> list[ReadGoal]:
    """A bridge: one object put on a pair of objects the robot moves ("lay the log
    across the two red blocks", "balance the cylinder on top of the red blocks") rests
    on both, so the pair stands apart in a row first, where no goal of the words moves
    the pair already; the goals after it one step later."""
    by_name = {m.name: m for m in found}
    moved = {o for g in goals for o in g.objects}
    out = list(goals)
    for g in goals:
        pair = by_name.get(g.anchor or "")
        deck = [by_name.get(o) for o in g.objects]
        if g.relation != "on" or pair is None or not pair.movable or pair.count != 2 \
                or pair.name in moved or len(deck) != 1 or deck[0] is None \
                or deck[0].count != 1:
            continue
        out = [replace(x, step=x.step + 1) if x.step >= g.step else x for x in out]
        out.insert(out.index(replace(g, step=g.step + 1)),
                   ReadGoal("row", (pair.name,), None, False, g.step))
        moved.add(pair.name)
    return out


__all__ = ["LAYER_WORDS", "bridged", "in_colour_sequence", "in_member_sequence", "layered",
           "stacked_in_order"]
