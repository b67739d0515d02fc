"""Goal checks of a whole task: every factor's status, the reward, success.

Each factor's status comes from its relation unit
(:meth:`~factask.relations.base.RelationBase.status`; see
:mod:`factask.relations.status` for what it holds and
:mod:`factask.relations` for each relation's check). This module adds them up:
reward = sum of weight x progress, success = every final factor satisfied at
once and every milestone reached.

Every call re-checks every factor from the current poses. Milestones
(:attr:`SubtaskFactor.milestone`, rules in :mod:`factask.graph.order`) latch:
the caller passes the factors reached so far (``reached``) and gets the new set
back in :attr:`TaskStatus.reached`; a milestone waits (progress 0) until every
factor before it has been reached, is reached the first time its goal holds
while ready, and keeps progress 1 after that.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass, field, replace

from factask.geometry import Pose
from factask.graph.order import topological_order
from factask.graph.taskgraph import TaskGraph
from factask.relations.solving import SolvedFactor
from factask.relations.status import MAX_TILT_DEG, CheckError, CheckScene, FactorStatus
from factask.scene.objects import SceneObject, objects_by_name


@dataclass(frozen=True)
class TaskStatus:
    """How far the whole task is.

    Attributes:
        reward: Weighted sum of factor progress, in [0, 1].
        success: Every final factor satisfied now and every milestone reached.
        factors: Factor name -> status.
        reached: Factors reached so far, in order (pass it to the next check).
    """

    reward: float
    success: bool
    factors: dict[str, FactorStatus] = field(default_factory=dict)
    reached: frozenset[str] = frozenset()


def check_factor(graph: TaskGraph, solved: SolvedFactor, poses: Mapping[str, Pose],
                 held: Collection[str] = frozenset(),
                 objects: Mapping[str, SceneObject] | None = None) -> FactorStatus:
    """Status of one factor from the current poses.

    Args:
        graph: The task graph (for the factor's relation and the objects).
        solved: The factor's solved targets (:func:`factask.sim.layout.solving.solve_targets`).
        poses: Current pose of every instance (fixed ones too).
        held: Instances the robot holds now (never count as placed).
        objects: ``objects_by_name(graph)``, to save rebuilding it each call.

    Returns:
        The factor's :class:`~factask.relations.status.FactorStatus`.

    Raises:
        CheckError: a needed pose is missing or not finite.
        GraphValidationError: the factor is not in ``graph``.
    """
    objs = objects if objects is not None else objects_by_name(graph)
    goal = graph.factor(solved.factor).goal
    return goal.status(solved, CheckScene(objs, poses, held))


def check_task(graph: TaskGraph, solved: Mapping[str, SolvedFactor],
               poses: Mapping[str, Pose], held: Collection[str] = frozenset(),
               objects: Mapping[str, SceneObject] | None = None,
               reached: Collection[str] = frozenset()) -> TaskStatus:
    """Reward and success of the whole task (every factor re-checked).

    Args:
        graph: The task graph.
        solved: Factor name -> solved targets, for every factor of ``graph``.
        poses: Current pose of every instance.
        held: Instances the robot holds now.
        objects: ``objects_by_name(graph)`` (optional cache).
        reached: Factors reached at earlier checks (the previous
            :attr:`TaskStatus.reached`); milestones among them stay latched.

    Returns:
        :class:`TaskStatus`: reward = sum of weight x progress; success = every final
        factor satisfied and every milestone reached.

    Raises:
        CheckError: a factor has no solved targets, or a pose is missing.
    """
    objs = objects if objects is not None else objects_by_name(graph)
    scene = CheckScene(objs, poses, held)
    statuses: dict[str, FactorStatus] = {}
    for f in graph.factors:
        if f.name not in solved:
            raise CheckError(f"factor {f.name!r} has no solved targets; pass the dict "
                             "solve_targets / reset_layout returns")
        statuses[f.name] = f.goal.status(solved[f.name], scene)
    now = latch_milestones(graph, statuses, reached) if graph.milestones() else frozenset(
        n for n, st in statuses.items() if st.satisfied)
    reward = sum(f.weight * statuses[f.name].progress for f in graph.factors)
    success = bool(statuses) and all(
        (f.name in now) if f.milestone else statuses[f.name].satisfied for f in graph.factors)
    return TaskStatus(float(min(1.0, max(0.0, reward))), success, statuses, now)


def latch_milestones(graph: TaskGraph, statuses: dict[str, FactorStatus],
                     reached: Collection[str]) -> frozenset[str]:
    """Latch milestones in order, rewriting statuses in place.

    A factor is reached when its goal holds while every factor before it is
    reached. A milestone keeps progress 1 once reached; before it is ready it
    waits (progress 0). A final factor with a milestone not yet reached somewhere
    before it waits too (nothing after a pending milestone counts yet: a
    towers-of-hanoi disk that starts where it must end has not been moved there);
    otherwise its status is the live one, and it stays reached once it was (Ravens
    pops it too).

    Args:
        graph: The task graph (valid: its order is acyclic).
        statuses: Factor name -> live status; entries of waiting and latched
            factors are replaced.
        reached: Factors reached at earlier checks.

    Returns:
        The factors reached now (a superset of ``reached`` within the graph).
    """
    d = graph.dependency_graph()
    now = set(reached) & set(statuses)
    # Factor -> milestones before it (anywhere upstream) not reached yet.
    pending: dict[str, set[str]] = {}
    for name in topological_order(d, graph.factor_names()):
        f = graph.factor(name)
        live = statuses[name]
        preds = list(d.predecessors(name))
        pending[name] = set().union(*(pending[p] for p in preds)) | {
            p for p in preds if graph.factor(p).milestone and p not in now}
        waiting = tuple(p for p in preds if p not in now)
        if f.milestone and name in now:
            statuses[name] = FactorStatus(1.0, True, "reached earlier (milestone)",
                                          latched=True)
        elif (f.milestone and waiting) or (not f.milestone and pending[name]):
            before = waiting if f.milestone else tuple(sorted(pending[name]))
            statuses[name] = replace(live, progress=0.0, satisfied=False, waiting_for=before,
                                     detail=f"waits for {', '.join(before)}")
        elif live.satisfied and not waiting:
            now.add(name)
            if f.milestone:
                statuses[name] = replace(live, latched=True)
    return frozenset(now)


__all__ = ["MAX_TILT_DEG", "CheckError", "FactorStatus", "TaskStatus", "check_factor",
           "check_task", "latch_milestones"]
