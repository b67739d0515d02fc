"""What ``switched_on`` and ``switched_off`` share: a switch's press, its target, its check.

A switch (kind ``switch``) is the push button of a switchable fixture (a stove, a
lamp); how far it is pressed is a fraction of its travel
(:func:`~factask.scene.switch.switch_pressed`, from its pose and its host's). Each
relation solves every switch it names into one slot: the pose of that button
pressed all the way down (``switched_on``) or all the way up (``switched_off``).
The check reads the press against the thresholds of
:mod:`factask.vocabulary.tolerances`; a switch the robot holds counts as not there
yet (a button is on once the cup has let it go and it stays down).
"""

from __future__ import annotations

import abc
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from factask.relations.base import RelationBase
from factask.relations.solving import Plan, SolveContext, SolvedFactor, make_plan
from factask.relations.status import CheckScene, Verdict
from factask.scene.objects import SceneObject
from factask.scene.switch import switch_host, switch_pose, switch_pressed

if TYPE_CHECKING:  # the graph model sits above the relations
    from factask.vocabulary.variables import StateVariable

#: The kind whose variables these relations move.
SWITCH_KIND = "switch"


def switch_example(on: bool) -> list[dict[str, Any]]:
    """A stove whose switch starts on or off, as variable dicts (the relations'
    examples)."""
    return [{"name": "stove", "kind": "stove", "color": "gray"},
            {"name": "knob", "kind": "switch", "color": "red",
             "initial": {"type": "mounted_on", "host": "stove", "on": on}}]


class SwitchRelation(RelationBase):
    """Base of the relations that press switches to a state."""

    moves_kinds: ClassVar[frozenset[str] | None] = frozenset([SWITCH_KIND])
    other_kinds_fix: ClassVar[str] = ("name a switch variable (kind switch, initial mounted_on "
                                      "a stove or lamp), not the fixture itself")

    #: How far each switch is solved to be pressed (the slot), a fraction of its travel.
    target_pressed: ClassVar[float]

    @abc.abstractmethod
    def holds(self, pressed: Any) -> Any:
        """Whether a switch pressed down by ``pressed`` meets the goal.

        Args:
            pressed: A fraction of the button's travel, or an array of them (the
                batched check applies the same threshold).

        Returns:
            A bool, or an array of them.
        """

    def met_at_start(self, variables: Mapping[str, StateVariable]) -> str | None:
        """The first switch when every switch the goal names starts in the state it
        asks for (``mounted_on`` with ``on`` = the goal's): every reset would be
        refused; else None.

        Args:
            variables: The graph's variables by name.
        """
        wanted = self.target_pressed > 0.5
        starts = [getattr(getattr(variables.get(o), "initial", None), "on", None)
                  for o in self.objects]
        return self.objects[0] if starts and all(s is wanted for s in starts) else None

    def met_at_start_problem(self, host: str) -> tuple[str, str]:
        """Switches that start as the goal asks: say so, with the fix."""
        state = "on" if self.target_pressed > 0.5 else "off"
        return (f"met at the start: every switch it names starts {state} ({host!r} "
                f"among them)",
                f'start them {"off" if state == "on" else "on"} (initial "on": '
                f'{"false" if state == "on" else "true"}), or choose another goal')

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        """One slot per switch: its pose at :attr:`target_pressed` on its host as the
        host stands. The slot overlaps the host (the button sinks into it) and the
        switch's own start."""
        slots, supports, ignore = [], [], []
        for j, obj in enumerate(movers):
            host = switch_host(ctx.graph, obj.variable)
            slots.append(switch_pose(ctx.objs[host], ctx.current[host], self.target_pressed))
            supports.append(host)
            ignore.append({host, f"@slot{j}", *(f"@start:{o.name}" for o in movers)})
        n = len(movers)
        return make_plan(slots, [None] * n, supports, ignore, np.eye(n, dtype=bool),
                         check_yaw=False)

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        """A switch is placed when it is on its mount, its press meets the goal and
        the robot does not hold it."""
        placed: dict[str, int | None] = {}
        problems = []
        for i, name in enumerate(solved.objects):
            host = solved.supports[i]
            pressed, off_mount = switch_pressed(scene.objects[host], scene.pose(host),
                                                scene.pose(name))
            if name in scene.held:
                problems.append(f"{name}: held by the robot")
            elif off_mount > self.tolerances.xy:
                # Its joint keeps a button on its mount; a pose off it is no state of
                # this switch (a scene moved by hand), and its press means nothing.
                problems.append(f"{name}: {off_mount * 100:.1f} cm off its mount on {host}")
            elif self.holds(pressed):
                placed[name] = i
            else:
                problems.append(f"{name}: pressed {pressed:.0%} ({self.kind()} "
                                f"{self._threshold_text()})")
        return Verdict(placed, problems)

    @abc.abstractmethod
    def _threshold_text(self) -> str:
        """The threshold in words, for the check's details."""
