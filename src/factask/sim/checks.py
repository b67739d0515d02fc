"""Goal checks of a whole task: every factor's status, the reward, success.

Each factor's status comes from its relation unit
(:meth:`~factask.relations.base.RelationBase.status`; see
:mod:`factask.relations.status` for what it holds and
:mod:`factask.relations` for each relation's check). This module adds them up:
reward = sum of weight x progress, success = every factor satisfied at once.
Every call re-checks every factor from the current poses (nothing latches).
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass, field

from factask.geometry import Pose
from factask.model.graph import TaskGraph
from factask.relations.solving import SolvedFactor
from factask.relations.status import MAX_TILT_DEG, CheckError, CheckScene, FactorStatus
from factask.scene.objects import SceneObject, objects_by_name


@dataclass(frozen=True)
class TaskStatus:
    """How far the whole task is.

    Attributes:
        reward: Weighted sum of factor progress, in [0, 1].
        success: Every factor satisfied at once.
        factors: Factor name -> status.
    """

    reward: float
    success: bool
    factors: dict[str, FactorStatus] = field(default_factory=dict)


def check_factor(graph: TaskGraph, solved: SolvedFactor, poses: Mapping[str, Pose],
                 held: Collection[str] = frozenset(),
                 objects: Mapping[str, SceneObject] | None = None) -> FactorStatus:
    """Status of one factor from the current poses.

    Args:
        graph: The task graph (for the factor's relation and the objects).
        solved: The factor's solved targets (:func:`factask.sim.solving.solve_targets`).
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
               objects: Mapping[str, SceneObject] | None = None) -> TaskStatus:
    """Reward and success of the whole task (every factor re-checked).

    Args:
        graph: The task graph.
        solved: Factor name -> solved targets, for every factor of ``graph``.
        poses: Current pose of every instance.
        held: Instances the robot holds now.
        objects: ``objects_by_name(graph)`` (optional cache).

    Returns:
        :class:`TaskStatus`: reward = sum of weight x progress; success = all satisfied.

    Raises:
        CheckError: a factor has no solved targets, or a pose is missing.
    """
    objs = objects if objects is not None else objects_by_name(graph)
    scene = CheckScene(objs, poses, held)
    statuses: dict[str, FactorStatus] = {}
    reward = 0.0
    for f in graph.factors:
        if f.name not in solved:
            raise CheckError(f"factor {f.name!r} has no solved targets; pass the dict "
                             "solve_targets / reset_layout returns")
        st = f.goal.status(solved[f.name], scene)
        statuses[f.name] = st
        reward += f.weight * st.progress
    success = bool(statuses) and all(s.satisfied for s in statuses.values())
    return TaskStatus(float(min(1.0, max(0.0, reward))), success, statuses)


__all__ = ["MAX_TILT_DEG", "CheckError", "FactorStatus", "TaskStatus", "check_factor",
           "check_task"]
