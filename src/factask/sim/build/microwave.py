"""Microwaves and their doors in a compiled scene: the door's body, its hinge joint,
its pose read from the joint.

A microwave is a mocap body like every fixed object; its door is a body *inside*
the microwave's, at the door's closed place, turned by one hinge joint about the
vertical axis through :func:`~factask.vocabulary.kinds.door_hinge` (range 0 ..
:data:`~factask.vocabulary.kinds.DOOR_RANGE`), so the door goes wherever its
microwave is put and its opening is one number of ``qpos``. MuJoCo leaves out
contacts between a body and its parent, so the door never rubs on its microwave;
only the joint holds it. The shapes come from :mod:`factask.scene.microwave`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from factask.geometry import Pose, quat_from_yaw, quat_mul, rotation_matrix, wrap_angle, yaw_of
from factask.scene.objects import SceneObject
from factask.sim.build.mjspec import BodyHandles, add_plan_geoms
from factask.sim.build.parts import GEOM_SEPARATOR, ObjectPlan, fmt
from factask.vocabulary.kinds import DOOR_RANGE, door_closed_offset, door_hinge

#: Damping (N m s/rad) of a door's hinge: with the handle some 15 cm out, about a
#: drawer's slide damping at the handle; the door stops within a degree once let go.
HINGE_DAMPING = 0.45
#: Dry friction (N m) of the hinge: the door stays where it is left, though nudged.
HINGE_FRICTION = 0.15
#: Armature (kg m^2) of the hinge: steadies the joint under the suction weld.
HINGE_ARMATURE = 0.002


@dataclass(frozen=True)
class HingeHandle:
    """Where a door's state lives in a compiled model.

    Attributes:
        qpos_adr: Address of its hinge joint in ``qpos`` (radians swung out).
        qvel_adr: Address of the joint in ``qvel``.
        cabinet_mocap: Mocap id of its microwave (named as a drawer's slide names
            its cabinet's: the env reads both alike).
        closed: Its centre, closed, in the microwave's frame (3,).
        hinge: The hinge's axis point in the microwave's frame (3,).
        travel: The joint's range (rad).
    """

    qpos_adr: int
    qvel_adr: int
    cabinet_mocap: int
    closed: tuple[float, float, float]
    hinge: tuple[float, float, float]
    travel: float

    def pose(self, data: mujoco.MjData) -> Pose:
        """The door's world pose: its microwave's, turned about the hinge by the joint."""
        quat = data.mocap_quat[self.cabinet_mocap].copy()
        angle = float(data.qpos[self.qpos_adr])
        c, s = math.cos(angle), math.sin(angle)
        hinge = np.array(self.hinge)
        rel = np.array(self.closed) - hinge
        local = hinge + np.array([c * rel[0] - s * rel[1], s * rel[0] + c * rel[1], rel[2]])
        return Pose(data.mocap_pos[self.cabinet_mocap] + rotation_matrix(quat) @ local,
                    quat_mul(quat, quat_from_yaw(angle)))

    def set_pose(self, data: mujoco.MjData, pose: Pose) -> None:
        """Swing the door to ``pose``'s yaw relative to its microwave (the microwave
        stays; the rest of ``pose`` follows from the microwave's), and stop it."""
        quat = data.mocap_quat[self.cabinet_mocap]
        angle = wrap_angle(pose.yaw - yaw_of(quat))
        data.qpos[self.qpos_adr] = float(np.clip(angle, 0.0, self.travel))
        data.qvel[self.qvel_adr] = 0.0


def add_door(spec: mujoco.MjSpec, plan: ObjectPlan, obj: SceneObject,
             microwave: BodyHandles, microwave_obj: SceneObject,
             obj_cls: mujoco.MjsDefault) -> BodyHandles:
    """Add a door's body inside its microwave's, with its hinge joint.

    Args:
        spec: The scene's spec.
        plan: The door's plan (:func:`~factask.sim.build.cabinet.furniture_plan`).
        obj: The door.
        microwave: Its microwave's body.
        microwave_obj: Its microwave.
        obj_cls: The spec's default class of object geoms.

    Returns:
        Handles of the body, its geoms and its hinge joint.
    """
    closed = np.array(door_closed_offset(microwave_obj.size))
    hinge = np.array(door_hinge(microwave_obj.size))
    body = microwave.body.add_body(name=plan.name, pos=list(fmt(closed)))
    joint = body.add_joint(name=f"{plan.name}{GEOM_SEPARATOR}hinge",
                           type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0.0, 0.0, 1.0],
                           pos=list(fmt(hinge - closed)), range=[0.0, DOOR_RANGE],
                           limited=mujoco.mjtLimited.mjLIMITED_TRUE, damping=HINGE_DAMPING,
                           frictionloss=HINGE_FRICTION, armature=HINGE_ARMATURE)
    return BodyHandles(body, add_plan_geoms(body, plan, obj_cls), joint)


def hinge_handle(model: mujoco.MjModel, door: BodyHandles, microwave_obj: SceneObject,
                 microwave: BodyHandles) -> HingeHandle:
    """The :class:`HingeHandle` of a compiled door."""
    assert door.joint is not None
    return HingeHandle(int(model.jnt_qposadr[door.joint.id]),
                       int(model.jnt_dofadr[door.joint.id]),
                       int(model.body_mocapid[microwave.body.id]),
                       door_closed_offset(microwave_obj.size), door_hinge(microwave_obj.size),
                       DOOR_RANGE)
