"""A low pick-and-place (Ravens' ``PickPlace(height=0.02)`` of its rope tasks).

The usual primitive (:class:`~factask.sim.robots.primitive.SuctionRobot`) carries an
object at least 5 cm over the table, clear of everything. A rope's segment is
1-2 cm long: lifted that high, it pulls its neighbours off the table into a
dangling chain that falls in a heap where it is set down. This primitive lifts
the grasped segment only ``lift`` metres (the env action's ``lift``), carries it
over at that height and sets it down, so the rest of the rope slides after it
along the table. The way to the pick is the usual transfer (the cup is empty).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from factask.geometry import Pose, wrap_angle
from factask.sim.robots.primitive import (
    APPROACH_HEIGHT,
    DEFAULT_CALLBACK_EVERY,
    DEFAULT_MAX_STEPS,
    GUARDED_SPEED,
    PICK_OVERSHOOT,
    RELEASE_MAX_TIME,
    RELEASE_SPEED_FLAT,
    RETREAT,
    PrimitiveAbort,
    PrimitiveResult,
    SuctionRobot,
)

#: Lift (m) of a rope segment while carried (Ravens' rope primitive: 2 cm).
ROPE_LIFT = 0.02
#: Speed (m/s) of the carry: slow, so the rope trailing behind does not run on and
#: pile up over the segment when it stops (Ravens' rope primitive is slow too).
CARRY_SPEED = 0.08
#: The carry's straight line is followed in pieces this long (m).
CARRY_PIECE = 0.02


@dataclass(frozen=True)
class CarryAction:
    """One planned low pick-and-place and why it was chosen.

    Attributes:
        pick: (x, y, z, yaw) of the tip at the grasp.
        place: (x, y, z, yaw) of the tip at the release.
        lift: How high (m) the object is carried.
        obj: The object moved.
        factor: The factor it works on.
        purpose: In words.
    """

    pick: np.ndarray
    place: np.ndarray
    lift: float
    obj: str
    factor: str
    purpose: str

    def as_env_action(self) -> dict[str, np.ndarray]:
        """The env's action: ``pick``, ``place`` and ``lift``."""
        return {"pick": self.pick, "place": self.place, "lift": np.array([self.lift])}


def low_pick_and_place(robot: SuctionRobot, pick: Pose, place: Pose, lift: float,
                       on_step: Callable[[], None] | None = None,
                       max_steps: int = DEFAULT_MAX_STEPS,
                       callback_every: int = DEFAULT_CALLBACK_EVERY) -> PrimitiveResult:
    """Pick at ``pick``, carry ``lift`` metres over the table, release at ``place``.

    Args:
        robot: The robot.
        pick: Tip pose at the grasp (position and tool yaw).
        place: Tip pose at the release; the object turns by ``place.yaw - pick.yaw``.
        lift: Height (m) the grasped object is raised for the carry.
        on_step: Called every ``callback_every`` physics steps.
        max_steps: Physics-step budget.
        callback_every: Physics steps between ``on_step`` calls.

    Returns:
        The result; failures come back as ``ok=False`` with a reason.
    """
    return robot.execute(lambda: _run(robot, pick, place, lift), on_step, max_steps,
                         callback_every)


def _carry(robot: SuctionRobot, goal: np.ndarray, yaw0: float, yaw1: float) -> None:
    """Straight to ``goal`` at :data:`CARRY_SPEED`, turning from ``yaw0`` to ``yaw1`` on
    the way, in pieces of :data:`CARRY_PIECE` (the arm's joint-space moves stay on
    the line, as a push's do)."""
    start = robot._cmd_pos.copy()
    pieces = max(1, math.ceil(float(np.linalg.norm(goal - start)) / CARRY_PIECE))
    for k in range(1, pieces + 1):
        f = k / pieces
        robot._follow(robot._line(start + (goal - start) * f, yaw0 + (yaw1 - yaw0) * f,
                                  CARRY_SPEED))


def _run(robot: SuctionRobot, pick: Pose, place: Pose, lift: float) -> int:
    """Down, grasp, up ``lift``, over, down, release; raises PrimitiveAbort."""
    if robot.gripper.held is not None:
        robot.gripper.release()
    up = np.array([0.0, 0.0, 1.0])
    yaw0 = robot._cmd_yaw
    yaw1 = yaw0 + wrap_angle(place.yaw - pick.yaw)
    robot._transfer(pick.pos + APPROACH_HEIGHT * up, yaw0)
    if robot._follow(robot._line(pick.pos - PICK_OVERSHOOT * up, yaw0, GUARDED_SPEED),
                     stop=robot.gripper.cup_in_contact):
        robot._hold_here()
    if not robot.suction_on():
        robot._follow(robot._path([(robot._cmd_pos + APPROACH_HEIGHT * up, yaw0)]))
        raise PrimitiveAbort("nothing to grasp at pick pose")
    grasped = robot.gripper.held
    assert grasped is not None
    low = place.pos + lift * up
    robot._follow(robot._path([(robot._cmd_pos + lift * up, yaw0)]))
    _carry(robot, low, yaw0, yaw1)
    robot._settle()
    if not robot.gripper.held_in_contact() and robot._follow(
            robot._line(place.pos, yaw1, GUARDED_SPEED), stop=robot.gripper.held_in_contact):
        robot._hold_here()
    robot._settle()
    if robot.gripper.held is None:
        raise PrimitiveAbort("object lost during transport")
    robot._wait_for_rest(RELEASE_SPEED_FLAT, RELEASE_MAX_TIME)
    robot.suction_off()
    robot._follow(robot._path([(robot._cmd_pos + RETREAT * up, robot._cmd_yaw)]))
    robot._wait_for_rest()
    return grasped
