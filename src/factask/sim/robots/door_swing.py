"""Swinging a door: hold its handle with the suction cup, move along the arc about
its hinge, let go.

A microwave's door has a flat handle tab at the top of its free end; the cup comes
down on its top (a guarded descent, as for a pick), holds it (the suction weld
takes the door's own body, which turns on a hinge joint, not a free object), then
moves level along the circle about the hinge's vertical axis to where the handle
is to end -- out to open the door, back to shut it -- at :data:`SWING_SPEED`, and
lets go. The tool turns with the door (its yaw follows the door's angle), so the
weld never twists against the hinge. The arc is followed in short straight pieces
(chords of :data:`SWING_PIECE`) so an arm's joint-space motions stay on it, as a
drawer's slide is (:mod:`factask.sim.robots.slide_pull`).
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
    RETREAT,
    PrimitiveAbort,
    PrimitiveResult,
    SuctionRobot,
)

#: Speed (m/s) of the handle along the arc: a drawer's slide speed, for the same
#: reason (what stands in the microwave is not shaken, the door does not swing on).
SWING_SPEED = 0.1
#: The arc is followed in chords this long (m): 1 mm off the circle at most for a
#: 15 cm door (the suction weld takes that up).
SWING_PIECE = 0.02
#: Time (s) the cup keeps holding once there, so the door comes to rest before it is
#: let go (its hinge's damping stops it).
SWING_HOLD = 0.1


@dataclass(frozen=True)
class SwingAction:
    """One planned swing of a door and why it was chosen.

    Attributes:
        grasp: (x, y, z, yaw) of the tip on the handle's top.
        to: (x, y, z, yaw) of the tip where the handle is to end (its z and yaw are
            not used: the move stays level and the tool turns with the door).
        hinge: (x, y) of the hinge's axis, the centre of the arc.
        obj: The door.
        factor: The factor it works on.
        purpose: In words.
    """

    grasp: np.ndarray
    to: np.ndarray
    hinge: np.ndarray
    obj: str
    factor: str
    purpose: str

    def as_env_action(self) -> dict[str, np.ndarray]:
        """The env's action: ``grasp``, ``swing_to`` and ``hinge``."""
        return {"grasp": self.grasp, "swing_to": self.to, "hinge": self.hinge}


def door_swing(robot: SuctionRobot, grasp: Pose, to: Pose, hinge: np.ndarray,
               on_step: Callable[[], None] | None = None,
               max_steps: int = DEFAULT_MAX_STEPS,
               callback_every: int = DEFAULT_CALLBACK_EVERY) -> PrimitiveResult:
    """Hold the handle at ``grasp``, swing it about ``hinge`` to ``to``'s bearing, let go.

    Args:
        robot: The robot.
        grasp: Tip pose on the handle's top (position; the tool keeps its yaw on the
            way down).
        to: Where the tip is to end (its bearing from the hinge; the radius is the
            handle's own).
        hinge: (x, y) of the hinge's vertical axis.
        on_step: Called every ``callback_every`` physics steps.
        max_steps: Physics-step budget.
        callback_every: Physics steps between ``on_step`` calls.

    Returns:
        The result; failures (no handle under the cup, ...) come back as
        ``ok=False`` with a reason.
    """
    centre = np.asarray(hinge, dtype=float).reshape(-1)[:2]
    return robot.execute(lambda: _run(robot, grasp, to, centre), on_step, max_steps,
                         callback_every)


def arc_points(start: np.ndarray, end_xy: np.ndarray, hinge: np.ndarray,
               piece: float = SWING_PIECE) -> tuple[list[np.ndarray], list[float]]:
    """Points along the circle about ``hinge`` through ``start`` (level at its z) to
    the bearing of ``end_xy``, the shorter way round, about ``piece`` apart.

    Args:
        start: (3,) the first point (not in the result).
        end_xy: (2,) any point on the bearing to end at.
        hinge: (2,) the circle's centre.
        piece: Chord length (m) between points, at most.

    Returns:
        The points (each (3,)) and, per point, the angle (rad) turned since ``start``.
    """
    rel = start[:2] - hinge
    radius = float(np.linalg.norm(rel))
    a0 = math.atan2(rel[1], rel[0])
    end = np.asarray(end_xy, dtype=float) - hinge
    turn = wrap_angle(math.atan2(end[1], end[0]) - a0)
    n = max(1, math.ceil(abs(turn) * radius / piece))
    points, angles = [], []
    for k in range(1, n + 1):
        a = turn * k / n
        points.append(np.array([hinge[0] + radius * math.cos(a0 + a),
                                hinge[1] + radius * math.sin(a0 + a), start[2]]))
        angles.append(a)
    return points, angles


def _run(robot: SuctionRobot, grasp: Pose, to: Pose, hinge: np.ndarray) -> int:
    """Down on the handle, hold it, swing, let go, up; raises PrimitiveAbort."""
    if robot.gripper.held is not None:
        robot.gripper.release()
    up = np.array([0.0, 0.0, 1.0])
    yaw = robot._cmd_yaw
    robot._transfer(grasp.pos + APPROACH_HEIGHT * up, yaw)
    if robot._follow(robot._line(grasp.pos - PICK_OVERSHOOT * up, yaw, GUARDED_SPEED),
                     stop=robot.gripper.cup_in_contact):
        robot._hold_here()
    if not robot.gripper.grasp(slider=True):
        robot._follow(robot._path([(robot._cmd_pos + APPROACH_HEIGHT * up, yaw)]))
        raise PrimitiveAbort("no door handle under the cup")
    held = robot.gripper.held
    assert held is not None
    yaw = robot._cmd_yaw
    points, angles = arc_points(robot._cmd_pos.copy(), to.pos[:2], hinge)
    for point, turned in zip(points, angles, strict=True):
        # The tool turns with the door, so the weld holds the handle as it was taken.
        robot._follow(robot._line(point, yaw + turned, SWING_SPEED))
    robot._settle()
    robot._hold(max(1, round(SWING_HOLD / robot.dt)))
    robot.suction_off()
    robot._follow(robot._path([(robot._cmd_pos + RETREAT * up, robot._cmd_yaw)]))
    return held
