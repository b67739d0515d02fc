"""Suction robots: build one into a scene, bind its controller to the compiled model.

Two robots share one contract (see docs/robot.md):

- ``"floating"``: a mocap-driven suction cup (the cup body IS the mocap body; a
  held object is welded to it). Fast mode, no arm dynamics
  (:mod:`factask.sim.robots.floating_cup`).
- an arm (``"ur10e"``, alias ``"arm"``; ``"ur5e"``, alias ``"arm_ur5e"``): a
  UR-type 6-DoF arm with position servos that track joint trajectories
  (:mod:`factask.sim.robots.arm_controller`).

Which names exist is the registry's business (:mod:`factask.sim.robots.registry`); the
pick-and-place primitive both share is :mod:`factask.sim.robots.primitive`. Both carry a
``suction_tip`` site and a ``suction`` weld (:mod:`factask.sim.robots.suction`).
"""

from __future__ import annotations

import mujoco

from factask.sim.robots.arm import build_arm
from factask.sim.robots.arm_controller import ArmSuctionRobot
from factask.sim.robots.floating_cup import FLOATING_BODY, FLOATING_HOME, FloatingSuctionRobot
from factask.sim.robots.primitive import PrimitiveResult, SuctionRobot
from factask.sim.robots.registry import RobotError, robot_entry
from factask.sim.robots.suction import add_suction_weld, add_tool

__all__ = [
    "ArmSuctionRobot",
    "FloatingSuctionRobot",
    "PrimitiveResult",
    "RobotError",
    "SuctionRobot",
    "attach_robot",
    "make_robot",
]


def attach_robot(spec: mujoco.MjSpec, kind: str) -> None:
    """Add a suction robot (tool, ``suction_tip`` site, ``suction`` weld) to ``spec``.

    Args:
        spec: The scene's spec; the robot base sits at the world origin.
        kind: A name of the robot registry (:data:`factask.sim.robots.registry.ROBOT_NAMES`).

    Raises:
        RobotError: Unknown kind.
    """
    entry = robot_entry(kind)
    if entry.arm is None:
        cup = spec.worldbody.add_body(name=FLOATING_BODY, mocap=True, pos=list(FLOATING_HOME))
        add_tool(cup, down=False)
        add_suction_weld(spec, cup)
    else:
        build_arm(spec, entry.arm)


def make_robot(kind: str, model: mujoco.MjModel, data: mujoco.MjData) -> SuctionRobot:
    """Bind a controller to a compiled model that :func:`attach_robot` built.

    The robot is reset (home pose, suction off) before it is returned.

    Args:
        kind: The kind given to :func:`attach_robot`.
        model: Compiled model.
        data: Its data.

    Returns:
        The controller.

    Raises:
        RobotError: Unknown kind or a robot element missing from the model.
    """
    entry = robot_entry(kind)
    robot: SuctionRobot
    if entry.arm is None:
        robot = FloatingSuctionRobot(model, data)
    else:
        robot = ArmSuctionRobot(model, data, entry.arm)
    robot.reset()
    return robot
