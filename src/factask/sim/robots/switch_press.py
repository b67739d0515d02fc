"""Pressing a switch: push its button down with the cup, or hold it and pull it up.

A switch is a push button on a vertical slide joint in its host (a stove, a lamp:
:mod:`factask.sim.build.switch`) whose dry friction keeps it where it is left.
Switching on is a top-down press: the cup comes down on the button's top (a
guarded descent, as for a pick) and keeps going at :data:`PRESS_SPEED` until the
top is :data:`PRESS_OVERSHOOT` below where the button is to end — the joint's
limit stops the button there, and the cup's contact, not the suction, moves it —
then it lifts off. Switching off pulls the button back up: the cup holds its top
(the suction weld takes the button's own body, as it takes a drawer's), rises
straight up to where the top is to end, and lets go.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from factask.geometry import Pose
from factask.sim.robots.primitive import (
    APPROACH_HEIGHT,
    DEFAULT_CALLBACK_EVERY,
    DEFAULT_MAX_STEPS,
    GUARDED_SPEED,
    PICK_OVERSHOOT,
    RETREAT,
    PrimitiveAbort,
    PrimitiveResult,
    SuctionRobot,
)

#: Speed (m/s) of the press and of the pull: slow, so the button's joint limit,
#: not the cup's momentum, ends the move.
PRESS_SPEED = 0.05
#: How far (m) past where the button is to end the cup pushes (the joint limit
#: stops the button; the margin makes sure it gets there against its friction).
PRESS_OVERSHOOT = 0.001
#: Time (s) the cup stays at the bottom of a press, or holds the pulled button, so
#: the button comes to rest before it is let go.
PRESS_HOLD = 0.1


@dataclass(frozen=True)
class PressAction:
    """One planned press (or pull) of a switch and why it was chosen.

    Attributes:
        press: (x, y, z, yaw) of the tip on the button's top.
        to: (x, y, z, yaw) of the tip where the button's top is to end (below
            ``press``: pushed down; above: pulled up).
        obj: The switch.
        factor: The factor it works on.
        purpose: In words.
    """

    press: np.ndarray
    to: np.ndarray
    obj: str
    factor: str
    purpose: str

    def as_env_action(self) -> dict[str, np.ndarray]:
        """The env's action: ``press`` and ``press_to``."""
        return {"press": self.press, "press_to": self.to}


def press_switch(robot: SuctionRobot, press: Pose, to: Pose,
                 on_step: Callable[[], None] | None = None,
                 max_steps: int = DEFAULT_MAX_STEPS,
                 callback_every: int = DEFAULT_CALLBACK_EVERY) -> PrimitiveResult:
    """Press the button whose top is at ``press`` down to ``to`` (or pull it up).

    Args:
        robot: The robot.
        press: Tip pose on the button's top (position; the tool keeps its yaw).
        to: Where the button's top is to end (its z; x, y are ``press``'s).
        on_step: Called every ``callback_every`` physics steps.
        max_steps: Physics-step budget.
        callback_every: Physics steps between ``on_step`` calls.

    Returns:
        The result; failures (nothing under the cup, ...) come back as ``ok=False``
        with a reason.
    """
    return robot.execute(lambda: _run(robot, press, to), on_step, max_steps, callback_every)


def _run(robot: SuctionRobot, press: Pose, to: Pose) -> int | None:
    """Down on the button, push it (or hold it and pull it), up; raises PrimitiveAbort."""
    if robot.gripper.held is not None:
        robot.gripper.release()
    up = np.array([0.0, 0.0, 1.0])
    yaw = robot._cmd_yaw
    robot._transfer(press.pos + APPROACH_HEIGHT * up, yaw)
    if robot._follow(robot._line(press.pos - PICK_OVERSHOOT * up, yaw, GUARDED_SPEED),
                     stop=robot.gripper.cup_in_contact):
        robot._hold_here()
    # Only a body on a slide joint of its own is pushed (never the table, an object).
    if not robot.gripper.touched_sliders():
        robot._follow(robot._path([(robot._cmd_pos + APPROACH_HEIGHT * up, yaw)]))
        raise PrimitiveAbort("no switch under the cup")
    # The cup's tip where it touched the top; the tip ends where the top is to end
    # (the planned heights, not the touch's: a guarded stop may already have nudged
    # the button).
    start = robot._cmd_pos.copy()
    end = np.array([start[0], start[1], to.pos[2]])
    held = None
    if to.pos[2] < press.pos[2]:  # on: push down past the end, the joint limit stops it
        robot._follow(robot._line(end - PRESS_OVERSHOOT * up, yaw, PRESS_SPEED))
        robot._hold(max(1, round(PRESS_HOLD / robot.dt)))
    else:  # off: hold the top and pull it up
        if not robot.gripper.grasp(slider=True):
            robot._follow(robot._path([(robot._cmd_pos + APPROACH_HEIGHT * up, yaw)]))
            raise PrimitiveAbort("no switch under the cup")
        held = robot.gripper.held
        robot._follow(robot._line(end, yaw, PRESS_SPEED))
        robot._settle()
        robot._hold(max(1, round(PRESS_HOLD / robot.dt)))
        robot.suction_off()
    robot._follow(robot._path([(robot._cmd_pos + RETREAT * up, yaw)]))
    return held
