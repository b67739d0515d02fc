"""The reset loop: an initial layout whose targets solve and whose goals are open.

:func:`reset_layout` samples an initial layout (:mod:`factask.sim.layout.sampling`),
solves every factor's targets from it (:mod:`factask.sim.layout.solving`) and resamples
— at most :data:`MAX_RESETS` times — when the targets cannot be solved from it or
when it already satisfies a goal. The whole loop has a wall-clock budget
(:data:`RESET_TIME_BUDGET_S`): a layout the sampler cannot find ends in a
:class:`~factask.scene.collision.LayoutError` in bounded time.
"""

from __future__ import annotations

import numpy as np

from factask.geometry import Pose
from factask.graph.taskgraph import TaskGraph
from factask.relations.solving import SolvedFactor
from factask.scene.collision import Deadline, LayoutError
from factask.scene.objects import objects_by_name
from factask.sim.layout.checks import check_task
from factask.sim.layout.sampling import sample_layout
from factask.sim.layout.solving import solve_targets

#: Initial layouts tried by :func:`reset_layout`.
MAX_RESETS = 10
#: Wall-clock seconds a reset may search before it gives up.
RESET_TIME_BUDGET_S = 8.0


def moving_factors(graph: TaskGraph) -> list[str]:
    """Factors whose goal moves at least one object (every factor, by the schema)."""
    return [f.name for f in graph.factors if f.goal.objects]


def reset_layout(graph: TaskGraph, rng: np.random.Generator,
                 max_resets: int = MAX_RESETS, time_budget: float = RESET_TIME_BUDGET_S
                 ) -> tuple[dict[str, Pose], dict[str, SolvedFactor]]:
    """Sample an initial layout and solve every factor's targets.

    The layout is resampled (at most ``max_resets`` times) when the targets cannot
    be solved from it, or when it already satisfies a goal.

    Args:
        graph: The task graph.
        rng: Random generator (same seed, same result).
        max_resets: Initial layouts tried.
        time_budget: Wall-clock seconds before giving up (same seed, same result
            whenever the budget is not hit).

    Returns:
        (initial poses, solved factors).

    Raises:
        LayoutError: no layout worked; the message has the last reason.
    """
    objs = objects_by_name(graph)
    deadline = Deadline.after(time_budget)
    last: LayoutError | None = None
    for _ in range(max_resets):
        try:
            layout = sample_layout(graph, rng, deadline=deadline)
            solved = solve_targets(graph, layout, rng, deadline=deadline)
        except LayoutError as exc:
            last = exc
            if not exc.retryable:
                raise
            continue
        status = check_task(graph, solved, layout, objects=objs)
        # Reached, not merely satisfied: a goal that holds at the start but comes after
        # a milestone that will undo it (towers-of-hanoi's last moves) is not done yet.
        done = [n for n in moving_factors(graph) if n in status.reached]
        if done:
            last = LayoutError(f"factor(s) {done}", "every sampled initial layout already "
                               "satisfies them", tries=max_resets,
                               fix="start the objects somewhere else")
            continue
        return layout, solved
    assert last is not None
    raise LayoutError(last.what, last.reason, tries=max_resets, retryable=False)
