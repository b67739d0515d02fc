"""The order of a task's factors: dependency edges, milestones, and their rules.

Two kinds of factor (:attr:`SubtaskFactor.milestone`):

* a **final** factor (the default) must hold at the end of the episode; it is
  re-checked every step;
* a **milestone** counts once achieved, in order: it becomes *ready* when every
  factor before it has been reached, is *reached* (latched) the first time its
  goal holds while ready, and keeps full progress after that even if a later
  factor moves its objects again (Ravens' goal queue; towers-of-hanoi's moves).

Order edges ``A -> B`` ("A before B") come from B's explicit ``after`` and from
implied order: B's goal is anchored to (rests on, goes into, aligns with) a
variable that A moves. When several factors move that variable, B relies on the
pose it has when B runs: a mover that ``after`` edges put behind B gives no edge.
A goal anchored to a receptacle is also anchored to its gates (a drawer is its own
gate, a microwave's door gates the microwave: ``gates``). A mover whose relation
shuts its objects (:attr:`~factask.relations.base.RelationBase.anchored_goals`
``"before"``: ``closed``) comes *after* the goals anchored to them instead -- what
goes into a drawer goes in before it is shut -- so "put the block in the drawer
that starts open, then close it" needs no ``after`` at all, and one that says so
is no cycle.

Rules (each broken rule is a :class:`Problem` naming the factor):

* the order has no cycle;
* a variable moved by several factors: those factors are totally ordered, and
  every one but the last is a milestone (only an object's last goal can hold at
  the end).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from itertools import pairwise
from typing import TYPE_CHECKING

import networkx as nx

from factask.vocabulary.errors import Problem

if TYPE_CHECKING:
    from factask.graph.factors import SubtaskFactor

#: Cycles listed in one validation report at most.
MAX_CYCLES_REPORTED = 5


def dependency_graph(factors: Sequence[SubtaskFactor],
                     gates: Mapping[str, Sequence[str]] | None = None) -> nx.DiGraph:
    """Directed graph of factor order (an edge A -> B means A comes before B).

    Args:
        factors: The graph's factors (unknown names in ``after`` are skipped; the
            graph's validation reports them).
        gates: Receptacle variable -> the variables that gate it
            (:func:`~factask.vocabulary.variables.gates_of`); None: none.

    Returns:
        A DiGraph over every factor name; each edge's ``why`` says where it came from.
    """
    d = nx.DiGraph()
    names = [f.name for f in factors]
    d.add_nodes_from(names)
    known = set(names)
    for f in factors:
        for a in f.after:
            if a in known and a != f.name:
                d.add_edge(a, f.name, why="after")
    explicit = d.copy()
    movers = movers_by_variable(factors)
    by_name = {f.name: f for f in factors}
    for f in factors:
        anchors = list(dict.fromkeys(a for anchor in f.anchors()
                                     for a in (anchor, *(gates or {}).get(anchor, ()))))
        for anchor in anchors:
            for m in movers.get(anchor, []):
                if m == f.name:
                    continue
                if by_name[m].goal.anchored_goals == "before":
                    # A shutting goal comes after what goes in, unless the author
                    # ordered it before f on purpose.
                    if not nx.has_path(explicit, m, f.name):
                        d.add_edge(f.name, m, why=f"{m} shuts {anchor}, which {f.name} "
                                   "is anchored to")
                    continue
                # A mover ordered behind f moves the anchor only after f is done.
                if len(movers[anchor]) > 1 and nx.has_path(explicit, f.name, m):
                    continue
                d.add_edge(m, f.name, why=f"{f.name} is anchored to {anchor}")
    return d


def movers_by_variable(factors: Sequence[SubtaskFactor]) -> dict[str, list[str]]:
    """Variable name -> the factors that move it, in declaration order."""
    movers: dict[str, list[str]] = {}
    for f in factors:
        for v in dict.fromkeys(f.goal.objects):
            movers.setdefault(v, []).append(f.name)
    return movers


def topological_order(d: nx.DiGraph, declared: Sequence[str]) -> list[str]:
    """Factor names in dependency order, declaration order breaking ties.

    Raises:
        nx.NetworkXUnfeasible: ``d`` has a cycle.
    """
    index = {n: i for i, n in enumerate(declared)}
    return list(nx.lexicographical_topological_sort(d, key=index.__getitem__))


def cycle_problems(d: nx.DiGraph) -> list[Problem]:
    """One problem per cycle of ``d`` (at most :data:`MAX_CYCLES_REPORTED`), each
    naming the factors around it."""
    problems = []
    for cycle in nx.simple_cycles(d):
        path = " -> ".join([*cycle, cycle[0]])
        problems.append(Problem(cycle[0], "after", f"factor order has a cycle: {path}",
                                "remove one 'after' entry, or anchor the goals differently"))
        if len(problems) >= MAX_CYCLES_REPORTED:
            break
    return problems


def mover_problems(factors: Sequence[SubtaskFactor], d: nx.DiGraph) -> list[Problem]:
    """Problems with variables that several factors move (see the module's rules).

    Args:
        factors: The graph's factors.
        d: Their :func:`dependency_graph` (acyclic; with a cycle, nothing is reported).
    """
    if not nx.is_directed_acyclic_graph(d):
        return []
    by_name = {f.name: f for f in factors}
    out: list[Problem] = []
    for var, who in movers_by_variable(factors).items():
        if len(who) < 2:
            continue
        loose = [(a, b) for i, a in enumerate(who) for b in who[i + 1:]
                 if not (nx.has_path(d, a, b) or nx.has_path(d, b, a))]
        if loose:
            a, b = loose[0]
            out.append(Problem(b, "after", f"variable {var!r} is moved by factors {a!r} and "
                               f"{b!r} with no order between them",
                               f"add {a!r} to the 'after' of {b!r} (or the reverse)"))
            continue
        ordered = sorted(who, key=lambda n: sum(nx.has_path(d, m, n) for m in who))
        for name in ordered[:-1]:
            if not by_name[name].milestone:
                out.append(Problem(name, "milestone", f"moves {var!r}, which the later "
                                   f"factor {ordered[-1]!r} moves again, so its goal cannot "
                                   "hold at the end", "set milestone=true (it then counts "
                                   "once achieved), or let one factor move the variable"))
    return out


def in_listed_order(factors: Sequence[SubtaskFactor]) -> list[SubtaskFactor]:
    """The factors with the order their listing implies for shared objects.

    For a plan whose subtasks are listed in the order they are done (an LLM's
    subtask plan or outline): where several factors move the same variable and
    nothing orders them yet, each goes ``after`` the previous one in the list,
    and every one but the last is a milestone -- the rule that
    :func:`mover_problems` checks, made to hold the way the listing says. Pairs
    already ordered (either way, by ``after`` or by anchors) are left alone, and
    an edge that would close a cycle is not added (the validation then reports
    the cycle the factors already have).

    Args:
        factors: The factors in listed order.

    Returns:
        Copies of the factors (the same objects where nothing changes).
    """
    d = dependency_graph(factors)
    added: dict[str, list[str]] = {}
    for who in movers_by_variable(factors).values():
        for a, b in pairwise(who):
            if nx.has_path(d, a, b) or nx.has_path(d, b, a):
                continue
            d.add_edge(a, b, why="listed order")
            added.setdefault(b, []).append(a)
    if not nx.is_directed_acyclic_graph(d):
        return list(factors)
    earlier: set[str] = set()
    for who in movers_by_variable(factors).values():
        if len(who) > 1:
            ordered = sorted(who, key=lambda n: sum(nx.has_path(d, m, n) for m in who))
            earlier.update(ordered[:-1])
    out = []
    for f in factors:
        update: dict[str, object] = {}
        if f.name in added:
            update["after"] = [*f.after, *(a for a in added[f.name] if a not in f.after)]
        if f.name in earlier and not f.milestone:
            update["milestone"] = True
        out.append(f.model_copy(update=update) if update else f)
    return out


__all__ = ["cycle_problems", "dependency_graph", "in_listed_order", "mover_problems",
           "movers_by_variable", "topological_order"]
