"""Target solving: every factor's relation turned into concrete target slots.

:func:`solve_targets` drives the relation units (:mod:`factask.relations`): in
:meth:`TaskGraph.factor_order`, each factor's relation proposes slots, the
context holds them to the shared rules (collision-free, supported, inside the
workspace), and a factor anchored to a variable moved earlier uses that
variable's *solved* pose. Each factor gets at most :data:`MAX_SOLVE_ATTEMPTS`
attempts with other random choices; failure raises
:class:`~factask.scene.collision.LayoutError` naming the factor and why.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from factask.geometry import Pose
from factask.graph.taskgraph import TaskGraph
from factask.relations.solving import Infeasible, Plan, SolveContext, SolvedFactor
from factask.scene.collision import NO_DEADLINE, Deadline, LayoutError, Occupancy
from factask.scene.objects import objects_by_name

#: Attempts (other random choices) per factor before :func:`solve_targets` gives up.
MAX_SOLVE_ATTEMPTS = 20


def solve_targets(graph: TaskGraph, layout: Mapping[str, Pose], rng: np.random.Generator,
                  max_attempts: int = MAX_SOLVE_ATTEMPTS,
                  deadline: Deadline = NO_DEADLINE) -> dict[str, SolvedFactor]:
    """Turn every factor's relation into concrete target slots.

    Args:
        graph: The task graph.
        layout: Initial pose of every instance (from :func:`sample_layout`).
        rng: Random generator (free spots, phases, offsets).
        max_attempts: Attempts per factor with other random choices.
        deadline: When to give up (checked between attempts and candidate spots).

    Returns:
        Factor name -> :class:`SolvedFactor`, in ``graph.factor_order()``.

    Raises:
        LayoutError: a factor has no feasible targets (names the factor and why).
    """
    objs = objects_by_name(graph)
    missing = [n for n in objs if n not in layout]
    if missing:
        raise LayoutError(f"layout of {graph.name!r}", f"no initial pose for {missing}",
                          retryable=False, fix="pass the dict sample_layout returns")
    ctx = SolveContext(graph, objs, dict(layout), Occupancy(), rng, deadline=deadline)
    # Obstacles for targets: what will still stand where it started. Flat markers
    # do not collide, and an object some factor moves vacates its start (the
    # oracle moves it out of the way first if a target needs the spot); its own
    # target becomes an obstacle once solved.
    moved = {i for f in graph.factors for v in f.goal.objects for i in ctx.inst(v)}
    for name, pose in layout.items():
        if name in objs and objs[name].collides and name not in moved:
            ctx.occ.put(name, objs[name], pose)
    out: dict[str, SolvedFactor] = {}
    for fname in graph.factor_order():
        f = graph.factor(fname)
        movers = [objs[i] for v in f.goal.objects for i in ctx.inst(v)]
        last: Infeasible | None = None
        plan: Plan | None = None
        tries = 0
        for attempt in range(max_attempts):
            deadline.check(f"factor {fname!r} ({f.goal.type})", last.reason if last else "")
            tries += 1
            ctx.attempt = attempt
            plan = None
            try:
                plan = f.goal.solve(ctx, movers)
                ctx.accept(movers, plan)
                break
            except Infeasible as exc:
                last, made = exc, plan
                plan = None
                # Anchored, deterministic targets come out the same every attempt.
                if not exc.retry or (made is not None and not made.random):
                    break
        if plan is None:
            assert last is not None
            # retry=False marks reasons no initial layout can change (capacity, shape).
            raise LayoutError(f"factor {fname!r} ({f.goal.type})", last.reason, tries=tries,
                              retryable=last.retry)
        solved = SolvedFactor(
            factor=fname, relation=f.goal.type, objects=[o.name for o in movers],
            slots=plan.slots, matches=plan.matches.astype(bool),
            region=plan.region[0] if plan.region else None, regions=list(plan.region),
            supports=plan.supports, surfaces=plan.surfaces, assignment=plan.assignment,
            check_yaw=plan.check_yaw, chain=plan.chain, support_group=plan.support_group,
        )
        for name, pose in solved.targets(objs).items():
            ctx.current[name] = pose
            ctx.occ.put(name, objs[name], pose)
            ctx.placed.add(name)
        out[fname] = solved
    return out


