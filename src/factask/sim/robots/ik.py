"""Top-down inverse kinematics of the suction arm with mink.

IK runs on a private arm-only model (the same spec elements the scene got,
compiled alone), so free objects in the scene never enter the IK problem and the solve
stays ~6x6. Its joint order is ``robot_arm.JOINT_NAMES``; the caller maps it to
the scene's joints by name.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import mink
import mujoco
import numpy as np

from factask.geometry import Pose, quat_from_yaw, quat_mul, slerp
from factask.sim.robots.arm import HOME_QPOS, build_arm
from factask.sim.robots.registry import DEFAULT_ARM, DHArm
from factask.sim.robots.suction import TIP_SITE

#: QP solver bundled with mink's dependencies.
QP_SOLVER = "daqp"
#: Weight of the tip-pose task versus the posture regulariser.
POSITION_COST = 1.0
ORIENTATION_COST = 1.0
POSTURE_COST = 1e-3
#: Levenberg-Marquardt damping: keeps steps bounded near singular poses.
LM_DAMPING = 1e-4
#: Nominal differential-IK step (s); with task gain 1 one iteration closes the
#: whole linearised error, so the value only scales the returned velocity.
IK_DT = 0.01
#: Convergence thresholds of :meth:`TopDownIK.solve`.
POS_TOL = 1e-3
#: Largest target move per iteration when :meth:`TopDownIK.solve` walks a path (m).
MAX_TARGET_STEP = 0.02
ROT_TOL = 1e-2
#: Damped least squares (:meth:`TopDownIK.solve_near`): damping, iterations,
#: largest joint step per iteration (rad) and convergence thresholds (m, rad).
DLS_DAMPING = 1e-6
DLS_ITERATIONS = 40
DLS_MAX_STEP = 0.3
DLS_POS_TOL = 1e-4
DLS_ROT_TOL = 1e-3


def top_down_pose(pos: Sequence[float], yaw: float, lean: np.ndarray | None = None) -> Pose:
    """Tip pose with the tool straight down and yaw ``yaw`` (tip frame z is up), then
    leaned by ``lean`` (:func:`tool_quat`; None: straight down)."""
    return Pose(np.asarray(pos, dtype=float), tool_quat(yaw, lean))


def tool_quat(yaw: float, lean: np.ndarray | None = None) -> np.ndarray:
    """Orientation (w, x, y, z) of the tip frame: straight down at ``yaw``, then leaned by
    ``lean``, a rotation in that yawed frame (None: none). The lean turns with the yaw,
    so an object held by a leaning tool turns about the vertical only, staying level."""
    down = quat_from_yaw(yaw)
    return down if lean is None else quat_mul(down, lean)


class TopDownIK:
    """Differential IK (mink) for the ``suction_tip`` site of the arm.

    Args:
        arm: DH parameters; must match the arm in the scene.
        home: Posture target and initial configuration (6 joint angles).
    """

    def __init__(self, arm: DHArm = DEFAULT_ARM, home: Sequence[float] = HOME_QPOS) -> None:
        spec = mujoco.MjSpec()
        spec.modelname = "ik_arm"
        build_arm(spec, arm)
        self.model = spec.compile()
        self.home = np.asarray(home, dtype=float)
        self.configuration = mink.Configuration(self.model, self.home.copy())
        self.frame_task = mink.FrameTask(
            frame_name=TIP_SITE, frame_type="site",
            position_cost=POSITION_COST, orientation_cost=ORIENTATION_COST,
            lm_damping=LM_DAMPING,
        )
        self.posture_task = mink.PostureTask(self.model, cost=POSTURE_COST)
        self.posture_task.set_target(self.home)
        self.limits = [mink.ConfigurationLimit(self.model)]
        self.solve_calls = 0
        # Damped least squares on the same private model (see :meth:`solve_near`).
        self._data = mujoco.MjData(self.model)
        self._site = self.model.site(TIP_SITE).id
        self._jac = np.zeros((6, self.model.nv))
        self._damping = DLS_DAMPING * np.eye(6)
        self._lo = self.model.jnt_range[:, 0].copy()
        self._hi = self.model.jnt_range[:, 1].copy()

    @property
    def q(self) -> np.ndarray:
        """Current IK joint solution (copy)."""
        return self.configuration.q.copy()

    def set_q(self, q: Sequence[float]) -> None:
        """Restart the IK from joint angles ``q``."""
        self.configuration.update(np.asarray(q, dtype=float))

    def tip_pose(self) -> Pose:
        """Tip pose of the current IK solution (forward kinematics)."""
        t = self.configuration.get_transform_frame_to_world(TIP_SITE, "site")
        wxyz_xyz = t.wxyz_xyz
        return Pose(wxyz_xyz[4:], wxyz_xyz[:4])

    def error(self, target: Pose) -> tuple[float, float]:
        """Position (m) and orientation (rad) error of the current solution to ``target``."""
        cur = self.tip_pose()
        pos_err = float(np.linalg.norm(cur.pos - target.pos))
        dot = abs(float(np.dot(cur.quat, target.quat)))
        rot_err = 2.0 * float(np.arccos(min(1.0, dot)))
        return pos_err, rot_err

    def step(self, target: Pose, iterations: int = 1) -> np.ndarray:
        """Take ``iterations`` differential-IK steps toward ``target``.

        Args:
            target: Desired tip pose.
            iterations: QP solves to run.

        Returns:
            The joint solution after the steps (copy).
        """
        self.frame_task.set_target(
            mink.SE3.from_rotation_and_translation(mink.SO3(target.quat), target.pos)
        )
        tasks = [self.frame_task, self.posture_task]
        for _ in range(iterations):
            vel = mink.solve_ik(
                self.configuration, tasks, IK_DT, QP_SOLVER, damping=LM_DAMPING,
                limits=self.limits,
            )
            self.configuration.integrate_inplace(vel, IK_DT)
            self.solve_calls += 1
        return self.q

    def solve(
        self, target: Pose, max_iterations: int = 300, max_step: float = MAX_TARGET_STEP,
    ) -> tuple[np.ndarray, float, float]:
        """Converge on ``target`` from the current solution along a straight path.

        The intermediate targets move at most ``max_step`` metres per iteration
        from the current tip toward ``target``, as the arm would follow a path;
        jumping straight to a far target can land differential IK in a local
        minimum (a folded wrist).

        Args:
            target: Desired tip pose.
            max_iterations: Upper bound on QP solves.
            max_step: Largest target displacement per iteration (m).

        Returns:
            (joint solution, position error m, orientation error rad).
        """
        start = self.tip_pose()
        dist = float(np.linalg.norm(target.pos - start.pos))
        n_path = max(1, math.ceil(dist / max_step))
        iterations = 0
        for k in range(1, n_path + 1):
            s = k / n_path
            waypoint = Pose(
                start.pos + s * (target.pos - start.pos), slerp(start.quat, target.quat, s)
            )
            self.step(waypoint)
            iterations += 1
        pos_err, rot_err = self.error(target)
        while iterations < max_iterations and not (pos_err < POS_TOL and rot_err < ROT_TOL):
            self.step(target)
            iterations += 1
            pos_err, rot_err = self.error(target)
        return self.q, pos_err, rot_err

    def fk(self, q: np.ndarray) -> np.ndarray:
        """Tip position of joint angles ``q`` (forward kinematics, no IK state change).

        Args:
            q: Joint angles.

        Returns:
            The tip position (3,).
        """
        d = self._data
        d.qpos[:] = q
        mujoco.mj_kinematics(self.model, d)
        return d.site_xpos[self._site].copy()

    def solve_near(self, q0: np.ndarray, pos: np.ndarray, yaw: float,
                   iterations: int = DLS_ITERATIONS,
                   lean: np.ndarray | None = None) -> tuple[np.ndarray, float]:
        """Top-down IK from ``q0`` by damped least squares (Newton steps on the
        pose error); fast, for targets near the pose of ``q0``.

        Args:
            q0: Start joint angles (the current or the previous waypoint's).
            pos: Tip target position.
            yaw: Tip target yaw (tool straight down).
            iterations: Newton steps at most.
            lean: The tool's lean (:func:`tool_quat`); None: straight down.

        Returns:
            (joint angles, position error m); :meth:`solve` (mink) is the fallback
            when the error stays large.
        """
        m, d = self.model, self._data
        target = np.zeros(9)
        mujoco.mju_quat2Mat(target, tool_quat(yaw, lean))
        rt = target.reshape(3, 3)
        q = np.array(q0, dtype=float)
        goal = np.asarray(pos, dtype=float)
        err = np.zeros(6)
        damping = self._damping
        qpos, tip, rot = d.qpos, d.site_xpos[self._site], d.site_xmat[self._site].reshape(3, 3)
        jac, jac_pos, jac_rot = self._jac, self._jac[:3], self._jac[3:]
        lo, hi = self._lo, self._hi
        for _ in range(iterations):
            qpos[:] = q
            mujoco.mj_kinematics(m, d)
            np.subtract(goal, tip, out=err[:3])
            # Rotation error: half the sum of axis cross products (small-angle axis-angle),
            # sum_k rot[:, k] x rt[:, k] written out (np.cross costs more than the rest).
            err[3] = 0.5 * float(rot[1] @ rt[2] - rot[2] @ rt[1])
            err[4] = 0.5 * float(rot[2] @ rt[0] - rot[0] @ rt[2])
            err[5] = 0.5 * float(rot[0] @ rt[1] - rot[1] @ rt[0])
            if float(err[:3] @ err[:3]) < DLS_POS_TOL ** 2 and \
                    float(err[3:] @ err[3:]) < DLS_ROT_TOL ** 2:
                break
            mujoco.mj_comPos(m, d)  # the Jacobian needs it; the error test does not
            mujoco.mj_jacSite(m, d, jac_pos, jac_rot, self._site)
            dq = jac.T @ np.linalg.solve(jac @ jac.T + damping, err)
            # Bounded steps keep the Newton iteration from jumping to another branch.
            biggest = float(np.abs(dq).max())
            if biggest > DLS_MAX_STEP:
                dq *= DLS_MAX_STEP / biggest
            q += dq
            np.maximum(q, lo, out=q)
            np.minimum(q, hi, out=q)
        qpos[:] = q
        mujoco.mj_kinematics(m, d)
        return q, float(np.linalg.norm(goal - tip))
