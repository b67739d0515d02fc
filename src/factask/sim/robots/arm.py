"""The UR-like 6-DoF suction arm as MjSpec elements, built from published DH kinematics.

No mesh and no download: each link is a body placed by the standard DH transform
``Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i)`` with a capsule collision shape along the
link. Joint ``i`` rotates about the z axis of body ``i`` (DH frame ``i-1``).
Every link has ``gravcomp=1`` (gravity compensated, as a real arm's controller
does) and a high-gain position actuator with velocity damping.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from factask.geometry import quat_from_axis_angle
from factask.sim.robots.registry import DEFAULT_ARM, DHArm
from factask.sim.robots.suction import (
    ROBOT_CONAFFINITY,
    ROBOT_CONTYPE,
    STEM_RADIUS,
    add_suction_weld,
    add_tool,
)

#: Joint names, base to wrist.
JOINT_NAMES = (
    "shoulder_pan", "shoulder_lift", "elbow", "wrist_1", "wrist_2", "wrist_3",
)
#: Joint ranges (radians): +-2 pi like the real arm, elbow +-pi (it cannot fold through itself).
JOINT_RANGES = ((-2 * math.pi, 2 * math.pi),) * 2 + ((-math.pi, math.pi),) + (
    (-2 * math.pi, 2 * math.pi),) * 3
#: Home configuration: elbow up, tool straight down, over the workspace near x = 0.4.
HOME_QPOS = (0.0, -1.9, 1.9, -1.5708, -1.5708, -1.5708)
#: Position servo gains (N m / rad) and damping (N m s / rad) per joint: stiff
#: enough that a held 0.1 kg block moves the tip well under 1 mm.
KP = (4000.0, 4000.0, 3000.0, 1000.0, 1000.0, 1000.0)
KV = (400.0, 400.0, 300.0, 100.0, 100.0, 100.0)
#: Joint torque limits (N m) of the actuators.
FORCE_LIMIT = (330.0, 330.0, 150.0, 56.0, 56.0, 56.0)
#: Rotor inertia added to each joint: keeps the stiff servos stable at dt = 2 ms.
ARMATURE = 0.1
#: Link masses (kg), base to wrist.
LINK_MASS = (3.7, 8.4, 2.3, 1.2, 1.2, 0.25)
#: Height of the fixed base pedestal geom (m).
BASE_HEIGHT = 0.09
#: Orientation of the base (w, x, y, z): half a turn about z.
BASE_QUAT = (0.0, 0.0, 0.0, 1.0)
#: Name of the flange body that carries the suction tool.
FLANGE_BODY = "flange"
#: Body name of link i (1..6).
LINK_BODY = "link{}"
#: Name of the body (under the flange) that carries the suction tool.
TOOL_BODY = "suction_tool"
#: Length (m) of the tube between the flange and the suction tool. The wrist's last
#: link is 8-9 cm wide around the tool axis: as a capsule right on the 10 cm tool its
#: cap came down to 6 cm above the tip, and placing a block beside a 15 cm pillar drove
#: it into the pillar's top, which pushed the block 2-3 cm off its target (CLIPort probe
#: blocks_around_fixed_cylinder). Now the link ends flat at the flange, 12 cm above the
#: tip: it clears bodies up to 12 cm above the tip within its radius of the tool axis.
#: Longer costs reach: at 3 cm the UR5e no longer reaches the table's far corners 15 cm up.
TOOL_EXTENSION = 0.02


def build_arm(spec: mujoco.MjSpec, arm: DHArm = DEFAULT_ARM) -> mujoco.MjsBody:
    """Add the arm (base at the origin), its tool, actuators and suction weld.

    Args:
        spec: Spec to add to (its angles must be in radians: ``compiler.degree``
            False, as :func:`factask.sim.build.mjspec.new_spec` makes it).
        arm: DH parameters of the arm.

    Returns:
        The flange body (its child TOOL_BODY, TOOL_EXTENSION below it, carries the
        suction tool).
    """
    spec.compiler.degree = False
    # The DH base frame has the arm reaching along -x at q = 0; turning the base
    # by pi about z puts the home pose over the Ravens workspace (+x).
    base = spec.worldbody.add_body(name="arm_base", pos=[0, 0, 0], quat=list(BASE_QUAT))
    base.add_geom(
        name="arm_base_geom", type=mujoco.mjtGeom.mjGEOM_CYLINDER,
        size=[arm.radii[0], BASE_HEIGHT / 2, 0.0], pos=[0, 0, BASE_HEIGHT / 2],
        rgba=[0.6, 0.6, 0.65, 1], contype=ROBOT_CONTYPE, conaffinity=ROBOT_CONAFFINITY,
    )
    parent = base
    child_pos: list[float] = [0.0, 0.0, 0.0]
    child_quat: list[float] = [1.0, 0.0, 0.0, 0.0]
    for i in range(6):
        body = parent.add_body(name=LINK_BODY.format(i + 1), pos=child_pos, quat=child_quat,
                               gravcomp=1.0)
        body.add_joint(
            name=JOINT_NAMES[i], type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0, 0, 1],
            range=list(JOINT_RANGES[i]), limited=mujoco.mjtLimited.mjLIMITED_TRUE,
            armature=ARMATURE, damping=1.0,
        )
        # Next DH frame, expressed in this body's (rotated) frame.
        child_pos = [arm.a[i], 0.0, arm.d[i]]
        child_quat = quat_from_axis_angle((1.0, 0.0, 0.0), arm.alpha[i]).tolist()
        start = np.zeros(3)
        if i == 0:
            # Keep the shoulder capsule above the pedestal (and the table).
            start = np.array([0.0, 0.0, BASE_HEIGHT + arm.radii[0]])
        end = np.array(child_pos)
        if np.linalg.norm(end - start) < 1e-6:
            end = start + np.array([0.0, 0.0, 0.02])
        # The last link ends flat at the flange, as a real wrist does: a capsule's
        # cap would reach its radius (4 cm) further down along the tool.
        last = i == 5
        body.add_geom(
            name=f"link{i + 1}_geom",
            type=mujoco.mjtGeom.mjGEOM_CYLINDER if last else mujoco.mjtGeom.mjGEOM_CAPSULE,
            size=[arm.radii[i], 0.0, 0.0], fromto=[*start, *end], mass=LINK_MASS[i],
            rgba=[0.55, 0.6, 0.7, 1], contype=ROBOT_CONTYPE, conaffinity=ROBOT_CONAFFINITY,
        )
        servo = spec.add_actuator(
            name=f"{JOINT_NAMES[i]}_servo", target=JOINT_NAMES[i],
            trntype=mujoco.mjtTrn.mjTRN_JOINT,
            # No ctrlrange: the controller clamps targets to JOINT_RANGES itself.
            forcelimited=mujoco.mjtLimited.mjLIMITED_TRUE,
            forcerange=[-FORCE_LIMIT[i], FORCE_LIMIT[i]],
        )
        servo.set_to_position(kp=KP[i], kv=KV[i])
        parent = body
    flange = parent.add_body(name=FLANGE_BODY, pos=child_pos, quat=child_quat, gravcomp=1.0)
    # The extension tube, then the tool at its end (a body without joints: fixed to it).
    flange.add_geom(
        name="tool_extension", type=mujoco.mjtGeom.mjGEOM_CYLINDER,
        size=[STEM_RADIUS, TOOL_EXTENSION / 2, 0.0], pos=[0, 0, TOOL_EXTENSION / 2],
        rgba=[0.3, 0.3, 0.3, 1], mass=0.03, contype=ROBOT_CONTYPE,
        conaffinity=ROBOT_CONAFFINITY,
    )
    tool = flange.add_body(name=TOOL_BODY, pos=[0, 0, TOOL_EXTENSION], gravcomp=1.0)
    add_tool(tool, down=True)
    add_suction_weld(spec, tool)
    return flange
