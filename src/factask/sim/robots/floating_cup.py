"""The floating suction cup: a mocap body moved along minimum-time tool paths.

Fast mode: no arm dynamics, the command is applied exactly every step. Being an
abstract robot (no arm whose joints bound it), it moves faster than a UR arm's
tool (:data:`FLOATING_SPEED` ...); guarded descents, pushes and low carries keep
the speeds every robot shares.
"""

from __future__ import annotations

import itertools
import math

import mujoco
import numpy as np

from factask.geometry import wrap_angle
from factask.sim.robots.motion import Profile, blend, constant_speed, profile
from factask.sim.robots.primitive import (
    CLEARANCE,
    TOOL_ACCEL,
    TOOL_SPEED,
    YAW_ACCEL,
    YAW_RATE,
    SuctionRobot,
)
from factask.sim.robots.registry import RobotError
from factask.sim.robots.suction import WELD_SOLREF, find_id

#: State parts one control row of :meth:`FloatingSuctionRobot._play` writes.
_MOCAP_STATE = int(mujoco.mjtState.mjSTATE_MOCAP_POS | mujoco.mjtState.mjSTATE_MOCAP_QUAT)
#: Name of the floating cup's mocap body.
FLOATING_BODY = "suction_cup_body"
#: Floating cup home: above the robot base, out of the workspace (m).
FLOATING_HOME = (0.1, 0.0, 0.45)
#: Tool limits of the floating cup's free moves (transfers, lifts): speed (m/s),
#: acceleration (m/s^2), yaw rate (rad/s), yaw acceleration (rad/s^2). Three times
#: a UR arm's tool speed, 40 m/s^2 instead of 12: nothing bounds a mocap body; what
#: bounds these is the held object, which trails the cup by its speed times
#: :data:`WELD_LAG` (3 cm at 3 m/s, measured; the corners allow for it) and, held
#: 5 cm off the axis, feels 0.05 x 120 = 6 m/s^2 tangential and 0.05 x (4 pi)^2 =
#: 8 m/s^2 centripetal at the yaw limits. Transfers take 0.54 s per pick-and-place
#: instead of 1.19 at a UR arm's tool limits (3 quick tasks).
FLOATING_SPEED = 3.0
FLOATING_ACCEL = 40.0
FLOATING_YAW_RATE = 4 * math.pi
FLOATING_YAW_ACCEL = 120.0
#: Time (s) by which a held object trails the cup while it moves: the suction weld
#: is a critically damped spring (:data:`~factask.sim.robots.suction.WELD_SOLREF`: time
#: constant tau, damping ratio zeta), and such a spring follows a steady motion
#: 2 zeta tau behind (measured: 11, 21, 31 mm at 1, 2, 3 m/s).
WELD_LAG = 2 * WELD_SOLREF[1] * WELD_SOLREF[0]


def corner_overlap(accel: float) -> float:
    """Overlap (s) of two blended moves such that the corner is cut by at most
    CLEARANCE, the held object included: in the last ``T`` seconds of a move the
    cup covers ``accel T^2 / 2`` and the object trails by ``WELD_LAG accel T``."""
    return math.sqrt(WELD_LAG**2 + 2 * CLEARANCE / accel) - WELD_LAG


#: (speed, yaw rate) and (acceleration, yaw acceleration) of the cup's free moves;
#: holding a rope's segment, a UR arm's tool limits: the rest of the rope hangs on
#: connect constraints and whips when its segment is jerked at 40 m/s^2 (a CLIPort
#: bead chain missed its line within the action budget).
_FREE_LIMITS = (np.array([FLOATING_SPEED, FLOATING_YAW_RATE]),
                np.array([FLOATING_ACCEL, FLOATING_YAW_ACCEL]))
_LINKED_LIMITS = (np.array([TOOL_SPEED, YAW_RATE]), np.array([TOOL_ACCEL, YAW_ACCEL]))


def _tool_profile(a: np.ndarray, b: np.ndarray,
                  limits: tuple[np.ndarray, np.ndarray] = _FREE_LIMITS) -> Profile:
    """Minimum-time profile of a tool move between (x, y, z, yaw) points."""
    delta = np.array([float(np.linalg.norm(b[:3] - a[:3])), abs(float(b[3] - a[3]))])
    return profile(delta, *limits)


class FloatingSuctionRobot(SuctionRobot):
    """Mocap-driven suction cup: the command is applied exactly every step.

    Control samples are rows (x, y, z, qw, qx, qy, qz) of the cup's mocap pose.
    """

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        super().__init__(model, data)
        body = find_id(model, mujoco.mjtObj.mjOBJ_BODY, FLOATING_BODY)
        mocap = int(model.body_mocapid[body])
        if mocap < 0:
            raise RobotError(f"body {FLOATING_BODY!r} is not a mocap body")
        self.mocap = mocap
        # Views into data: writing them costs one copy per step, no indexing.
        self._mocap_pos = data.mocap_pos[mocap]
        self._mocap_quat = data.mocap_quat[mocap]

    def _reset_robot(self) -> None:
        self.data.mocap_pos[self.mocap] = FLOATING_HOME
        self.data.mocap_quat[self.mocap] = (1.0, 0.0, 0.0, 0.0)

    def _rows(self, xyzyaw: np.ndarray) -> np.ndarray:
        """Mocap rows of (x, y, z, yaw) samples; the command follows the last one."""
        half = 0.5 * xyzyaw[:, 3]
        rows = np.zeros((len(xyzyaw), 7))
        rows[:, :3] = xyzyaw[:, :3]
        rows[:, 3] = np.cos(half)
        rows[:, 6] = np.sin(half)
        self._cmd_pos = xyzyaw[-1, :3].copy()
        self._cmd_yaw = float(xyzyaw[-1, 3])
        return rows

    def _path(self, points: list[tuple[np.ndarray, float]]) -> np.ndarray:
        pts = [np.array([*self._cmd_pos, self._cmd_yaw])]
        pts += [np.array([*p, y]) for p, y in points]
        limits = _LINKED_LIMITS if self.gripper.holds_linked else _FREE_LIMITS
        profiles = [_tool_profile(a, b, limits) for a, b in itertools.pairwise(pts)]
        return self._rows(blend(pts, profiles, corner_overlap(float(limits[1][0])), self.dt))

    def _line(self, goal: np.ndarray, yaw: float, speed: float) -> np.ndarray:
        start = np.array([*self._cmd_pos, self._cmd_yaw])
        end = np.array([*goal, yaw])
        duration = max(float(np.linalg.norm(end[:3] - start[:3])) / speed, self.dt)
        return self._rows(constant_speed(start, end, duration, self.dt))

    def _apply(self, row: np.ndarray) -> None:
        self._mocap_pos[:] = row[:3]
        self._mocap_quat[:] = row[3:]

    def _play(self, rows: np.ndarray) -> None:
        # One mj_setState per step writes every mocap pose (the goal markers keep
        # theirs): one C call, cheaper than two array copies from Python.
        m, d = self.model, self.data
        n = m.nmocap
        full = np.empty((len(rows), 7 * n))
        full[:, :3 * n] = d.mocap_pos.ravel()
        full[:, 3 * n:] = d.mocap_quat.ravel()
        i, j = 3 * self.mocap, 3 * n + 4 * self.mocap
        full[:, i:i + 3] = rows[:, :3]
        full[:, j:j + 4] = rows[:, 3:]
        step, set_state = mujoco.mj_step, mujoco.mj_setState
        for row in full:
            set_state(m, d, row, _MOCAP_STATE)
            step(m, d)

    def _hold_here(self) -> None:
        ee = self.ee_pose()
        self._cmd_pos = ee.pos.copy()
        self._cmd_yaw += wrap_angle(ee.yaw - self._cmd_yaw)  # stay on the unwrapped branch
        self._apply(self._rows(np.array([[*self._cmd_pos, self._cmd_yaw]]))[0])
