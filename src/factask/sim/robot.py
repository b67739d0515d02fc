"""Suction robots and the top-down pick-and-place primitive.

Two robots share one contract (see docs/robot.md):

- ``"floating"``: a mocap-driven suction cup (the cup body IS the mocap body; a
  held object is welded to it). Fast mode, no arm dynamics.
- an arm (``"ur10e"``, alias ``"arm"``; ``"ur5e"``, alias ``"arm_ur5e"``): a
  UR-type 6-DoF arm with position servos; the tip follows Cartesian paths through
  mink IK.

Which names exist is the registry's business (:mod:`factask.sim.robots`).

Both carry a ``suction_tip`` site and a ``suction`` weld (factask.sim.suction).
Everything runs in simulated time (``mujoco.mj_step``); nothing reads the clock.

Why one file of ~550 lines: both robots share one primitive (the same phases,
budgets and failure handling); splitting the controllers from the primitive would
put one contract in two places.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass

import mujoco
import numpy as np

from factask.geometry import Pose, quat_from_yaw, wrap_angle
from factask.sim.health import FATAL_WARNINGS, physics_problem, warning_counts
from factask.sim.ik import TopDownIK, top_down_pose
from factask.sim.robot_arm import HOME_QPOS, JOINT_NAMES, JOINT_RANGES, build_arm
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

#: Peak tip speed (m/s) and tool yaw rate (rad/s) on free moves.
TRANSIT_SPEED = 1.0
YAW_RATE = 2.0
#: Speed of guarded moves (descents until contact), m/s: 0.1 mm per 2 ms step,
#: so first contact is detected at sub-millimetre penetration.
GUARDED_SPEED = 0.05
#: Shortest duration of any move (s), so accelerations stay bounded.
MIN_MOVE_TIME = 0.1
#: Height of the tip above the table while carrying (m), and the clearance kept
#: above the pick/place heights when those are higher.
SAFE_HEIGHT = 0.25
SAFE_CLEARANCE = 0.1
#: The guarded part of a descent starts this far above the target (m) ...
APPROACH_HEIGHT = 0.04
#: ... and the pick descent may go this far below the pick pose looking for contact (m).
PICK_OVERSHOOT = 0.03
#: Arm: physics steps per IK/servo update (100 Hz control at dt = 2 ms).
ARM_CONTROL_DECIMATION = 5
#: Arm: a move has settled when the tip is this close to its command (m) ...
SETTLE_TOL = 0.002
#: ... or after this long (s).
SETTLE_MAX_TIME = 0.6
#: Arm: a command the IK cannot reach within this distance (m) fails the primitive.
REACH_TOL = 0.005
#: Simulated time spent after release and lift so the object comes to rest (s).
REST_TIME = 0.2
#: Default cap on physics steps of one primitive (40 s at dt = 2 ms).
DEFAULT_MAX_STEPS = 20_000
#: Default number of physics steps between ``on_step`` calls.
DEFAULT_CALLBACK_EVERY = 10
#: World up axis.
_UP = np.array([0.0, 0.0, 1.0])
#: Simulated seconds the arm takes to return home after an aborted primitive.
RECOVER_TIME = 1.5
#: Distance (rad) the arm's last wrist joint keeps from its range limits.
WRIST_MARGIN = 0.6
#: Physics steps between health checks (NaN state, fatal MuJoCo warnings).
HEALTH_EVERY = 10


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


def _smoothstep(s: float) -> float:
    """Quintic 0 -> 1 profile with zero velocity and acceleration at both ends."""
    return s * s * s * (10 + s * (-15 + 6 * s))


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
    def _command(self, pos: np.ndarray, yaw: float, tick: int) -> None:
        """Set actuator/mocap targets for the next physics step toward tip (pos, yaw)."""

    def _hold_here(self) -> None:
        """Re-command the current tip pose (after a guarded stop, to stop pushing)."""
        ee = self.ee_pose()
        self._cmd_pos = ee.pos.copy()
        self._cmd_yaw += wrap_angle(ee.yaw - self._cmd_yaw)  # stay on the unwrapped branch
        self._command(self._cmd_pos, self._cmd_yaw, 0)

    def _recover(self) -> None:  # noqa: B027 - optional hook, a mocap cannot get stuck
        """Bring the robot back to a known state after an aborted primitive."""

    def _settle(self) -> None:  # noqa: B027 - optional hook, a mocap needs no settling
        """Step until the tip tracks its command (arm); nothing to do for a mocap."""

    def _check_reach(self) -> None:  # noqa: B027 - optional hook, a mocap reaches anywhere
        """Raise _PrimitiveAbort when the command cannot be reached (arm only)."""

    # ----- public API -----

    def reset(self) -> None:
        """Home pose, zero robot velocity, suction off; runs ``mj_forward``."""
        self.gripper.release()
        self._reset_robot()
        mujoco.mj_forward(self.model, self.data)
        ee = self.ee_pose()
        self._cmd_pos = ee.pos.copy()
        self._cmd_yaw = ee.yaw

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
        safe_z = max(SAFE_HEIGHT, pick.pos[2] + SAFE_CLEARANCE, place.pos[2] + SAFE_CLEARANCE)
        pick_yaw, place_yaw = self._yaw_plan(pick, place)
        if self.gripper.held is not None:
            self.gripper.release()
        # Up, over, and down to just above the pick pose.
        self._move(np.array([*self._cmd_pos[:2], max(safe_z, self._cmd_pos[2])]), self._cmd_yaw)
        self._move(np.array([*pick.pos[:2], safe_z]), pick_yaw)
        self._move(pick.pos + APPROACH_HEIGHT * _UP, pick_yaw)
        self._settle()
        self._check_reach()
        # Guarded descent: stop at the first cup contact.
        touched = self._move(
            pick.pos - PICK_OVERSHOOT * _UP, pick_yaw, speed=GUARDED_SPEED,
            stop=self.gripper.cup_in_contact,
        )
        if touched:
            self._hold_here()
        if not self.suction_on():
            self._move(np.array([*pick.pos[:2], safe_z]), pick_yaw)
            raise _PrimitiveAbort("nothing to grasp at pick pose")
        grasped = self.gripper.held
        assert grasped is not None
        # Lift, carry, rotate to the place yaw on the way, descend.
        self._move(np.array([*self._cmd_pos[:2], safe_z]), self._cmd_yaw)
        self._move(np.array([*place.pos[:2], safe_z]), place_yaw)
        self._move(place.pos + APPROACH_HEIGHT * _UP, place_yaw)
        self._settle()
        self._check_reach()
        if self.gripper.held_in_contact():
            pass  # already resting on something: release here
        elif self._move(place.pos, place_yaw, speed=GUARDED_SPEED,
                        stop=self.gripper.held_in_contact):
            self._hold_here()
        self._settle()
        if self.gripper.held is None:
            raise _PrimitiveAbort("object lost during transport")
        self.suction_off()
        self._move(np.array([*self._cmd_pos[:2], safe_z]), self._cmd_yaw)
        self._idle(REST_TIME)
        return grasped

    def _move(
        self,
        goal: np.ndarray,
        goal_yaw: float,
        speed: float = TRANSIT_SPEED,
        stop: Callable[[], bool] | None = None,
    ) -> bool:
        """Drive the tip command along a straight line to (goal, goal_yaw).

        Free moves use a quintic time profile; guarded moves (``stop`` given) a
        constant speed so that contact is met slowly.

        Returns:
            True when ``stop`` fired (the move ended early).
        """
        start = self._cmd_pos.copy()
        goal = np.asarray(goal, dtype=float)
        dyaw = goal_yaw - self._cmd_yaw  # unwrapped on purpose: see _yaw_plan
        yaw0 = self._cmd_yaw
        dist = float(np.linalg.norm(goal - start))
        duration = max(dist / speed, abs(dyaw) / YAW_RATE, MIN_MOVE_TIME)
        if stop is None:
            duration *= 1.875  # peak speed of the quintic profile is 1.875 x mean
        n = max(1, math.ceil(duration / self.model.opt.timestep))
        for k in range(1, n + 1):
            s = k / n if stop is not None else _smoothstep(k / n)
            self._cmd_pos = start + s * (goal - start)
            self._cmd_yaw = yaw0 + s * dyaw
            self._command(self._cmd_pos, self._cmd_yaw, k)
            self._step()
            if stop is not None and stop():
                return True
        return False

    def _yaw_plan(self, pick: Pose, place: Pose) -> tuple[float, float]:
        """Unwrapped tool yaws at the pick and at the place.

        The cup is round, so only the difference matters: the object turns by the
        shortest rotation ``place.yaw - pick.yaw``. Tool moves follow these values
        without wrapping; this default takes the pick yaw nearest the current one.
        """
        pick_yaw = self._cmd_yaw + wrap_angle(pick.yaw - self._cmd_yaw)
        return pick_yaw, pick_yaw + wrap_angle(place.yaw - pick.yaw)

    def _idle(self, seconds: float) -> None:
        """Hold the current command for ``seconds`` of simulated time."""
        for k in range(max(1, math.ceil(seconds / self.model.opt.timestep))):
            self._command(self._cmd_pos, self._cmd_yaw, k)
            self._step()

    def _step(self) -> None:
        """One physics step with budget, health and callback bookkeeping."""
        if self._steps >= self._max_steps:
            raise _PrimitiveAbort(f"step limit exceeded ({self._max_steps} physics steps)")
        mujoco.mj_step(self.model, self.data)
        self._steps += 1
        # Checking every step costs a quarter of a primitive's wall time; a blow-up
        # is still caught within HEALTH_EVERY steps (MuJoCo's own NaN warnings latch).
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


class FloatingSuctionRobot(SuctionRobot):
    """Mocap-driven suction cup: the command is applied exactly every step."""

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        super().__init__(model, data)
        body = find_id(model, mujoco.mjtObj.mjOBJ_BODY, FLOATING_BODY)
        mocap = int(model.body_mocapid[body])
        if mocap < 0:
            raise RobotError(f"body {FLOATING_BODY!r} is not a mocap body")
        self.mocap = mocap

    def _reset_robot(self) -> None:
        self.data.mocap_pos[self.mocap] = FLOATING_HOME
        self.data.mocap_quat[self.mocap] = quat_from_yaw(0.0)

    def _command(self, pos: np.ndarray, yaw: float, tick: int) -> None:
        self.data.mocap_pos[self.mocap] = pos
        self.data.mocap_quat[self.mocap] = quat_from_yaw(yaw)


class ArmSuctionRobot(SuctionRobot):
    """UR-type arm: mink IK on the tip path, position servos track the joint solution.

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
        self._lo = np.array([r[0] for r in JOINT_RANGES])
        self._hi = np.array([r[1] for r in JOINT_RANGES])

    def _reset_robot(self) -> None:
        home = np.asarray(HOME_QPOS)
        self.data.qpos[self.qpos_adr] = home
        self.data.qvel[self.dof_adr] = 0.0
        self.data.ctrl[self.act] = home
        self.ik.set_q(home)

    def _command(self, pos: np.ndarray, yaw: float, tick: int) -> None:
        # IK + servo update at the control rate; servos hold targets in between.
        if tick % ARM_CONTROL_DECIMATION != 0:
            return
        q = self.ik.step(top_down_pose(pos, yaw))
        self.data.ctrl[self.act] = np.clip(q, self._lo, self._hi)

    def _hold_here(self) -> None:
        # Restart IK from the measured joints so the servo stops pushing down.
        self.ik.set_q(self.data.qpos[self.qpos_adr])
        self.data.ctrl[self.act] = self.data.qpos[self.qpos_adr]
        ee = self.ee_pose()
        self._cmd_pos = ee.pos.copy()
        self._cmd_yaw += wrap_angle(ee.yaw - self._cmd_yaw)  # stay on the unwrapped branch

    def _settle(self) -> None:
        target = top_down_pose(self._cmd_pos, self._cmd_yaw)
        self.ik.solve(target, max_iterations=50)
        self.data.ctrl[self.act] = np.clip(self.ik.q, self._lo, self._hi)
        for _ in range(math.ceil(SETTLE_MAX_TIME / self.model.opt.timestep)):
            err = float(np.linalg.norm(self.ee_pose().pos - self._cmd_pos))
            speed = float(np.abs(self.data.qvel[self.dof_adr]).max())
            if err < SETTLE_TOL and speed < 0.05:
                return
            self._step()

    def _recover(self) -> None:
        # An aborted primitive can leave the IK in a poor local solution it cannot
        # leave by small steps: lift straight up, then move the joints back home.
        up = self.ee_pose().pos.copy()
        up[2] = max(up[2], SAFE_HEIGHT)
        self._move(up, self._cmd_yaw)
        start = self.data.qpos[self.qpos_adr].copy()
        home = np.asarray(HOME_QPOS)
        n = max(1, math.ceil(RECOVER_TIME / self.model.opt.timestep))
        for k in range(1, n + 1):
            self.data.ctrl[self.act] = start + _smoothstep(k / n) * (home - start)
            self._step()
        self.ik.set_q(home)
        self._settle_joints()
        ee = self.ee_pose()
        self._cmd_pos = ee.pos.copy()
        self._cmd_yaw += wrap_angle(ee.yaw - self._cmd_yaw)

    def _settle_joints(self) -> None:
        for _ in range(math.ceil(SETTLE_MAX_TIME / self.model.opt.timestep)):
            if float(np.abs(self.data.qvel[self.dof_adr]).max()) < 0.05:
                return
            self._step()

    def _yaw_plan(self, pick: Pose, place: Pose) -> tuple[float, float]:
        # The last wrist joint turns by (shoulder pan change) - (tool yaw change)
        # and has a finite range: choose the 2*pi turn of the pick yaw that keeps
        # it closest to the middle of its range at both the pick and the place,
        # else it winds up over successive primitives and hits its limit.
        near, _ = super()._yaw_plan(pick, place)
        delta = wrap_angle(place.yaw - pick.yaw)
        wrist_now = float(self.data.qpos[self.qpos_adr[-1]])
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

    def _check_reach(self) -> None:
        pos_err, _ = self.ik.error(top_down_pose(self._cmd_pos, self._cmd_yaw))
        if pos_err > REACH_TOL:
            raise _PrimitiveAbort(
                f"pose out of reach: IK stays {pos_err * 1000:.0f} mm from "
                f"{np.round(self._cmd_pos, 3).tolist()}"
            )
