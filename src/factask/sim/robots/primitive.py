"""The top-down suction pick-and-place primitive, shared by every robot.

:class:`SuctionRobot` holds what both robots share: the phases of the primitive,
its budgets and failure handling, the waits. The controllers live beside it:
:mod:`factask.sim.robots.floating_cup` (a mocap cup) and :mod:`factask.sim.robots.arm_controller`
(a UR-type arm); :mod:`factask.sim.robots.attach` binds them to a scene.

Motions are minimum-time (:mod:`factask.sim.robots.motion`): trapezoidal profiles under
the tool's speed and acceleration limits (floating cup) or the arm's joint limits
(joint space, IK only at the waypoints). A transfer goes up to the height that
clears every object (and the held one), over, and down to just above the target,
the three moves blended; only the last centimetres before a contact are a slow
guarded move. After the release the robot lifts a little and waits until the
objects rest (settle detection, not a fixed wait). Every sample of a motion is
computed before it starts and played in a tight loop (one array copy into the
controls plus ``mj_step``); health and budget are checked between chunks of
steps, contacts only during guarded moves (and there only once the clearance
below allows one: :meth:`SuctionRobot._descend`).

Everything runs in simulated time (``mujoco.mj_step``); nothing reads the clock.

Why one file of a little over 500 lines: the phases share one robot's commanded
state and budgets; splitting them would spread that state over modules.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass

import mujoco
import numpy as np

from factask.geometry import Pose, wrap_angle
from factask.sim.robots.health import HealthWatch
from factask.sim.robots.suction import REST_RADIUS, TIP_SITE, SuctionGripper, find_id
from factask.vocabulary.errors import FactaskError

#: A UR arm's tool limits: speed (m/s), acceleration (m/s^2), yaw rate (rad/s) and
#: yaw acceleration (rad/s^2) -- its tool moves at up to 1 m/s. (The floating cup,
#: an abstract robot, has its own: :data:`~factask.sim.robots.floating_cup.FLOATING_SPEED`.)
TOOL_SPEED = 1.0
TOOL_ACCEL = 12.0
YAW_RATE = 2 * math.pi
YAW_ACCEL = 40.0
#: Speed of guarded moves (descents until contact), m/s: 0.4 mm per 2 ms step,
#: so first contact is detected at sub-millimetre penetration.
GUARDED_SPEED = 0.2
#: A guarded descent tests contacts only once the command has come within this
#: distance (m) of the clearance below (a servo's overshoot, objects settling) ...
GUARD_SLACK = 0.002
#: ... counting what lies within this distance (m) sideways of the moving part.
GUARD_MARGIN = 0.01
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
#: Lift after the release before the primitive ends (m): off the object, not more
#: (the next transfer climbs from here anyway).
RETREAT = 0.015
#: The objects rest when no free object moves faster than this (m/s; see
#: :meth:`~factask.sim.robots.suction.SuctionGripper.objects_resting`) ...
REST_SPEED = 0.02
#: ... or after this long (s).
REST_MAX_TIME = 0.3
#: Before release, objects must move slower than this (m/s) when the held one
#: can roll (a ball let go while it swings rolls on: rolling friction, BALL_FRICTION,
#: stops one at 2 cm/s within 1.5 mm, one at 4 cm/s within 5 mm: faster goes further) ...
RELEASE_SPEED = 0.003
#: ... or this when it cannot (a box set down moving at 1 cm/s stops at once) ...
RELEASE_SPEED_FLAT = 0.01
#: A round object's turning is weighed at this distance (m) before its release:
#: every turn of a ball becomes rolling once it is let go, so it must barely turn
#: (|angular velocity| below RELEASE_SPEED in rad/s); a box's at REST_RADIUS.
ROUND_TURN_RADIUS = 1.0
#: ... or this many seconds pass.
RELEASE_MAX_TIME = 0.5
#: Default cap on physics steps of one primitive (40 s at dt = 2 ms).
DEFAULT_MAX_STEPS = 20_000
#: Default number of physics steps between ``on_step`` calls.
DEFAULT_CALLBACK_EVERY = 10
#: Physics steps between health checks (NaN state, fatal MuJoCo warnings): a
#: blow-up is caught within 0.1 s of simulated time (MuJoCo's warnings latch), and
#: motions are played in chunks of at most this many steps.
HEALTH_EVERY = 50
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


class PrimitiveAbort(FactaskError):
    """Ends a primitive early with a reason (caught in
    :meth:`SuctionRobot.pick_and_place` and the other primitives; never leaves
    the robot modules)."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason



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
        self._health = HealthWatch(data)
        self._aborted = False
        #: How the tool leans from straight down during the current primitive, a
        #: rotation in its yawed frame (None: straight down); see :meth:`lean_clear_of`.
        self.tool_lean: np.ndarray | None = None

    #: How far (m) the tip may end a transfer below its command: a transfer stops
    #: this much higher than the clearance below would allow (none for a mocap).
    overshoot = 0.0

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
    def _play(self, rows: np.ndarray) -> None:
        """Apply ``rows`` and step once after each, nothing else: the hot loop (the
        caller keeps the books, :meth:`_follow`)."""

    @abstractmethod
    def _hold_here(self) -> None:
        """Command the measured tip pose (after a guarded stop, to stop pushing)."""

    def _recover(self) -> None:  # noqa: B027 - optional hook, a mocap cannot get stuck
        """Bring the robot back to a known state after an aborted primitive."""

    def _settle(self) -> None:  # noqa: B027 - optional hook, a mocap needs no settling
        """Step until the tip tracks its command (arm); nothing to do for a mocap."""

    def lean_clear_of(self, tip: np.ndarray, yaw: float) -> np.ndarray | None:
        """How to lean the tool, its tip at ``tip`` turned by ``yaw``, so that the
        robot's links clear the solids beside it (a handle on a tall cabinet's face):
        a rotation for :attr:`tool_lean` (:func:`factask.sim.robots.ik.tool_quat`), or
        None when straight down is clear. The floating cup has no links: always None."""
        return None

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
        return self.execute(lambda: self._run(pick, place), on_step, max_steps, callback_every)

    def execute(self, body: Callable[[], int | None],
                on_step: Callable[[], None] | None = None,
                max_steps: int = DEFAULT_MAX_STEPS,
                callback_every: int = DEFAULT_CALLBACK_EVERY) -> PrimitiveResult:
        """Run one primitive's motions with the books every primitive keeps: the
        step budget and callback, the health watch, recovery after an aborted one,
        and on an abort the suction let go.

        Args:
            body: The motions; returns the grasped body (or None), raises
                :class:`PrimitiveAbort` to fail.
            on_step: Called every ``callback_every`` physics steps.
            max_steps: Physics-step budget; exceeding it fails the primitive.
            callback_every: Physics steps between ``on_step`` calls.

        Returns:
            The result; an abort comes back as ``ok=False`` with its reason.
        """
        self._steps = 0
        self._max_steps = max_steps
        self._on_step = on_step
        self._callback_every = max(1, callback_every)
        self._health.rebase()
        grasped: int | None = None
        self.tool_lean = None
        try:
            self._check_health()
            if self._aborted:
                self._recover()
            self._aborted = False
            grasped = body()
            self._check_health()
        except PrimitiveAbort as abort:
            self._aborted = True
            if self.gripper.held is not None:
                grasped = self.gripper.held
            self.gripper.release()
            return PrimitiveResult(False, abort.reason, self._steps, grasped)
        finally:
            self._on_step = None
            self.tool_lean = None
        return PrimitiveResult(True, None, self._steps, grasped)

    # ----- the primitive -----

    def _run(self, pick: Pose, place: Pose) -> int:
        """Execute the primitive; returns the grasped body or raises PrimitiveAbort."""
        pick_yaw, place_yaw = self._yaw_plan(pick, place)
        if self.gripper.held is not None:
            self.gripper.release()
        up = np.array([0.0, 0.0, 1.0])
        # Lean out of tall furniture beside the pick, and keep the lean to the place so
        # the held object stays level.
        self.tool_lean = self.lean_clear_of(pick.pos, pick_yaw)
        # Transfer to just above the pick, then a guarded descent to the first contact.
        self._transfer(self._pick_approach(pick.pos), pick_yaw)
        if self._descend(pick.pos - PICK_OVERSHOOT * up, pick_yaw, held=False):
            self._hold_here()
        if not self.suction_on():
            self._transfer(self._cmd_pos + APPROACH_HEIGHT * up, self._cmd_yaw)
            raise PrimitiveAbort("nothing to grasp at pick pose")
        grasped = self.gripper.held
        assert grasped is not None
        # Carry to just above the place pose, then a guarded descent until it rests.
        self._transfer(place.pos + APPROACH_HEIGHT * up, place_yaw)
        if not self.gripper.held_in_contact() and self._descend(place.pos, place_yaw, held=True):
            self._hold_here()
        self._settle()
        if self.gripper.held is None:
            raise PrimitiveAbort("object lost during transport")
        # Release only once everything is still: a ball let go while it still swings
        # on the cup rolls on (rolling friction stops it only after mm to cm).
        if self.gripper.held_can_roll():
            self._wait_for_rest(RELEASE_SPEED, RELEASE_MAX_TIME, ROUND_TURN_RADIUS)
        else:
            self._wait_for_rest(RELEASE_SPEED_FLAT, RELEASE_MAX_TIME)
        self.suction_off()
        self._follow(self._path([(self._cmd_pos + RETREAT * up, self._cmd_yaw)]))
        self._wait_for_rest()
        return grasped

    def _transfer(self, goal: np.ndarray, yaw: float) -> None:
        """Up, over and down to ``goal`` in one blended motion (the arm settles at the
        end and checks the goal was reached).

        The move over is a straight line that clears every object along the way
        (and the held one, hanging below the tip) by CLEARANCE; it may slope, so
        the climb to clear a tower at one end happens on the way, not straight up
        at the other (:meth:`_travel_heights`).
        """
        start = self._cmd_pos
        h_start, h_goal = self._travel_heights(start, goal)
        points: list[tuple[np.ndarray, float]] = []
        if start[2] < h_start - 1e-4:
            points.append((np.array([start[0], start[1], h_start]), self._cmd_yaw))
        if np.linalg.norm(goal[:2] - start[:2]) > 1e-4 or abs(yaw - self._cmd_yaw) > 1e-4:
            points.append((np.array([goal[0], goal[1], h_goal]), yaw))
        points.append((np.asarray(goal, dtype=float), yaw))
        self._follow(self._path(points))
        self._settle()

    def _pick_approach(self, target: np.ndarray) -> np.ndarray:
        """Where the transfer to a pick at ``target`` ends: APPROACH_HEIGHT above it,
        less what the clearance below the cup there leaves free (less GUARD_SLACK and
        the robot's :attr:`overshoot`), never below ``target``.

        The guarded descent would play that part untested anyway (:meth:`_descend`);
        as the end of the transfer it costs a few steps of its deceleration instead
        of a crawl at GUARDED_SPEED. The gap is measured before the transfer, with
        the solids where they are then. A place keeps its APPROACH_HEIGHT: a carried
        object hangs from a compliant weld and, after a fast move over, still trails
        and tilts (a 5 cm box's low corner about 1 cm below a rigid hold's), so its
        measured gap is not its gap; lowering that end tipped a column of boxes
        (CLIPort example stack_boxes_column).
        """
        above = np.asarray(target, dtype=float) + np.array([0.0, 0.0, APPROACH_HEIGHT])
        tip = self.data.site_xpos[self.tip_site].copy()
        room = (self.gripper.clearance(False, GUARD_MARGIN, move=(tip, above)) - GUARD_SLACK
                - self.overshoot - self.gripper.contact_reach)
        if not math.isfinite(room) or room <= 0.0:
            return above
        return above - np.array([0.0, 0.0, min(room, APPROACH_HEIGHT)])

    def _descend(self, goal: np.ndarray, yaw: float, held: bool) -> bool:
        """Guarded straight move down to (goal, yaw) at GUARDED_SPEED until the cup
        (``held`` False) or the held object touches something; True when it did.

        Contacts are tested after every step only once contact is possible: the
        steps before the command has come down by the clearance below
        (:meth:`~factask.sim.robots.suction.SuctionGripper.clearance`, less GUARD_SLACK
        and any lag of the tip behind its command) are played as one motion.
        """
        start = self._cmd_pos.copy()
        rows = self._line(goal, yaw, GUARDED_SPEED)
        stop = self.gripper.held_in_contact if held else self.gripper.cup_in_contact
        free = 0
        drop = float(start[2] - goal[2])
        if (self._on_step is None and drop > 0.0
                and float(np.abs(goal[:2] - start[:2]).max()) < 1e-6):
            lag = max(0.0, float(self.data.site_xpos[self.tip_site, 2] - start[2]))
            room = (self.gripper.clearance(held, GUARD_MARGIN) - lag - GUARD_SLACK
                    - self.gripper.contact_reach)
            n = len(rows)
            # After row i (0-based) the command is drop * (i + 1) / n lower. Nothing
            # below at all (no table there): the whole descent; NaN: none of it.
            free = (min(n, max(0, math.ceil(room * n / drop) - 1)) if math.isfinite(room)
                    else n if room > 0 else 0)
        if free:
            self._follow(rows[:free])
        return self._follow(rows[free:], stop=stop)

    def _travel_heights(self, start: np.ndarray, goal: np.ndarray) -> tuple[float, float]:
        """Tip heights above ``start`` and above ``goal`` of the move over.

        Every object along the way (the corridor as wide as the held object's
        footprint plus the cup's clearance) needs the line at least ``its top +
        the held object's hang + CLEARANCE`` high wherever it lies under it. One
        end is at the highest need (as a level move would be); the other is as low
        as the needs allow, whichever of the two choices climbs and descends less.
        """
        grip = self.gripper
        boxes = grip.object_boxes()  # once for the three queries: nothing moves meanwhile
        t_lo, t_hi, top = grip.corridor_obstacles(
            start, goal, grip.held_footprint(boxes) + CUP_CLEARANCE, boxes)
        bottom = grip.held_bottom(boxes)
        tip_z = float(self.data.site_xpos[self.tip_site, 2])
        hang = 0.0 if bottom is None else max(0.0, tip_z - bottom)
        need = top + hang + CLEARANCE
        # The table (its top at z = 0) lies under the whole line: a held object taller
        # than MIN_TRAVEL_HEIGHT - CLEARANCE would drag on it (an arm carrying a 6 cm
        # cylinder 5 cm up pressed it into the table and tipped it over).
        floor = max(MIN_TRAVEL_HEIGHT, hang + CLEARANCE)
        z0, z1 = float(start[2]), float(goal[2])
        high = max(float(need.max(initial=0.0)), floor, z1)
        # The line's height is linear along it: checking both ends of each shadow suffices.
        t = np.concatenate([t_lo, t_hi])
        n2 = np.concatenate([need, need])
        rise = t < 1.0 - 1e-9   # line ends at `high` above the goal: the start end may be low
        low_start = max(floor, z0, float(((n2 - high * t)[rise] / (1.0 - t[rise]))
                                                     .max(initial=0.0)))
        fall = t > 1e-9         # line starts at `high` above the start: the goal end may be low
        low_goal = max(floor, z1, float(((n2 - high * (1.0 - t))[fall] / t[fall])
                                                    .max(initial=0.0)))
        low_start, low_goal = min(low_start, high), min(low_goal, high)
        climb_rising = max(0.0, low_start - z0) + (high - z1)
        climb_falling = max(0.0, high - z0) + (low_goal - z1)
        if climb_rising <= climb_falling:
            return max(low_start, z0), high
        return max(high, z0), low_goal

    def _yaw_plan(self, pick: Pose, place: Pose) -> tuple[float, float]:
        """Unwrapped tool yaws at the pick and at the place.

        The cup is round, so only the difference matters: the object turns by the
        shortest rotation ``place.yaw - pick.yaw``. Tool moves follow these values
        without wrapping; this default keeps the current yaw at the pick (turning
        the empty cup would only cost time).
        """
        return self._cmd_yaw, self._cmd_yaw + wrap_angle(place.yaw - pick.yaw)

    def _wait_for_rest(self, speed: float = REST_SPEED, max_time: float = REST_MAX_TIME,
                       turn_radius: float = REST_RADIUS) -> None:
        """Step, the controls held, until no free object moves faster than ``speed``
        (at most ``max_time`` seconds; tested every REST_EVERY steps; turning
        counts at ``turn_radius``, see
        :meth:`~factask.sim.robots.suction.SuctionGripper.objects_resting`)."""
        total = max(1, math.ceil(max_time / self.dt))
        done = 0
        while done < total:
            k = min(REST_EVERY, total - done)
            self._hold(k)
            done += k
            if done < total and self.gripper.objects_resting(speed, turn_radius):
                return

    def _follow(self, samples: np.ndarray, stop: Callable[[], bool] | None = None) -> bool:
        """Apply ``samples`` one per physics step; True when ``stop`` fired.

        Without ``stop`` and ``on_step`` the samples are played in chunks that end
        at the health checks (:meth:`_play`: nothing but the controls and
        ``mj_step`` per step); a guarded move tests ``stop`` after every step.
        """
        if stop is not None or self._on_step is not None:
            for row in samples:
                self._apply(row)
                self._step()
                if stop is not None and stop():
                    return True
            return False
        done, n = 0, len(samples)
        while done < n:
            k = self._chunk(n - done)
            self._play(samples[done:done + k])
            done += k
            self._advanced(k)
        return False

    def _hold(self, steps: int) -> None:
        """``steps`` physics steps with the controls held (one ``mj_step`` call per chunk)."""
        if self._on_step is not None:
            for _ in range(steps):
                self._step()
            return
        while steps > 0:
            k = self._chunk(steps)
            mujoco.mj_step(self.model, self.data, k)
            steps -= k
            self._advanced(k)

    def _chunk(self, wanted: int) -> int:
        """How many steps to run before the next bookkeeping: at most ``wanted``, up
        to the next health check, within the budget (raises once it is spent)."""
        if self._steps >= self._max_steps:
            raise PrimitiveAbort(f"step limit exceeded ({self._max_steps} physics steps)")
        return min(wanted, HEALTH_EVERY - self._steps % HEALTH_EVERY,
                   self._max_steps - self._steps)

    def _advanced(self, steps: int) -> None:
        """Count ``steps`` done; the health check when one is due."""
        self._steps += steps
        # A blow-up is still caught within HEALTH_EVERY steps (MuJoCo's NaN warnings latch).
        if self._steps % HEALTH_EVERY == 0:
            self._check_health()

    def _step(self) -> None:
        """One physics step with budget, health and callback bookkeeping."""
        self._chunk(1)
        mujoco.mj_step(self.model, self.data)
        self._advanced(1)
        if self._on_step is not None and self._steps % self._callback_every == 0:
            self._on_step()

    def _check_health(self) -> None:
        """Raise PrimitiveAbort on a fatal MuJoCo warning since the primitive began, or
        a non-finite state (:func:`~factask.sim.robots.health.physics_problem`)."""
        problem = self._health.problem()
        if problem is not None:
            raise PrimitiveAbort(f"physics failure: {problem}")
