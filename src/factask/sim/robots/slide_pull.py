"""Sliding a drawer: hold its handle with the suction cup, move straight along its
joint, let go.

The drawer's handle is a flat tab at its front; the cup comes down on its top
(a guarded descent, as for a pick), holds it (the suction weld takes the drawer's
own body, which slides on a joint, not a free object), then moves straight
and level to where the handle is to end — out to open the drawer, in to close it
— at :data:`SLIDE_SPEED`, and lets go. Anything in the drawer rides with it on
its floor. The move is followed in short pieces so an arm's joint-space motions
stay on the line (as a push's do).
"""

from __future__ import annotations

import math
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

#: Speed (m/s) of the slide: slow enough that an object in the drawer rides along
#: on its floor's friction rather than slipping when the drawer starts and stops.
SLIDE_SPEED = 0.1
#: The slide's straight line is followed in pieces this long (m).
SLIDE_PIECE = 0.02
#: Time (s) the cup keeps holding once there, so the drawer comes to rest before
#: it is let go (its joint's damping stops it).
SLIDE_HOLD = 0.1


@dataclass(frozen=True)
class SlideAction:
    """One planned slide of a drawer and why it was chosen.

    Attributes:
        grasp: (x, y, z, yaw) of the tip on the handle's top.
        to: (x, y, z, yaw) of the tip where the handle is to end (its z is not used:
            the move stays level).
        obj: The drawer.
        factor: The factor it works on.
        purpose: In words.
    """

    grasp: np.ndarray
    to: np.ndarray
    obj: str
    factor: str
    purpose: str

    def as_env_action(self) -> dict[str, np.ndarray]:
        """The env's action: ``grasp`` and ``slide_to``."""
        return {"grasp": self.grasp, "slide_to": self.to}


def slide_pull(robot: SuctionRobot, grasp: Pose, to: Pose,
               on_step: Callable[[], None] | None = None,
               max_steps: int = DEFAULT_MAX_STEPS,
               callback_every: int = DEFAULT_CALLBACK_EVERY) -> PrimitiveResult:
    """Hold the handle at ``grasp``, move level to above ``to``'s x, y, let go.

    Args:
        robot: The robot.
        grasp: Tip pose on the handle's top (position; the tool keeps its yaw).
        to: Where the tip is to end (its x, y).
        on_step: Called every ``callback_every`` physics steps.
        max_steps: Physics-step budget.
        callback_every: Physics steps between ``on_step`` calls.

    Returns:
        The result; failures (no handle under the cup, ...) come back as
        ``ok=False`` with a reason.
    """
    return robot.execute(lambda: _run(robot, grasp, to), on_step, max_steps, callback_every)


def _run(robot: SuctionRobot, grasp: Pose, to: Pose) -> int:
    """Down on the handle, hold it, slide, let go, up; raises PrimitiveAbort."""
    if robot.gripper.held is not None:
        robot.gripper.release()
    up = np.array([0.0, 0.0, 1.0])
    yaw = robot._cmd_yaw
    # A low drawer's handle sits under the rest of its cabinet: an arm leans its
    # tool out so its wrist clears the cabinet's face (straight down elsewhere).
    robot.tool_lean = robot.lean_clear_of(grasp.pos, yaw)
    robot._transfer(grasp.pos + APPROACH_HEIGHT * up, yaw)
    if robot._follow(robot._line(grasp.pos - PICK_OVERSHOOT * up, yaw, GUARDED_SPEED),
                     stop=robot.gripper.cup_in_contact):
        robot._hold_here()
    if not robot.gripper.grasp(slider=True):
        robot._follow(robot._path([(robot._cmd_pos + APPROACH_HEIGHT * up, yaw)]))
        raise PrimitiveAbort("no drawer handle under the cup")
    held = robot.gripper.held
    assert held is not None
    start = robot._cmd_pos.copy()
    goal = np.array([to.pos[0], to.pos[1], start[2]])
    pieces = max(1, math.ceil(float(np.linalg.norm(goal - start)) / SLIDE_PIECE))
    for k in range(1, pieces + 1):
        robot._follow(robot._line(start + (goal - start) * k / pieces, yaw, SLIDE_SPEED))
    robot._settle()
    robot._hold(max(1, round(SLIDE_HOLD / robot.dt)))
    robot.suction_off()
    robot._follow(robot._path([(robot._cmd_pos + RETREAT * up, yaw)]))
    return held
