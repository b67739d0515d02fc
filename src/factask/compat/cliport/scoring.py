"""Ravens' own reward semantics, for comparing factask's checks with CLIPort's.

factask re-checks every factor every step, in XY, height and yaw. Ravens does
not: its goals are a **queue**, only the head goal is scored, a goal whose
reward reaches its share is popped and never checked again (a stack knocked
over later still counts), pose checks look at XY (1 cm; 5 cm for bowl tasks) and
yaw modulo symmetry only, and zone checks count the fraction of an object's
sample points (a 2 cm grid over its box) inside the zone's XY rectangle.
:func:`ravens_reward` replays those rules over a sequence of pose snapshots, so
an episode run in factask can also be scored as CLIPort would have.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from factask.compat.cliport.errors import PoseError
from factask.compat.cliport.transforms import rotation_wxyz, yaw_of_xyzw
from factask.geometry import Pose
from factask.graph.taskgraph import TaskGraph
from factask.vocabulary.tolerances import XY_TOLERANCE, YAW_TOLERANCE_DEG

#: A goal counts as done when its step reward is within this of its share (Ravens).
GOAL_DONE_EPS = 0.01
#: Total reward above which a Ravens episode is a success.
RAVENS_SUCCESS_REWARD = 0.99
#: Height of Ravens' zone bounds: points above it are outside any zone.
ZONE_TOP = 0.3
#: Spacing of an object's sample points, metres.
POINT_SPACING = 0.02


def pose_match(pos0: Any, quat0_xyzw: Any, pos1: Any, quat1_xyzw: Any, symmetry: float,
               pos_eps: float, rot_eps: float) -> bool:
    """Ravens' ``is_match``: XY distance < ``pos_eps`` and yaw error < ``rot_eps``.

    Args:
        pos0, quat0_xyzw: The object's pose.
        pos1, quat1_xyzw: The target pose.
        symmetry: Yaw symmetry in radians; 0 means yaw is never checked.
        pos_eps: XY tolerance, metres.
        rot_eps: Yaw tolerance, radians.
    """
    dist = float(np.linalg.norm(np.asarray(pos0, float)[:2] - np.asarray(pos1, float)[:2]))
    diff = 0.0
    if symmetry > 0:
        diff = abs(yaw_of_xyzw(quat0_xyzw) - yaw_of_xyzw(quat1_xyzw)) % symmetry
        if diff > symmetry / 2:
            diff = symmetry - diff
    return dist < pos_eps and diff < rot_eps


@dataclass(frozen=True)
class RavensGoal:
    """One CLIPort goal, in factask's names, in the order the task added it.

    Attributes:
        objects: Variable name of each CLIPort object (one variable per object).
        symmetries: Yaw symmetry of each object, radians.
        matches: len(objects) x len(targets) 0/1 matrix.
        targets: Target poses (x, y, z, yaw radians).
        replace: CLIPort's ``replace`` flag (oracle only).
        rotations: CLIPort's ``rotations`` flag (oracle only).
        metric: ``pose`` or ``zone``.
        zones: For ``zone``: (x, y, z, yaw radians, size x, size y) of each zone.
        max_reward: The goal's share of the reward.
        language: Its language goal.
    """

    objects: list[str]
    symmetries: list[float]
    matches: list[list[int]]
    targets: list[tuple[float, float, float, float]]
    replace: bool
    rotations: bool
    metric: str
    zones: list[tuple[float, float, float, float, float, float]] = field(default_factory=list)
    max_reward: float = 1.0
    language: str = ""


@dataclass(frozen=True)
class RavensScore:
    """Result of :func:`ravens_reward`.

    Attributes:
        reward: Total reward after the last snapshot, in [0, 1].
        goals_done: How many goals were popped from the queue.
        success: Every goal done, or reward above 0.99 (Ravens' ``done``).
        rewards: Total reward after each snapshot.
    """

    reward: float
    goals_done: int
    success: bool
    rewards: list[float]


def _pose_of(value: Any) -> tuple[np.ndarray, Rotation]:
    """Position and rotation of a snapshot entry.

    Accepted: a :class:`factask.geometry.Pose`; ``(position, quaternion wxyz)``;
    or ``(x, y, z, yaw)`` with yaw in radians.
    """
    if isinstance(value, Pose):
        return value.pos, rotation_wxyz(value.quat)
    if len(value) == 2:
        return np.asarray(value[0], float).reshape(3), rotation_wxyz(value[1])
    if len(value) == 4:
        x, y, z, yaw = (float(c) for c in value)
        return np.array([x, y, z]), Rotation.from_euler("z", yaw)
    raise PoseError(f"cannot read a pose from {value!r}: give a Pose, (pos, quat wxyz) "
                     "or (x, y, z, yaw)")


def _box_points(size: Sequence[float]) -> np.ndarray:
    axes = [np.arange(-d / 2, d / 2, POINT_SPACING) for d in size]
    grid = np.meshgrid(*axes, indexing="xy")
    return np.vstack([g.reshape(1, -1) for g in grid])


def _pose_step(goal: RavensGoal, snap: Mapping[str, Any], pos_eps: float,
               rot_eps: float) -> float:
    reward = 0.0
    for i, name in enumerate(goal.objects):
        if name not in snap:
            continue
        pos, rot = _pose_of(snap[name])
        quat = rot.as_quat()
        for j, flag in enumerate(goal.matches[i]):
            if not flag:
                continue
            tx, ty, tz, tyaw = goal.targets[j]
            tq = Rotation.from_euler("z", tyaw).as_quat()
            if pose_match(pos, quat, (tx, ty, tz), tq, goal.symmetries[i], pos_eps, rot_eps):
                reward += goal.max_reward / len(goal.objects)
                break
    return reward


def _zone_step(goal: RavensGoal, snap: Mapping[str, Any],
               sizes: Mapping[str, Sequence[float]]) -> float:
    inside, total = 0.0, 0
    for zx, zy, zz, zyaw, sx, sy in goal.zones:
        to_zone = Rotation.from_euler("z", zyaw).inv()
        for name in goal.objects:
            pts = _box_points(sizes[name])
            if name in snap:
                pos, rot = _pose_of(snap[name])
                world = rot.apply(pts.T) + pos
                local = to_zone.apply(world - np.array([zx, zy, zz]))
                ok = ((np.abs(local[:, 0]) < sx / 2) & (np.abs(local[:, 1]) < sy / 2)
                      & (local[:, 2] < ZONE_TOP))
                inside += float(np.sum(ok))
            total += pts.shape[1]
    return goal.max_reward * inside / total if total else 0.0


def ravens_reward(result: Any, poses_sequence: Sequence[Mapping[str, Any]]) -> RavensScore:
    """Score pose snapshots with Ravens' queue semantics.

    Args:
        result: An :class:`~factask.compat.cliport.loader.ImportResult` (its
            ``goals``, ``graph`` for object sizes, ``pos_eps`` and ``rot_eps``).
        poses_sequence: One snapshot per step (after each action): object name
            -> pose (see :func:`_pose_of` for the accepted forms). Objects left
            out of a snapshot match nothing.

    Returns:
        The final reward, goals done and success, as Ravens would report them.
    """
    sizes = {inst: v.extents for v in result.graph.variables for inst in v.instances}
    queue = list(result.goals)
    progress, total, done, history = 0.0, 0.0, 0, []
    for snap in poses_sequence:
        if not queue:
            history.append(total)
            continue
        goal = queue[0]
        if goal.metric == "zone":
            step = _zone_step(goal, snap, sizes)
        else:
            step = _pose_step(goal, snap, result.pos_eps, result.rot_eps)
        total = progress + step
        if abs(goal.max_reward - step) < GOAL_DONE_EPS:
            progress += goal.max_reward
            queue.pop(0)
            done += 1
        history.append(total)
    success = not queue or total > RAVENS_SUCCESS_REWARD
    return RavensScore(float(total), done, bool(success and poses_sequence), history)


def yaw_deg_of(quat_xyzw: Any) -> float:
    """Yaw of an x, y, z, w quaternion in degrees."""
    return math.degrees(yaw_of_xyzw(quat_xyzw))


#: The region relations Ravens would score with its zone metric.
ZONE_RELATIONS = ("in_zone", "inside", "pile_in_zone")


@dataclass(frozen=True)
class RavensTask:
    """What :func:`ravens_reward` needs: the graph (object sizes), the goal queue and
    Ravens' tolerances. An :class:`~factask.compat.cliport.loader.ImportResult` has
    the same attributes."""

    graph: Any
    goals: list[RavensGoal]
    pos_eps: float = XY_TOLERANCE
    rot_eps: float = math.radians(YAW_TOLERANCE_DEG)


def graph_goal_queue(graph: Any, solved: Mapping[str, Any], objects: Mapping[str, Any],
                     layout: Mapping[str, Pose]) -> list[RavensGoal]:
    """A factask task's goals as Ravens would queue them, for one reset.

    Each factor, in :meth:`~factask.graph.taskgraph.TaskGraph.factor_order`, becomes one
    goal worth its weight: a region relation (``in_zone``, ``inside``) a zone goal
    over the region's footprint, any other a pose goal over its solved slots (XY
    and yaw modulo the object's symmetry; yaw ignored where the factor ignores it).

    Args:
        graph: The task graph.
        solved: The reset's solved factors (``env.solved``).
        objects: Scene objects by instance name (``env.objects``).
        layout: Initial poses (``env.initial_layout``: where the regions are).
    """
    queue = []
    for name in graph.factor_order():
        f, sf = graph.factor(name), solved[name]
        symmetries = [math.radians(objects[o].symmetry_deg) if sf.check_yaw else 0.0
                      for o in sf.objects]
        targets = []
        for j in range(len(sf.slots)):
            allowed = [o for i, o in enumerate(sf.objects) if sf.matches[i, j]] or sf.objects
            pose = sf.target_pose(objects[allowed[0]], j)
            targets.append((*(float(c) for c in pose.pos), float(pose.yaw)))
        zones = []
        if sf.relation in ZONE_RELATIONS and sf.region is not None:
            rpose, rsize = layout[sf.region], objects[sf.region].size
            zones = [(*(float(c) for c in rpose.pos), float(rpose.yaw),
                      float(rsize[0]), float(rsize[1]))]
        queue.append(RavensGoal(
            objects=list(sf.objects), symmetries=symmetries,
            matches=sf.matches.astype(int).tolist(), targets=targets, replace=False,
            rotations=bool(sf.check_yaw), metric="zone" if zones else "pose", zones=zones,
            max_reward=f.weight, language=f.description))
    return queue


def scored_episode(result: Any, seed: int, robot: str = "floating", env: Any = None,
                   on_action: Any = None, video: Any = None) -> tuple[Any, RavensScore]:
    """Run one oracle episode and score it both ways: factask's checks and Ravens'.

    Args:
        result: An :class:`~factask.compat.cliport.loader.ImportResult` (its own
            goal queue), or a :class:`~factask.graph.taskgraph.TaskGraph` (its factors
            in order as the queue: :func:`graph_goal_queue`).
        seed: Reset seed of the episode.
        robot: A robot of the registry.
        env: Reuse this env (must be of ``result.graph``).
        on_action: Also called after each action, as by
            :func:`~factask.sim.episode.run_episode`.
        video: Write a video of the episode here.

    Returns:
        (the :class:`~factask.sim.episode.EpisodeResult` with factask's checks,
        the :class:`RavensScore` of the same episode).
    """
    from factask.sim.env import FactaskEnv
    from factask.sim.episode import run_episode

    graph = result if isinstance(result, TaskGraph) else result.graph
    own = env if env is not None else FactaskEnv(graph, robot=robot)
    snapshots: list[Mapping[str, Any]] = []

    def record(i: int, planned: Any, info: dict[str, Any]) -> None:
        snapshots.append(own.object_poses())
        if on_action is not None:
            on_action(i, planned, info)

    try:
        episode = run_episode(graph, seed, robot=robot, env=own, on_action=record,
                              video=video)
        if isinstance(result, TaskGraph):
            result = RavensTask(graph, graph_goal_queue(graph, own.solved, own.objects,
                                                         own.initial_layout))
    finally:
        if env is None:
            own.close()
    return episode, ravens_reward(result, snapshots)
