"""What ``open`` and ``closed`` share: an articulated part's opening, its target,
its check.

Two kinds move on a joint of their own: a ``drawer`` slides in its cabinet (its
opening a fraction of its travel: :func:`~factask.scene.cabinet.drawer_opening`)
and a ``door`` swings on its microwave's hinge (a fraction of its range:
:func:`~factask.scene.microwave.door_opening`); each reads its opening from its
pose and its host's. Each relation solves every part it names into one slot: its
pose opened all the way (``open``) or shut (``closed``), so that goals anchored to
a drawer (``inside`` it) are solved where it will be. The check reads the opening
against the thresholds of :mod:`factask.vocabulary.tolerances`; a part the robot
holds counts as not there yet.
"""

from __future__ import annotations

import abc
from typing import Any, ClassVar

import numpy as np

from factask.geometry import Pose
from factask.relations.base import RelationBase
from factask.relations.solving import Plan, SolveContext, SolvedFactor, make_plan
from factask.relations.status import CheckScene, Verdict
from factask.scene.cabinet import drawer_opening, drawer_pose, drawer_seat
from factask.scene.microwave import door_opening, door_pose
from factask.scene.objects import SceneObject, placement_area
from factask.scene.shelf import LEVEL_KIND, level_pose, level_seat
from factask.vocabulary.errors import InvalidValueError
from factask.vocabulary.kinds import drawer_size, kind_spec
from factask.vocabulary.variables import InCabinet, VariableSet, drawers_of

#: The kinds whose variables these relations move.
DRAWER_KIND = "drawer"
DOOR_KIND = "door"
ARTICULATED_KINDS = frozenset([DRAWER_KIND, DOOR_KIND])


def drawer_example(opening: float) -> list[dict[str, Any]]:
    """A cabinet with one drawer that starts pulled out by ``opening``, as variable
    dicts (the relations' examples)."""
    cabinet = kind_spec("cabinet").default_size
    return [{"name": "cabinet", "kind": "cabinet", "color": "brown"},
            {"name": "drawer", "kind": "drawer", "color": "brown",
             "size": list(drawer_size(cabinet, 1)),
             "initial": {"type": "in_cabinet", "cabinet": "cabinet", "level": 0,
                         "opening": opening}}]


def host_of(graph: VariableSet, part: str) -> str:
    """The cabinet or microwave variable (one object: its instance) that drawer or
    door variable ``part`` starts in.

    Raises:
        InvalidValueError: ``part`` does not start in one (validation forbids it).
    """
    start = graph.variable(part).initial
    if not isinstance(start, InCabinet):
        raise InvalidValueError(f"variable {part!r} is not a drawer in a cabinet or a door "
                                "on a microwave")
    return start.cabinet


def pose_at(graph: VariableSet, obj: SceneObject, host: SceneObject, host_pose: Pose,
            opening: float) -> Pose:
    """The pose of drawer or door ``obj`` opened by ``opening`` in ``host`` as it
    stands, or of shelf level ``obj`` in its shelf (which never opens) -- the one
    dispatch on a furniture part's kind for poses.

    Args:
        graph: The task graph (a drawer's seat, a level's).
        obj: The drawer, door or shelf level.
        host: Its cabinet, microwave or shelf.
        host_pose: The host's pose.
        opening: 0 shut .. 1 all the way open (a level ignores it).
    """
    if obj.kind == LEVEL_KIND:
        return level_pose(host, host_pose, level_seat(graph, obj.variable))
    if obj.kind == DOOR_KIND:
        return door_pose(host, host_pose, obj, opening)
    return drawer_pose(host, host_pose, drawer_seat(graph, obj.variable), obj, opening)


def opening_of(obj: SceneObject, pose: Pose, host: SceneObject, host_pose: Pose) -> float:
    """How open drawer or door ``obj`` at ``pose`` is (a fraction; the one dispatch on
    the part's kind for openings)."""
    if obj.kind == DOOR_KIND:
        return door_opening(host, host_pose, obj, pose)
    return drawer_opening(host, host_pose, obj, pose)


def _riders(ctx: SolveContext, part: SceneObject) -> set[str]:
    """What stands in drawer ``part`` as the solving has it so far (its start, or a
    target an earlier goal put it at): it rides along when the drawer slides, so it
    is no obstacle to the drawer's slot. A door carries nothing."""
    if part.kind != DRAWER_KIND:
        return set()
    pose = ctx.current[part.name]
    area = placement_area(part, pose)
    low, high = pose.pos[2] - part.size[2] / 2, pose.pos[2] + part.size[2] / 2
    return {name for name, p in ctx.current.items()
            if name != part.name and ctx.objs[name].kind not in ARTICULATED_KINDS
            and low <= p.pos[2] <= high and bool(area.contains(p.pos[:2])[0])}


class ArticulatedRelation(RelationBase):
    """Base of the relations that move drawers and doors to an opening."""

    moves_kinds: ClassVar[frozenset[str] | None] = ARTICULATED_KINDS
    other_kinds_fix: ClassVar[str] = ("name a drawer (kind drawer, initial in_cabinet of a "
                                      "cabinet) or a door (kind door, initial in_cabinet of "
                                      "a microwave)")

    #: The opening each part is solved to (the slot), a fraction of its travel.
    target_opening: ClassVar[float]

    @abc.abstractmethod
    def holds(self, opening: float) -> bool:
        """Whether a part open by ``opening`` (a fraction) meets the goal."""

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        """One slot per part: its pose at :attr:`target_opening` in its host as the
        host stands. The slot overlaps the host and its other parts (it moves among
        them) and the part's own start."""
        slots, supports, ignore = [], [], []
        for j, obj in enumerate(movers):
            host = host_of(ctx.graph, obj.variable)
            slots.append(pose_at(ctx.graph, obj, ctx.objs[host], ctx.current[host],
                                 self.target_opening))
            supports.append(host)
            siblings = {i for d in drawers_of(ctx.graph.variables, host) for i in d.instances}
            ignore.append({host, *siblings, *_riders(ctx, obj), f"@slot{j}",
                           *(f"@start:{o.name}" for o in movers)})
        n = len(movers)
        return make_plan(slots, [None] * n, supports, ignore, np.eye(n, dtype=bool),
                         check_yaw=False)

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        """A part is placed when its opening meets the goal and the robot does not
        hold it."""
        placed: dict[str, int | None] = {}
        problems = []
        for i, name in enumerate(solved.objects):
            host = solved.supports[i]
            opening = opening_of(scene.objects[name], scene.pose(name), scene.objects[host],
                                 scene.pose(host))
            if name in scene.held:
                problems.append(f"{name}: held by the robot")
            elif self.holds(opening):
                placed[name] = i
            else:
                problems.append(f"{name}: {opening:.0%} open ({self.kind()} "
                                f"{self._threshold_text()})")
        return Verdict(placed, problems)

    @abc.abstractmethod
    def _threshold_text(self) -> str:
        """The threshold in words, for the check's details."""
