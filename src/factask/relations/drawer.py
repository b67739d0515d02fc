"""What ``open`` and ``closed`` share: a drawer's opening, its target, its check.

A drawer (kind ``drawer``) slides in its cabinet; its opening is a fraction of its
travel (:func:`~factask.scene.cabinet.drawer_opening`, from its pose and its
cabinet's). Each relation solves every drawer it names into one slot: the pose of
that drawer pulled out all the way (``open``) or pushed all the way in
(``closed``), so that goals anchored to the drawer (``inside`` it) are solved
where it will be. The check reads the opening against the thresholds of
:mod:`factask.vocabulary.tolerances`; a drawer the robot holds counts as not there
yet.
"""

from __future__ import annotations

import abc
from typing import Any, ClassVar

import numpy as np

from factask.relations.base import RelationBase
from factask.relations.solving import Plan, SolveContext, SolvedFactor, make_plan
from factask.relations.status import CheckScene, Verdict
from factask.scene.cabinet import drawer_opening, drawer_pose, drawer_seat
from factask.scene.objects import SceneObject
from factask.vocabulary.kinds import drawer_size, kind_spec
from factask.vocabulary.variables import drawers_of

#: The kind whose variables these relations move.
DRAWER_KIND = "drawer"


def drawer_example(opening: float) -> list[dict[str, Any]]:
    """A cabinet with one drawer that starts pulled out by ``opening``, as variable
    dicts (the relations' examples)."""
    cabinet = kind_spec("cabinet").default_size
    return [{"name": "cabinet", "kind": "cabinet", "color": "brown"},
            {"name": "drawer", "kind": "drawer", "color": "brown",
             "size": list(drawer_size(cabinet, 1)),
             "initial": {"type": "in_cabinet", "cabinet": "cabinet", "level": 0,
                         "opening": opening}}]


class DrawerRelation(RelationBase):
    """Base of the relations that slide drawers to an opening."""

    moves_kinds: ClassVar[frozenset[str] | None] = frozenset([DRAWER_KIND])
    other_kinds_fix: ClassVar[str] = "name a drawer variable (kind drawer, initial in_cabinet)"

    #: The opening each drawer is solved to (the slot), a fraction of its travel.
    target_opening: ClassVar[float]

    @abc.abstractmethod
    def holds(self, opening: float) -> bool:
        """Whether a drawer pulled out by ``opening`` (a fraction) meets the goal."""

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        """One slot per drawer: its pose at :attr:`target_opening` in its cabinet as
        the cabinet stands. The slot overlaps the cabinet and its other drawers (it
        slides among them) and the drawer's own start."""
        slots, supports, ignore = [], [], []
        for j, obj in enumerate(movers):
            seat = drawer_seat(ctx.graph, obj.variable)
            cabinet = ctx.objs[seat.cabinet]
            slots.append(drawer_pose(cabinet, ctx.current[seat.cabinet], seat, obj,
                                     self.target_opening))
            supports.append(seat.cabinet)
            siblings = {i for d in drawers_of(ctx.graph.variables, seat.cabinet)
                        for i in d.instances}
            ignore.append({seat.cabinet, *siblings, f"@slot{j}",
                           *(f"@start:{o.name}" for o in movers)})
        n = len(movers)
        return make_plan(slots, [None] * n, supports, ignore, np.eye(n, dtype=bool),
                         check_yaw=False)

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        """A drawer is placed when its opening meets the goal and the robot does not
        hold it."""
        placed: dict[str, int | None] = {}
        problems = []
        for i, name in enumerate(solved.objects):
            cabinet = solved.supports[i]
            opening = drawer_opening(scene.objects[cabinet], scene.pose(cabinet),
                                     scene.objects[name], scene.pose(name))
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
