"""The spatula end effector and the push primitive (Ravens' ``Spatula`` and ``push``).

A task whose goals push things (:func:`needs_spatula`: a ``pile_in_zone`` goal,
the way a Ravens task sets ``ee = Spatula``) gets a spatula: a thin vertical
blade fixed under the suction tip, :data:`BLADE_DEPTH` deep, its long side
across the tool's x axis. A push (:func:`push`) goes over to just above the
start, lowers the blade until it is :data:`BLADE_LIFT` above the table, moves it
in a straight line to the end at :data:`PUSH_SPEED` (cut into short pieces so
an arm's joint-space moves stay on the line and the blade stays along the
table), lifts it and waits until the objects rest. Both robots push the same way:
the primitive drives the robot's own motion hooks
(:class:`~factask.sim.robots.primitive.SuctionRobot`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import mujoco
import numpy as np

from factask.geometry import Pose, rotate, wrap_angle
from factask.graph.taskgraph import TaskGraph
from factask.sim.robots.primitive import (
    APPROACH_HEIGHT,
    DEFAULT_CALLBACK_EVERY,
    DEFAULT_MAX_STEPS,
    GUARDED_SPEED,
    PrimitiveResult,
    SuctionRobot,
)
from factask.sim.robots.suction import ROBOT_CONAFFINITY, ROBOT_CONTYPE, TIP_SITE
from factask.vocabulary.world import TABLE_Z

#: Relations whose goals are reached by pushing (the task gets a spatula).
PUSH_RELATIONS = ("pile_in_zone",)
#: Name of the spatula's blade geom.
BLADE_GEOM = "spatula_blade"
#: Blade thickness along the push (m), width across it (m), depth below the tip (m).
BLADE_THICKNESS = 0.006
BLADE_WIDTH = 0.07
BLADE_DEPTH = 0.025
#: Height (m) of the blade's lower edge over the table while pushing. At 3 mm the
#: floating cup's blade rode over a lone 1 cm block after 5-25 cm (15 of 16 tries).
BLADE_LIFT = 0.002
#: Speed of the push itself (m/s): slow enough that small blocks slide, not fly.
PUSH_SPEED = 0.15
#: Length (m) of the straight pieces a push is cut into.
PUSH_PIECE = 0.02
#: Lift (m) of the blade after the push before the primitive ends.
PUSH_RETREAT = 0.03


def needs_spatula(graph: TaskGraph) -> bool:
    """True when some goal of ``graph`` is reached by pushing (Ravens' ``ee = Spatula``)."""
    return any(f.goal.type in PUSH_RELATIONS for f in graph.factors)


def add_spatula(spec: mujoco.MjSpec) -> mujoco.MjsGeom:
    """Fix the spatula's blade under the ``suction_tip`` site of the robot in ``spec``.

    Args:
        spec: A scene spec with a robot attached.

    Returns:
        The blade geom (on the body carrying the tip site).
    """
    site = spec.site(TIP_SITE)
    quat = np.asarray(site.quat, dtype=float)
    quat = quat / np.linalg.norm(quat)
    # The tip frame has z up the tool: the blade hangs below the tip, along -z.
    centre = np.asarray(site.pos, dtype=float) + rotate(quat, np.array(
        [0.0, 0.0, -BLADE_DEPTH / 2]))
    return site.parent.add_geom(
        name=BLADE_GEOM, type=mujoco.mjtGeom.mjGEOM_BOX,
        size=[BLADE_THICKNESS / 2, BLADE_WIDTH / 2, BLADE_DEPTH / 2],
        pos=list(centre), quat=list(quat), rgba=[0.75, 0.75, 0.8, 1], mass=0.02,
        contype=ROBOT_CONTYPE, conaffinity=ROBOT_CONAFFINITY, friction=[0.5, 0.005, 0.0001],
    )


def push_yaw(start: np.ndarray, end: np.ndarray, current: float) -> float:
    """Tool yaw of a push from ``start`` to ``end`` (the blade faces the motion),
    the one of the blade's two equivalent yaws closest to ``current`` (unwrapped)."""
    d = np.asarray(end[:2], dtype=float) - np.asarray(start[:2], dtype=float)
    yaw = math.atan2(d[1], d[0])
    turn = wrap_angle(yaw - current)
    if turn > math.pi / 2:  # the blade is symmetric: half a turn is the same blade
        turn -= math.pi
    elif turn < -math.pi / 2:
        turn += math.pi
    return current + turn


def push(robot: SuctionRobot, start: Pose, end: Pose,
         on_step: Callable[[], None] | None = None, max_steps: int = DEFAULT_MAX_STEPS,
         callback_every: int = DEFAULT_CALLBACK_EVERY) -> PrimitiveResult:
    """Push along the table from ``start`` to ``end`` (their x, y; z and yaw unused).

    Args:
        robot: The robot (with a spatula: :func:`add_spatula`).
        start: Where the blade comes down.
        end: Where it stops before lifting.
        on_step: Called every ``callback_every`` physics steps (video frames ...).
        max_steps: Physics-step budget; exceeding it fails the primitive.
        callback_every: Physics steps between ``on_step`` calls.

    Returns:
        The result (``grasped_body`` always None); failures (unreachable pose,
        physics blow-up, step limit) come back as ``ok=False`` with a reason.
    """
    a, b = np.asarray(start.pos, dtype=float), np.asarray(end.pos, dtype=float)

    def body() -> None:
        robot.gripper.release()
        _run_push(robot, a, b)

    return robot.execute(body, on_step, max_steps, callback_every)


def _run_push(robot: SuctionRobot, start: np.ndarray, end: np.ndarray) -> None:
    """Over to the start, blade down, along the line, up; raises PrimitiveAbort."""
    z = TABLE_Z + BLADE_LIFT + BLADE_DEPTH  # the tip's height while pushing
    yaw = push_yaw(start, end, robot._cmd_yaw)
    a = np.array([start[0], start[1], z])
    b = np.array([end[0], end[1], z])
    robot._transfer(a + np.array([0.0, 0.0, APPROACH_HEIGHT]), yaw)
    robot._follow(robot._line(a, yaw, GUARDED_SPEED))
    pieces = max(1, math.ceil(float(np.linalg.norm(b - a)) / PUSH_PIECE))
    for k in range(1, pieces + 1):
        robot._follow(robot._line(a + (b - a) * k / pieces, yaw, PUSH_SPEED))
    robot._follow(robot._path([(b + np.array([0.0, 0.0, PUSH_RETREAT]), yaw)]))
    robot._settle()
    robot._wait_for_rest()
