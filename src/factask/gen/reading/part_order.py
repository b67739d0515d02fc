"""The order of goals on articulated parts, from the table
(:data:`~factask.gen.reading.articulated.PART_KINDS`): two goals of one step on one
part keep the words' order ("put the block in the drawer and close it"); a part that
starts shut is opened (its ``admits`` relation) before anything goes into it or into
its host behind it (a microwave behind its door); several parts of one host are done
in the table's ``order`` ("open both drawers": the bottom one first).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from factask.gen.reading.articulated import PART_KINDS
from factask.gen.reading.parts import Mention, seated
from factask.gen.reading.read_goal import ReadGoal


def sequence_parts(goals: list[ReadGoal], found: Sequence[Mention]) -> list[ReadGoal]:
    """Goals renumbered so that two goals of one step that act on the same part (slide it,
    or put something in it) follow the words' order: "put the block in the drawer and
    close it" puts first, then closes."""
    kinds = {m.name: m.kind for m in found}
    goals = _in_reach_order(_opened_first(_into_hosts(goals, found), found), found)
    ordered = _ordered_actions(found)

    held = {m.name: v for m in found for k, v in m.start if k == "container"}

    def touched(g: ReadGoal) -> set[str]:
        names = {*g.objects, *([g.anchor] if g.anchor else [])}
        names |= {held[n] for n in g.objects if n in held}  # taken out of a drawer
        return {n for n in names if kinds.get(n) in PART_KINDS}

    out: list[ReadGoal] = []
    step, old, group, done = -1, None, set(), set()
    for g in goals:
        parts = touched(g)
        # "open both drawers": one after the other, as the table orders them
        acts = {(ordered[n], g.relation) for n in g.objects if n in ordered}
        if g.step != old or parts & group or acts & done:
            step, group, done = step + 1, set(), set()
        old = g.step
        group |= parts
        done |= acts
        out.append(replace(g, step=step))
    return out


def _ordered_actions(found: Sequence[Mention]) -> dict[str, str]:
    """Part -> its host, for the parts of a kind whose relations the table orders."""
    return {m.name: seat[0] for m in found if (seat := seated(m))
            and PART_KINDS[m.kind].order}


def _in_reach_order(goals: list[ReadGoal], found: Sequence[Mention]) -> list[ReadGoal]:
    """``goals`` with each goal that acts on several parts split into one per part, and
    the goals of one step that do an ordered relation to parts of one host put in the
    table's order (:attr:`~factask.gen.reading.articulated.PartKind.order`): "open the
    top and bottom drawers" opens the bottom one first."""
    by_name = {m.name: m for m in found}
    seats = {n: s for n, m in by_name.items() if (s := seated(m))}

    def order_of(g: ReadGoal) -> str | None:
        kinds = {by_name[n].kind for n in g.objects if n in seats}
        if len(kinds) != 1 or len(kinds | {by_name[n].kind for n in g.objects}) != 1:
            return None
        return PART_KINDS[kinds.pop()].order.get(g.relation)

    split: list[ReadGoal] = []
    for g in goals:
        if order_of(g) and len(g.objects) > 1:
            split.extend(replace(g, objects=(n,)) for n in g.objects)
        else:
            split.append(g)
    out = list(split)
    runs: dict[tuple[int, str, str], list[int]] = {}
    for k, g in enumerate(split):
        if order_of(g) is not None:
            runs.setdefault((g.step, g.relation, seats[g.objects[0]][0]), []).append(k)
    for places in runs.values():
        members = [split[k] for k in places]
        up = order_of(members[0]) == "up"
        members.sort(key=lambda g: seats[g.objects[0]][1], reverse=not up)
        for k, g in zip(places, members, strict=True):
            out[k] = g
    return out


def _opened_first(goals: list[ReadGoal], found: Sequence[Mention]) -> list[ReadGoal]:
    """``goals`` with the goal that lets things in (the table's ``admits``: ``open``)
    before each goal that puts something into a part that starts shut, or into a host
    behind it (a microwave behind its door), where no goal before opens it: nothing
    goes into a shut drawer ("put the block in the drawer and close it": open it, put,
    close)."""
    kinds = {m.name: m.kind for m in found}
    gate: dict[str, str] = {}  # what things go into -> the part that shuts it
    shut: set[str] = set()
    for m in found:
        spec = PART_KINDS.get(m.kind)
        seat = spec.seat_of(dict(m.start)) if spec and spec.admits and spec.into else None
        if spec is None or seat is None:
            continue
        gate[m.name if spec.into == "part" else seat[0]] = m.name
        if seat[2] == 0:
            shut.add(m.name)
    out: list[ReadGoal] = []
    for g in goals:
        part = gate.get(g.anchor or "") if g.relation == "inside" else None
        admits = PART_KINDS[kinds[part]].admits if part in shut else None
        if part is not None and admits:
            out.append(ReadGoal(admits[0], (part,), None, False, g.step))
            shut.discard(part)
        out.append(g)
        for n in g.objects:
            spec = PART_KINDS.get(kinds.get(n, ""))
            if spec and spec.admits and g.relation in spec.admits:
                (shut.discard if g.relation == spec.admits[0] else shut.add)(n)
    return out


def _into_hosts(goals: list[ReadGoal], found: Sequence[Mention]) -> list[ReadGoal]:
    """``goals`` with a put into a part that things go in behind ("open the microwave
    and put the bowl inside": into its door, as the words run) put into its host."""
    hosts = {m.name: seat[0] for m in found if (spec := PART_KINDS.get(m.kind))
             and spec.into == "host" and (seat := spec.seat_of(dict(m.start)))}
    return [replace(g, anchor=hosts[g.anchor]) if g.relation == "inside" and g.anchor in hosts
            else g for g in goals]


__all__ = ["sequence_parts"]
