"""The UR-type arm's controller: IK at the waypoints, minimum-time joint trajectories.

The arm's geometry and servos are built by :mod:`factask.sim.robots.arm`; this
module plans its motions (joint space under the joint speed and acceleration
limits, via points where the tip would leave the straight line) and tracks them.
"""

from __future__ import annotations

import contextlib
import math

import mujoco
import numpy as np

from factask.geometry import Pose, quat_conj, quat_from_axis_angle, quat_mul, wrap_angle, yaw_of
from factask.sim.robots.arm import (
    HOME_QPOS,
    JOINT_NAMES,
    JOINT_RANGES,
    KP,
    KV,
)
from factask.sim.robots.ik import TopDownIK, top_down_pose
from factask.sim.robots.motion import (
    Profile,
    Shape,
    blend,
    constant_speed,
    curve_move,
    move_starts,
    profile,
)
from factask.sim.robots.primitive import (
    CLEARANCE,
    MIN_TRAVEL_HEIGHT,
    TOOL_ACCEL,
    PrimitiveAbort,
    SuctionRobot,
)
from factask.sim.robots.registry import DEFAULT_ARM, DHArm
from factask.sim.robots.suction import find_id

#: State part one control row of :meth:`ArmSuctionRobot._play` writes.
_CTRL_STATE = int(mujoco.mjtState.mjSTATE_CTRL)
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
#: ... but a vertical move (a lift off a pick or a release, a descent onto one) by at
#: most this much (m): it starts or ends between neighbours, and a joint-space lift
#: bulging 5 mm sideways pushed a picked block into one wedged against a pillar and
#: flipped it (CLIPort probe blocks_around_fixed_cylinder).
VERTICAL_DRIFT_TOL = 0.001
#: Halvings of a move at most when placing via points (2**4 = 16 segments).
VIA_DEPTH = 4
#: Simulated seconds the arm takes at least to return home after an aborted primitive.
RECOVER_TIME = 0.5
#: Distance (rad) the arm's last wrist joint keeps from its range limits.
WRIST_MARGIN = 0.6
#: How far (rad) the tool may lean from straight down when the arm's links would hit
#: a solid beside the tip (:meth:`ArmSuctionRobot.lean_clear_of`), the least that
#: clears first: the wrist's last link is a 4 cm cylinder round the tool axis from 12
#: cm above the tip, a drawer handle's middle is 1.75 cm in front of its cabinet's
#: face (13 degrees just clear it); the wrist, 24 cm above the tip, moves 8-15 cm.
LEAN_ANGLES = tuple(math.radians(a) for a in (20.0, 25.0, 30.0, 40.0))
#: Points tested along each of the arm's links (:meth:`ArmSuctionRobot.lean_clear_of`).
LINK_SAMPLES = 7
#: The links tested: the upper arm, forearm and wrist (the base column cannot move).
LEANING_LINKS = ("link2_geom", "link3_geom", "link4_geom", "link5_geom", "link6_geom")
#: Gap (m) within which a solid beside the arm's links, the tool straight down, makes
#: it lean (a lean is taken when its links touch nothing).
LEAN_MARGIN = 0.01


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

    #: The servos end a transfer's descent up to 4 mm below the command (measured:
    #: 116 transfers of 6 library tasks, median 1.2 mm); 5 mm kept.
    overshoot = 0.005

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
        m = self.ik.model
        self._link_geoms = np.array([find_id(m, mujoco.mjtObj.mjOBJ_GEOM, n)
                                     for n in LEANING_LINKS])
        # Offsets along each link's axis (its geom's z) of the points tested.
        self._link_spans = (np.linspace(-1.0, 1.0, LINK_SAMPLES)[None, :]
                            * m.geom_size[self._link_geoms, 1:2])

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
        last wrist turned to the unwrapped yaw; raises PrimitiveAbort if unreachable."""
        q, err = self.ik.solve_near(q0, pos, yaw, lean=self.tool_lean)
        if err > REACH_TOL:
            # Far or awkward targets: mink along a straight path, from q0.
            self.ik.set_q(q0)
            q, err, _ = self.ik.solve(top_down_pose(pos, yaw, self.tool_lean))
        if err > REACH_TOL:
            raise PrimitiveAbort(
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
              ya: float, yb: float, depth: int = VIA_DEPTH,
              drift_tol: float | None = None) -> list[np.ndarray]:
        """Joint via points so that the joint-space move from qa to qb sags at most
        SAG_TOL below the straight tip line from pa to pb and strays at most
        ``drift_tol`` from it sideways (obstacles are looked for along that line only:
        a joint-space arc can swing the cup through a tower beside it). Default:
        VERTICAL_DRIFT_TOL for a vertical move, else DRIFT_TOL."""
        if drift_tol is None:
            vertical = float(np.linalg.norm(pb[:2] - pa[:2])) < 1e-4
            drift_tol = VERTICAL_DRIFT_TOL if vertical else DRIFT_TOL
        sag = drift = 0.0
        for s in (0.25, 0.5, 0.75):
            tip, line = self.ik.fk(qa + s * (qb - qa)), pa + s * (pb - pa)
            sag = max(sag, float(line[2] - tip[2]))
            drift = max(drift, float(np.linalg.norm(tip[:2] - line[:2])))
        if (sag <= SAG_TOL and drift <= drift_tol) or depth == 0:
            return []
        pm, ym = 0.5 * (pa + pb), 0.5 * (ya + yb)
        qm = self._solve(qa, pa, ya, pm, ym)
        return [*self._vias(qa, qm, pa, pm, ya, ym, depth - 1, drift_tol), qm,
                *self._vias(qm, qb, pm, pb, ym, yb, depth - 1, drift_tol)]

    def _targets(self, qs: np.ndarray) -> np.ndarray:
        """Servo targets of joint samples: angles plus the damping lead of their speed."""
        qd = np.gradient(qs, self.dt, axis=0) if len(qs) > 1 else np.zeros_like(qs)
        qd[-1] = 0.0
        self._cmd_q = qs[-1].copy()
        return np.clip(qs, self._lo, self._hi) + self._lead * qd

    def _path(self, points: list[tuple[np.ndarray, float]]) -> np.ndarray:
        qs = [self._cmd_q.copy()]
        shapes: list[Shape | None] = []
        profiles: list[Profile] = []
        pa, ya = self._cmd_pos.copy(), self._cmd_yaw
        for pos, yaw in points:
            q = self._solve(qs[-1], pa, ya, pos, yaw)
            vias = self._vias(qs[-1], q, pa, pos, ya, yaw)
            if vias:
                # One smooth move through the via points: no slowing down at them.
                shape, prof = curve_move(np.array([qs[-1], *vias, q]), self._vmax, self._amax)
                shapes.append(shape)
            else:
                shapes.append(None)
                prof = profile(q - qs[-1], self._vmax, self._amax)
            qs.append(q)
            profiles.append(prof)
            pa, ya = np.asarray(pos, dtype=float), yaw
        laps = [math.sqrt(2 * CLEARANCE / TOOL_ACCEL)] * (len(profiles) - 1)
        samples = blend(qs, profiles, laps, self.dt, shapes)
        # Overlapping moves of one joint in opposite directions add their
        # accelerations: the corners where the limits break get no overlap.
        for _ in range(len(laps)):
            acc = np.abs(np.diff(samples, 2, axis=0)) / self.dt**2
            over = np.flatnonzero((acc > 1.05 * self._amax).any(axis=1))
            if len(over) == 0:
                break
            corners = np.array(move_starts(profiles, laps)[1:])
            for t in (over + 1) * self.dt:
                laps[int(np.abs(corners - t).argmin())] = 0.0
            samples = blend(qs, profiles, laps, self.dt, shapes)
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

    def _play(self, rows: np.ndarray) -> None:
        # One mj_setState per step writes the whole control vector: one C call,
        # cheaper than a fancy-indexed copy from Python.
        m, d = self.model, self.data
        full = np.empty((len(rows), m.nu))
        full[:] = d.ctrl
        full[:, self.act] = rows
        step, set_state = mujoco.mj_step, mujoco.mj_setState
        for row in full:
            set_state(m, d, row, _CTRL_STATE)
            step(m, d)

    def _hold_here(self) -> None:
        # Command the measured joints so the servos stop pushing down.
        q = self.data.qpos[self.qpos_adr].copy()
        self.data.ctrl[self.act] = q
        self._cmd_q = q
        ee = self.ee_pose()
        self._cmd_pos = ee.pos.copy()
        self._cmd_yaw += wrap_angle(self._tool_yaw(ee) - self._cmd_yaw)  # unwrapped branch

    def _settle(self) -> None:
        total, done = math.ceil(SETTLE_MAX_TIME / self.dt), 0
        while done < total:
            err = float(np.linalg.norm(self.data.site_xpos[self.tip_site] - self._cmd_pos))
            speed = float(np.abs(self.data.qvel[self.dof_adr]).max())
            if err < SETTLE_TOL and speed < SETTLE_SPEED:
                return
            k = min(2, total - done)
            self._hold(k)
            done += k

    def _recover(self) -> None:
        # An aborted primitive can leave the arm anywhere: lift straight up, then
        # move the joints home and restart from there.
        self._cmd_q = self.data.qpos[self.qpos_adr].copy()
        ee = self.ee_pose()
        self._cmd_pos = ee.pos.copy()
        self._cmd_yaw += wrap_angle(self._tool_yaw(ee) - self._cmd_yaw)
        up = self._cmd_pos.copy()
        up[2] = max(up[2], self.gripper.obstacle_top() + CLEARANCE, MIN_TRAVEL_HEIGHT)
        with contextlib.suppress(PrimitiveAbort):  # an unreachable lift: go home from here
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

    def _tool_yaw(self, ee: Pose) -> float:
        """Yaw of the tip pose ``ee`` with the current lean taken off."""
        if self.tool_lean is None:
            return ee.yaw
        return yaw_of(quat_mul(ee.quat, quat_conj(self.tool_lean)))

    def lean_clear_of(self, tip: np.ndarray, yaw: float) -> np.ndarray | None:
        """Lean the tool away from solids the arm's links would hit with the tool
        straight down at ``tip``.

        The arm's pose there (IK near the commanded joints) puts its links, each a
        capsule (the last a cylinder round the tool axis from 12 cm above the tip),
        against every solid's own box: the wrist, 24 cm above the tip, and the forearm
        reach over anything beside a low tip taller than about 19 cm (a tall cabinet
        over the handle of its bottom drawer, a fridge beside a block on the table).
        Those within :data:`LEAN_MARGIN` push the tool's upper end away from them,
        by the first of :data:`LEAN_ANGLES` with which none touches them (the tip
        stays where it is, the cup meets the surface its low rim first).

        Returns:
            The lean, a rotation in the frame of the tool turned by ``yaw``
            (:func:`factask.sim.robots.ik.tool_quat`), or None when straight down is
            clear, the pose is out of reach, or no lean clears it.
        """
        tip = np.asarray(tip, dtype=float)
        if not self.gripper.furniture.any():
            return None
        away = self._link_hits(tip, yaw, None)
        if away is None or not len(away):
            return None
        direction = (away / np.linalg.norm(away, axis=1, keepdims=True)).sum(axis=0)
        norm = float(np.linalg.norm(direction))
        if norm < 1e-6:
            return None
        n = direction / norm
        # The axis (z x n) in the yawed tool's frame: turning +z about it leans toward n.
        c, s = math.cos(yaw), math.sin(yaw)
        axis = (c * -float(n[1]) + s * float(n[0]), -s * -float(n[1]) + c * float(n[0]), 0.0)
        for angle in LEAN_ANGLES:
            lean = quat_from_axis_angle(axis, angle)
            left = self._link_hits(tip, yaw, lean, margin=0.0)
            if left is not None and not len(left):
                return lean
        return None

    def _link_hits(self, tip: np.ndarray, yaw: float, lean: np.ndarray | None,
                   margin: float = LEAN_MARGIN) -> np.ndarray | None:
        """Horizontal vectors (k, 2) from the furniture (fixed solids, drawers: loose
        objects are pushed aside, as before) to the points of the arm's links that come
        within ``margin`` of it with the tip at (tip, yaw, lean); None when IK does not
        reach it."""
        kept, self.tool_lean = self.tool_lean, lean
        try:
            q = self._solve(self._cmd_q, self._cmd_pos, self._cmd_yaw, tip, yaw)
        except PrimitiveAbort:
            return None
        finally:
            self.tool_lean = kept
        self.ik.fk(q)
        ik = self.ik._data
        ids = self._link_geoms
        points = (ik.geom_xpos[ids, None, :] + self._link_spans[:, :, None]
                  * ik.geom_xmat[ids].reshape(-1, 3, 3)[:, None, :, 2]).reshape(-1, 3)
        radius = np.repeat(self.ik.model.geom_size[ids, 0], LINK_SAMPLES) + margin
        g, d = self.gripper, self.data
        solids = g.object_geoms[g.furniture]
        centre, half = g.local_box_centre[g.furniture], g.local_box_half[g.furniture]
        rot = d.geom_xmat[solids].reshape(-1, 3, 3)
        rel = np.einsum("nji,knj->kni", rot, points[:, None, :] - d.geom_xpos[solids])
        near = np.clip(rel, centre - half, centre + half)
        away = np.einsum("nij,knj->kni", rot, rel - near)  # world: solid -> link point
        hit = np.linalg.norm(away, axis=2) <= radius[:, None]
        flat = away[hit][:, :2]
        return flat[np.linalg.norm(flat, axis=1) > 1e-6]

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
