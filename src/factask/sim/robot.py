"""Suction robots and the top-down pick-and-place primitive.

Two robots share one contract (see docs/robot.md):

- ``"floating"``: a mocap-driven suction cup (the cup body IS the mocap body; a
  held object is welded to it). Fast mode, no arm dynamics.
- an arm (``"ur10e"``, alias ``"arm"``; ``"ur5e"``, alias ``"arm_ur5e"``): a
  UR-type 6-DoF arm with position servos that track joint trajectories.

Which names exist is the registry's business (:mod:`factask.sim.robots`).

Motions are minimum-time (:mod:`factask.sim.motion`): trapezoidal profiles under
the tool's speed and acceleration limits (floating cup) or the arm's joint limits
(joint space, IK only at the waypoints). A transfer goes up to the height that
clears every object (and the held one), over, and down to just above the target,
the three moves blended; only the last centimetres before a contact are a slow
guarded move. After the release the robot lifts a little and waits until the
objects rest (settle detection, not a fixed wait). Every sample of a motion is
computed before it starts, so a physics step costs one array copy into the
controls plus ``mj_step``.

Both carry a ``suction_tip`` site and a ``suction`` weld (factask.sim.suction).
Everything runs in simulated time (``mujoco.mj_step``); nothing reads the clock.

Why one file of ~650 lines: both robots share one primitive (the same phases,
budgets and failure handling); splitting the controllers from the primitive would
put one contract in two places.
"""

from __future__ import annotations

import contextlib
import itertools
import math
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass

import mujoco
import numpy as np

from factask.geometry import Pose, wrap_angle
from factask.sim.health import FATAL_WARNINGS, physics_problem, warning_counts
from factask.sim.ik import TopDownIK, top_down_pose
from factask.sim.motion import Profile, blend, constant_speed, profile
from factask.sim.robot_arm import HOME_QPOS, JOINT_NAMES, JOINT_RANGES, KP, KV, build_arm
from factask.sim.robots import DEFAULT_ARM, DHArm, RobotError, robot_entry
from factask.sim.suction import (
    TIP_SITE,
    SuctionGripper,
    add_suction_weld,
    add_tool,
    find_id,
)

__all__ = [
    "ArmSuctionRobot",
    "FloatingSuctionRobot",
    "PrimitiveResult",
    "RobotError",
    "SuctionRobot",
    "attach_robot",
    "make_robot",
]

#: Name of the floating cup's mocap body.
FLOATING_BODY = "suction_cup_body"
#: Floating cup home: above the robot base, out of the workspace (m).
FLOATING_HOME = (0.1, 0.0, 0.45)

#: Tool limits of the floating cup: speed (m/s), acceleration (m/s^2), yaw rate
#: (rad/s) and yaw acceleration (rad/s^2) -- a UR arm's tool moves at up to 1 m/s.
TOOL_SPEED = 1.0
TOOL_ACCEL = 12.0
YAW_RATE = 2 * math.pi
YAW_ACCEL = 40.0
#: Speed of guarded moves (descents until contact), m/s: 0.2 mm per 2 ms step,
#: so first contact is detected at sub-millimetre penetration.
GUARDED_SPEED = 0.1
#: The guarded part of a descent starts this far above the target (m) ...
APPROACH_HEIGHT = 0.01
#: ... and the pick descent may go this far below the pick pose looking for contact (m).
PICK_OVERSHOOT = 0.03
#: Clearance (m) kept above every object while moving over the table; blended
#: corners never cut deeper than this.
CLEARANCE = 0.02
#: Half width (m) of the corridor whose objects a transfer clears, beyond the held
#: object's footprint (the cup's radius and a margin).
CUP_CLEARANCE = 0.05
#: Lowest tool height over the table while moving (m).
MIN_TRAVEL_HEIGHT = 0.05
#: Lift after the release before the primitive ends (m).
RETREAT = 0.03
#: The objects rest when no free object moves faster than this (m/s, rad/s) ...
REST_SPEED = 0.02
#: ... or after this long (s).
REST_MAX_TIME = 0.3
#: Before release, objects must move slower than this (m/s or rad/s) ...
RELEASE_SPEED = 0.003
#: ... or this many seconds pass.
RELEASE_MAX_TIME = 0.5
#: Arm: a move has settled when the tip is this close to its target (m) ...
SETTLE_TOL = 0.002
#: ... and no joint turns faster than this (rad/s), or after SETTLE_MAX_TIME (s).
SETTLE_SPEED = 0.05
SETTLE_MAX_TIME = 0.6
#: Arm: a waypoint the IK cannot reach within this distance (m) fails the primitive.
REACH_TOL = 0.005
#: Arm: joint-space moves may sag below the straight Cartesian line by this much (m)
#: before a via point is added.
SAG_TOL = 0.01
#: ... or stray sideways from it by this much (m): obstacles are searched along the
#: straight line, within the cup's clearance of it.
DRIFT_TOL = 0.02
#: Halvings of a move at most when placing via points (2**4 = 16 segments).
VIA_DEPTH = 4
#: Default cap on physics steps of one primitive (40 s at dt = 2 ms).
DEFAULT_MAX_STEPS = 20_000
#: Default number of physics steps between ``on_step`` calls.
DEFAULT_CALLBACK_EVERY = 10
#: Simulated seconds the arm takes at least to return home after an aborted primitive.
RECOVER_TIME = 0.5
#: Distance (rad) the arm's last wrist joint keeps from its range limits.
WRIST_MARGIN = 0.6
#: Physics steps between health checks (NaN state, fatal MuJoCo warnings).
HEALTH_EVERY = 25
#: Physics steps between the rest tests while waiting for objects to settle.
REST_EVERY = 5


@dataclass(frozen=True)
class PrimitiveResult:
    """Outcome of one primitive.

    Attributes:
        ok: True when the object was picked, carried and released at the place pose.
        reason: Why it failed (None when ok).
        sim_steps: Physics steps taken (simulated seconds = steps x timestep).
        grasped_body: Root body id that was picked (None when nothing was).
    """

    ok: bool
    reason: str | None
    sim_steps: int
    grasped_body: int | None


class _PrimitiveAbort(Exception):
    """Internal: ends a primitive early with a reason (never leaves this module)."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


def attach_robot(spec: mujoco.MjSpec, kind: str) -> None:
    """Add a suction robot (tool, ``suction_tip`` site, ``suction`` weld) to ``spec``.

    Args:
        spec: The scene's spec; the robot base sits at the world origin.
        kind: A name of the robot registry (:data:`factask.sim.robots.ROBOT_NAMES`).

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



class SuctionRobot(ABC):
    """A top-down suction robot bound to a compiled model.

    Args:
        model: Compiled model containing the robot.
        data: Its data (stepped by this controller during primitives).

    Raises:
        RobotError: The tip site, the cup or the weld is missing.
    """

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        self.model = model
        self.data = data
        self.dt = float(model.opt.timestep)
        self.gripper = SuctionGripper(model, data)
        self.tip_site = find_id(model, mujoco.mjtObj.mjOBJ_SITE, TIP_SITE)
        self._cmd_pos = np.zeros(3)
        self._cmd_yaw = 0.0
        self._steps = 0
        self._max_steps = DEFAULT_MAX_STEPS
        self._on_step: Callable[[], None] | None = None
        self._callback_every = DEFAULT_CALLBACK_EVERY
        self._warn0 = np.zeros(len(FATAL_WARNINGS), dtype=np.int64)
        self._aborted = False

    # ----- robot-specific hooks -----

    @abstractmethod
    def _reset_robot(self) -> None:
        """Put the robot's own state at home (no physics step)."""

    @abstractmethod
    def _path(self, points: list[tuple[np.ndarray, float]]) -> np.ndarray:
        """Control samples (one row per physics step) of a blended minimum-time path
        from the command through ``points`` (tip position, unwrapped yaw)."""

    @abstractmethod
    def _line(self, goal: np.ndarray, yaw: float, speed: float) -> np.ndarray:
        """Control samples of a constant-speed straight move to (goal, yaw)."""

    @abstractmethod
    def _apply(self, row: np.ndarray) -> None:
        """Write one control sample into ``data`` (mocap pose or servo targets)."""

    @abstractmethod
    def _hold_here(self) -> None:
        """Command the measured tip pose (after a guarded stop, to stop pushing)."""

    def _recover(self) -> None:  # noqa: B027 - optional hook, a mocap cannot get stuck
        """Bring the robot back to a known state after an aborted primitive."""

    def _settle(self) -> None:  # noqa: B027 - optional hook, a mocap needs no settling
        """Step until the tip tracks its command (arm); nothing to do for a mocap."""

    # ----- public API -----

    def reset(self) -> None:
        """Home pose, zero robot velocity, suction off; runs ``mj_forward``."""
        self.gripper.release()
        self._reset_robot()
        mujoco.mj_forward(self.model, self.data)
        ee = self.ee_pose()
        self._cmd_pos = ee.pos.copy()
        self._cmd_yaw = ee.yaw
        self._aborted = False

    def ee_pose(self) -> Pose:
        """Pose of the ``suction_tip`` site (z up the tool: top-down means yaw only)."""
        quat = np.zeros(4)
        mujoco.mju_mat2Quat(quat, self.data.site_xmat[self.tip_site])
        return Pose(self.data.site_xpos[self.tip_site].copy(), quat)

    def suction_on(self) -> bool:
        """Switch suction on; grasps the free object the cup touches, if any.

        Returns:
            True when an object is held.
        """
        return self.gripper.grasp()

    def suction_off(self) -> None:
        """Switch suction off (release the held object)."""
        self.gripper.release()

    def grasped(self) -> int | None:
        """Root body id of the object held, or None."""
        return self.gripper.held

    def pick_and_place(
        self,
        pick: Pose,
        place: Pose,
        on_step: Callable[[], None] | None = None,
        max_steps: int = DEFAULT_MAX_STEPS,
        callback_every: int = DEFAULT_CALLBACK_EVERY,
    ) -> PrimitiveResult:
        """Top-down suction pick at ``pick`` and release at ``place`` (Ravens semantics).

        ``pick`` is the suction contact point on the object's top (position, and
        the tool yaw); ``place`` is where the tip is when releasing. The object
        turns with the tool by ``place.yaw - pick.yaw``. Only position and yaw of
        the poses are used: the tool always points straight down.

        Args:
            pick: Tip pose at the grasp.
            place: Tip pose at the release.
            on_step: Called every ``callback_every`` physics steps (video frames ...).
            max_steps: Physics-step budget; exceeding it fails the primitive.
            callback_every: Physics steps between ``on_step`` calls.

        Returns:
            The result; failures (nothing to grasp, unreachable pose, physics
            blow-up, step limit) come back as ``ok=False`` with a reason, never raised.
        """
        self._steps = 0
        self._max_steps = max_steps
        self._on_step = on_step
        self._callback_every = max(1, callback_every)
        self._warn0 = warning_counts(self.data)
        grasped: int | None = None
        try:
            self._check_health()
            if self._aborted:
                self._recover()
            self._aborted = False
            grasped = self._run(pick, place)
            self._check_health()
        except _PrimitiveAbort as abort:
            self._aborted = True
            if self.gripper.held is not None:
                grasped = self.gripper.held
            self.gripper.release()
            return PrimitiveResult(False, abort.reason, self._steps, grasped)
        finally:
            self._on_step = None
        return PrimitiveResult(True, None, self._steps, grasped)

    # ----- the primitive -----

    def _run(self, pick: Pose, place: Pose) -> int:
        """Execute the primitive; returns the grasped body or raises _PrimitiveAbort."""
        pick_yaw, place_yaw = self._yaw_plan(pick, place)
        if self.gripper.held is not None:
            self.gripper.release()
        up = np.array([0.0, 0.0, 1.0])
        # Transfer to just above the pick, then a guarded descent to the first contact.
        self._transfer(pick.pos + APPROACH_HEIGHT * up, pick_yaw)
        if self._follow(self._line(pick.pos - PICK_OVERSHOOT * up, pick_yaw, GUARDED_SPEED),
                        stop=self.gripper.cup_in_contact):
            self._hold_here()
        if not self.suction_on():
            self._transfer(self._cmd_pos + APPROACH_HEIGHT * up, self._cmd_yaw)
            raise _PrimitiveAbort("nothing to grasp at pick pose")
        grasped = self.gripper.held
        assert grasped is not None
        # Carry to just above the place pose, then a guarded descent until it rests.
        self._transfer(place.pos + APPROACH_HEIGHT * up, place_yaw)
        if not self.gripper.held_in_contact() and self._follow(
                self._line(place.pos, place_yaw, GUARDED_SPEED),
                stop=self.gripper.held_in_contact):
            self._hold_here()
        self._settle()
        if self.gripper.held is None:
            raise _PrimitiveAbort("object lost during transport")
        # Release only once everything is still: a ball let go while it still swings
        # on the cup rolls away (nothing slows a rolling ball on the table).
        self._wait_for_rest(RELEASE_SPEED, RELEASE_MAX_TIME)
        self.suction_off()
        self._follow(self._path([(self._cmd_pos + RETREAT * up, self._cmd_yaw)]))
        self._wait_for_rest()
        return grasped

    def _transfer(self, goal: np.ndarray, yaw: float) -> None:
        """Up to the clearance height, over, and down to ``goal`` in one blended motion
        (the arm settles at the end and checks the goal was reached)."""
        start = self._cmd_pos
        # Only what lies along the way counts: the corridor is as wide as the held
        # object's footprint plus the clearance.
        top = self.gripper.obstacle_top(start, goal, self.gripper.held_footprint()
                                        + CUP_CLEARANCE)
        bottom = self.gripper.held_bottom()
        hang = 0.0 if bottom is None else max(0.0, float(self.ee_pose().pos[2]) - bottom)
        travel = max(top + hang + CLEARANCE, MIN_TRAVEL_HEIGHT, float(goal[2]))
        points: list[tuple[np.ndarray, float]] = []
        if start[2] < travel - 1e-4:
            points.append((np.array([start[0], start[1], travel]), self._cmd_yaw))
        level = max(travel, float(start[2]))
        if np.linalg.norm(goal[:2] - start[:2]) > 1e-4 or abs(yaw - self._cmd_yaw) > 1e-4:
            points.append((np.array([goal[0], goal[1], level]), yaw))
        points.append((np.asarray(goal, dtype=float), yaw))
        self._follow(self._path(points))
        self._settle()

    def _yaw_plan(self, pick: Pose, place: Pose) -> tuple[float, float]:
        """Unwrapped tool yaws at the pick and at the place.

        The cup is round, so only the difference matters: the object turns by the
        shortest rotation ``place.yaw - pick.yaw``. Tool moves follow these values
        without wrapping; this default keeps the current yaw at the pick (turning
        the empty cup would only cost time).
        """
        return self._cmd_yaw, self._cmd_yaw + wrap_angle(place.yaw - pick.yaw)

    def _wait_for_rest(self, speed: float = REST_SPEED, max_time: float = REST_MAX_TIME) -> None:
        """Step, the controls held, until no free object moves faster than ``speed``
        (at most ``max_time`` seconds)."""
        for k in range(max(1, math.ceil(max_time / self.dt))):
            if k % REST_EVERY == 0 and k and self.gripper.objects_resting(speed):
                return
            self._step()

    def _follow(self, samples: np.ndarray, stop: Callable[[], bool] | None = None) -> bool:
        """Apply ``samples`` one per physics step; True when ``stop`` fired."""
        for row in samples:
            self._apply(row)
            self._step()
            if stop is not None and stop():
                return True
        return False

    def _step(self) -> None:
        """One physics step with budget, health and callback bookkeeping."""
        if self._steps >= self._max_steps:
            raise _PrimitiveAbort(f"step limit exceeded ({self._max_steps} physics steps)")
        mujoco.mj_step(self.model, self.data)
        self._steps += 1
        # A blow-up is still caught within HEALTH_EVERY steps (MuJoCo's NaN warnings latch).
        if self._steps % HEALTH_EVERY == 0:
            self._check_health()
        if self._on_step is not None and self._steps % self._callback_every == 0:
            self._on_step()

    def _check_health(self) -> None:
        """Raise _PrimitiveAbort on a fatal MuJoCo warning since the primitive began, or
        a non-finite state (:func:`~factask.sim.health.physics_problem`)."""
        problem = physics_problem(self.data, self._warn0)
        if problem is not None:
            raise _PrimitiveAbort(f"physics failure: {problem}")


def _tool_profile(a: np.ndarray, b: np.ndarray) -> Profile:
    """Minimum-time profile of a tool move between (x, y, z, yaw) points."""
    delta = np.array([float(np.linalg.norm(b[:3] - a[:3])), abs(float(b[3] - a[3]))])
    return profile(delta, np.array([TOOL_SPEED, YAW_RATE]), np.array([TOOL_ACCEL, YAW_ACCEL]))


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
        profiles = [_tool_profile(a, b) for a, b in itertools.pairwise(pts)]
        overlap = math.sqrt(2 * CLEARANCE / TOOL_ACCEL)
        return self._rows(blend(pts, profiles, overlap, self.dt))

    def _line(self, goal: np.ndarray, yaw: float, speed: float) -> np.ndarray:
        start = np.array([*self._cmd_pos, self._cmd_yaw])
        end = np.array([*goal, yaw])
        duration = max(float(np.linalg.norm(end[:3] - start[:3])) / speed, self.dt)
        return self._rows(constant_speed(start, end, duration, self.dt))

    def _apply(self, row: np.ndarray) -> None:
        self._mocap_pos[:] = row[:3]
        self._mocap_quat[:] = row[3:]

    def _hold_here(self) -> None:
        ee = self.ee_pose()
        self._cmd_pos = ee.pos.copy()
        self._cmd_yaw += wrap_angle(ee.yaw - self._cmd_yaw)  # stay on the unwrapped branch
        self._apply(self._rows(np.array([[*self._cmd_pos, self._cmd_yaw]]))[0])


class ArmSuctionRobot(SuctionRobot):
    """UR-type arm: IK at the waypoints, minimum-time joint trajectories under the
    arm's joint speed and acceleration limits, tracked by position servos.

    Control samples are rows of the six servo targets: the planned joint angles plus
    ``KV / KP`` times the planned joint speeds, so the servos' damping does not make
    them lag behind a moving target.

    Args:
        model: Compiled model containing the arm.
        data: Its data.
        arm: DH parameters of the arm in the model.
    """

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData, arm: DHArm = DEFAULT_ARM):
        super().__init__(model, data)
        joints = [find_id(model, mujoco.mjtObj.mjOBJ_JOINT, n) for n in JOINT_NAMES]
        self.qpos_adr = np.array([model.jnt_qposadr[j] for j in joints])
        self.dof_adr = np.array([model.jnt_dofadr[j] for j in joints])
        self.act = np.array(
            [find_id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, f"{n}_servo") for n in JOINT_NAMES]
        )
        self.ik = TopDownIK(arm)
        self.arm = arm
        self._lo = np.array([r[0] for r in JOINT_RANGES])
        self._hi = np.array([r[1] for r in JOINT_RANGES])
        self._vmax = np.asarray(arm.max_speed, dtype=float)
        self._amax = np.asarray(arm.max_accel, dtype=float)
        self._lead = np.asarray(KV) / np.asarray(KP)
        self._cmd_q = np.asarray(HOME_QPOS, dtype=float)

    def _reset_robot(self) -> None:
        home = np.asarray(HOME_QPOS, dtype=float)
        self.data.qpos[self.qpos_adr] = home
        self.data.qvel[self.dof_adr] = 0.0
        self.data.ctrl[self.act] = home
        self.ik.set_q(home)
        self._cmd_q = home.copy()

    # ----- planning -----

    def _solve(self, q0: np.ndarray, pos0: np.ndarray, yaw0: float, pos: np.ndarray,
               yaw: float) -> np.ndarray:
        """Joint angles of tip (pos, yaw) near ``q0`` (the solution at pos0, yaw0), the
        last wrist turned to the unwrapped yaw; raises _PrimitiveAbort if unreachable."""
        q, err = self.ik.solve_near(q0, pos, yaw)
        if err > REACH_TOL:
            # Far or awkward targets: mink along a straight path, from q0.
            self.ik.set_q(q0)
            q, err, _ = self.ik.solve(top_down_pose(pos, yaw))
        if err > REACH_TOL:
            raise _PrimitiveAbort(
                f"pose out of reach: IK stays {err * 1000:.0f} mm from "
                f"{np.round(pos, 3).tolist()}"
            )
        # The tool yaw fixes the last joint only modulo 2 pi: take the turn the planned
        # (unwrapped) yaw change asks for, as the base turn and the yaw change add up.
        pan = math.atan2(pos[1], pos[0]) - math.atan2(pos0[1], pos0[0])
        wanted = q0[5] + wrap_angle(pan) - (yaw - yaw0)
        q[5] += 2 * math.pi * round((wanted - q[5]) / (2 * math.pi))
        while q[5] > self._hi[5]:
            q[5] -= 2 * math.pi
        while q[5] < self._lo[5]:
            q[5] += 2 * math.pi
        return q

    def _vias(self, qa: np.ndarray, qb: np.ndarray, pa: np.ndarray, pb: np.ndarray,
              ya: float, yb: float, depth: int = VIA_DEPTH) -> list[np.ndarray]:
        """Joint via points so that the joint-space move from qa to qb sags at most
        SAG_TOL below the straight tip line from pa to pb and strays at most
        DRIFT_TOL from it sideways (obstacles are looked for along that line only:
        a joint-space arc can swing the cup through a tower beside it)."""
        sag = drift = 0.0
        for s in (0.25, 0.5, 0.75):
            tip, line = self.ik.fk(qa + s * (qb - qa)), pa + s * (pb - pa)
            sag = max(sag, float(line[2] - tip[2]))
            drift = max(drift, float(np.linalg.norm(tip[:2] - line[:2])))
        if (sag <= SAG_TOL and drift <= DRIFT_TOL) or depth == 0:
            return []
        pm, ym = 0.5 * (pa + pb), 0.5 * (ya + yb)
        qm = self._solve(qa, pa, ya, pm, ym)
        return [*self._vias(qa, qm, pa, pm, ya, ym, depth - 1), qm,
                *self._vias(qm, qb, pm, pb, ym, yb, depth - 1)]

    def _targets(self, qs: np.ndarray) -> np.ndarray:
        """Servo targets of joint samples: angles plus the damping lead of their speed."""
        qd = np.gradient(qs, self.dt, axis=0) if len(qs) > 1 else np.zeros_like(qs)
        qd[-1] = 0.0
        self._cmd_q = qs[-1].copy()
        return np.clip(qs, self._lo, self._hi) + self._lead * qd

    def _path(self, points: list[tuple[np.ndarray, float]]) -> np.ndarray:
        qs = [self._cmd_q.copy()]
        pa, ya = self._cmd_pos.copy(), self._cmd_yaw
        for pos, yaw in points:
            q = self._solve(qs[-1], pa, ya, pos, yaw)
            qs += [*self._vias(qs[-1], q, pa, pos, ya, yaw), q]
            pa, ya = np.asarray(pos, dtype=float), yaw
        profiles = [profile(b - a, self._vmax, self._amax) for a, b in itertools.pairwise(qs)]
        samples = blend(qs, profiles, math.sqrt(2 * CLEARANCE / TOOL_ACCEL), self.dt)
        if len(samples) > 2:
            acc = np.abs(np.diff(samples, 2, axis=0)).max(axis=0) / self.dt**2
            if (acc > 1.05 * self._amax).any():
                # Overlapping moves of one joint in opposite directions add up: no overlap.
                samples = blend(qs, profiles, 0.0, self.dt)
        self._cmd_pos, self._cmd_yaw = pa, ya
        return self._targets(samples)

    def _line(self, goal: np.ndarray, yaw: float, speed: float) -> np.ndarray:
        q = self._solve(self._cmd_q, self._cmd_pos, self._cmd_yaw, goal, yaw)
        duration = max(float(np.linalg.norm(goal - self._cmd_pos)) / speed, self.dt)
        samples = constant_speed(self._cmd_q, q, duration, self.dt)
        self._cmd_pos, self._cmd_yaw = np.asarray(goal, dtype=float), yaw
        return self._targets(samples)

    # ----- execution -----

    def _apply(self, row: np.ndarray) -> None:
        self.data.ctrl[self.act] = row

    def _hold_here(self) -> None:
        # Command the measured joints so the servos stop pushing down.
        q = self.data.qpos[self.qpos_adr].copy()
        self.data.ctrl[self.act] = q
        self._cmd_q = q
        ee = self.ee_pose()
        self._cmd_pos = ee.pos.copy()
        self._cmd_yaw += wrap_angle(ee.yaw - self._cmd_yaw)  # stay on the unwrapped branch

    def _settle(self) -> None:
        for k in range(math.ceil(SETTLE_MAX_TIME / self.dt)):
            if k % 2 == 0:
                err = float(np.linalg.norm(self.data.site_xpos[self.tip_site] - self._cmd_pos))
                speed = float(np.abs(self.data.qvel[self.dof_adr]).max())
                if err < SETTLE_TOL and speed < SETTLE_SPEED:
                    return
            self._step()

    def _recover(self) -> None:
        # An aborted primitive can leave the arm anywhere: lift straight up, then
        # move the joints home and restart from there.
        self._cmd_q = self.data.qpos[self.qpos_adr].copy()
        ee = self.ee_pose()
        self._cmd_pos = ee.pos.copy()
        self._cmd_yaw += wrap_angle(ee.yaw - self._cmd_yaw)
        up = self._cmd_pos.copy()
        up[2] = max(up[2], self.gripper.obstacle_top() + CLEARANCE, MIN_TRAVEL_HEIGHT)
        with contextlib.suppress(_PrimitiveAbort):  # an unreachable lift: go home from here
            self._follow(self._path([(up, self._cmd_yaw)]))
        home = np.asarray(HOME_QPOS, dtype=float)
        prof = profile(home - self._cmd_q, self._vmax, self._amax, min_time=RECOVER_TIME)
        self._follow(self._targets(blend([self._cmd_q, home], [prof], 0.0, self.dt)))
        self.ik.set_q(home)
        self._cmd_pos = self.ik.fk(home)
        self._settle()
        ee = self.ee_pose()
        self._cmd_pos = ee.pos.copy()
        self._cmd_yaw += wrap_angle(ee.yaw - self._cmd_yaw)

    def _yaw_plan(self, pick: Pose, place: Pose) -> tuple[float, float]:
        # The last wrist joint turns by (shoulder pan change) - (tool yaw change)
        # and has a finite range: choose the 2*pi turn of the pick yaw that keeps
        # it closest to the middle of its range at both the pick and the place,
        # else it winds up over successive primitives and hits its limit.
        near, _ = super()._yaw_plan(pick, place)
        delta = wrap_angle(place.yaw - pick.yaw)
        wrist_now = float(self._cmd_q[-1])
        lo, hi = JOINT_RANGES[-1]
        mid = 0.5 * (lo + hi)
        pan_now = math.atan2(self._cmd_pos[1], self._cmd_pos[0])
        pan_pick = math.atan2(pick.pos[1], pick.pos[0])
        pan_place = math.atan2(place.pos[1], place.pos[0])
        allowed = 0.5 * (hi - lo) - WRIST_MARGIN
        best, best_cost = near, math.inf
        for turns in (0, -1, 1, -2, 2):  # fewest extra turns first: they cost time
            yaw = near + 2 * math.pi * turns
            at_pick = wrist_now + wrap_angle(pan_pick - pan_now) - (yaw - self._cmd_yaw)
            at_place = at_pick + wrap_angle(pan_place - pan_pick) - delta
            cost = max(abs(at_pick - mid), abs(at_place - mid))
            if cost <= allowed:
                return yaw, yaw + delta
            if cost < best_cost:
                best, best_cost = yaw, cost
        return best, best + delta
