"""Cabinets and drawers in a compiled scene: their bodies, the slide joints, the poses.

A cabinet is a mocap body like every fixed object; each of its drawers is a body
*inside* the cabinet's body, moved by one slide joint along the cabinet's -x axis
(range 0 .. :func:`~factask.vocabulary.kinds.drawer_travel`), so the drawer goes
wherever its cabinet is put and its opening is one number of ``qpos``. MuJoCo
leaves out contacts between a body and its parent: a drawer never rubs on its
cabinet (the gaps of :data:`~factask.vocabulary.kinds.DRAWER_GAP` keep it off its
neighbours), and only the joint holds it. Their panels come from
:mod:`factask.scene.cabinet`, the one description of their shapes.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import mujoco
import numpy as np

from factask.geometry import Pose, rotation_matrix
from factask.scene.cabinet import cabinet_boxes, drawer_boxes, drawer_seat
from factask.scene.microwave import door_boxes, microwave_boxes
from factask.scene.objects import SceneObject
from factask.scene.shelf import shelf_boxes
from factask.sim.build.mjspec import BodyHandles, add_plan_geoms
from factask.sim.build.parts import GEOM_SEPARATOR, GeomPlan, ObjectPlan, fmt
from factask.vocabulary.kinds import drawer_closed_offset, drawer_travel
from factask.vocabulary.variables import VariableSet, drawers_of

#: Kinds built here rather than from their stand-alone parts.
FURNITURE_KINDS = ("cabinet", "drawer", "microwave", "door", "shelf")
#: Damping (N s/m) of a drawer's slide: it stops within a few mm once let go.
SLIDE_DAMPING = 20.0
#: Dry friction (N) of a drawer's slide: it stays where it is left, though nudged.
SLIDE_FRICTION = 1.0
#: Armature (kg) of a drawer's slide: steadies the joint under the suction weld.
SLIDE_ARMATURE = 0.05


@dataclass(frozen=True)
class SlideHandle:
    """Where the state of a body sliding in a fixed host lives in a compiled model: a
    drawer in its cabinet, a switch's button in its stove (:mod:`factask.sim.build.switch`).

    Attributes:
        qpos_adr: Address of its slide joint in ``qpos`` (metres along ``axis``).
        qvel_adr: Address of the joint in ``qvel``.
        cabinet_mocap: Mocap id of its host (a cabinet, a stove).
        closed: Its centre at joint position 0, in the host's frame (3,).
        travel: The joint's range (m).
        axis: The joint's direction in the host's frame (a drawer slides out along
            -x, a button down along -z).
    """

    qpos_adr: int
    qvel_adr: int
    cabinet_mocap: int
    closed: tuple[float, float, float]
    travel: float
    axis: tuple[float, float, float] = (-1.0, 0.0, 0.0)

    def pose(self, data: mujoco.MjData) -> Pose:
        """The body's world pose: its host's, moved along the axis by the joint."""
        quat = data.mocap_quat[self.cabinet_mocap].copy()
        local = np.array(self.closed) + float(data.qpos[self.qpos_adr]) * np.array(self.axis)
        return Pose(data.mocap_pos[self.cabinet_mocap] + rotation_matrix(quat) @ local, quat)

    def set_pose(self, data: mujoco.MjData, pose: Pose) -> None:
        """Slide the body to where ``pose`` is along its joint (its host stays; the
        rest of ``pose`` follows from the host's), and stop it."""
        quat = data.mocap_quat[self.cabinet_mocap]
        local = rotation_matrix(quat).T @ (pose.pos - data.mocap_pos[self.cabinet_mocap])
        along = float(np.dot(local - np.array(self.closed), self.axis))
        data.qpos[self.qpos_adr] = float(np.clip(along, 0.0, self.travel))
        data.qvel[self.qvel_adr] = 0.0


def _geoms(plan: ObjectPlan, boxes: list, mass: float | None) -> tuple[GeomPlan, ...]:
    """The plan's geoms rebuilt from ``boxes`` (colour and group kept); ``mass``
    shared by volume (None: a mocap or visual body)."""
    first = plan.geoms[0]
    halves = [np.subtract(hi, lo) / 2 for _, lo, hi in boxes]
    volumes = [float(np.prod(2 * h)) for h in halves]
    total = sum(volumes)
    return tuple(
        GeomPlan(f"{plan.name}{GEOM_SEPARATOR}{name}", "box", fmt(h),
                 fmt(np.add(lo, hi) / 2), None, first.rgba, first.group,
                 None if mass is None else round(mass * v / total, 12))
        for (name, lo, hi), h, v in zip(boxes, halves, volumes, strict=True))


def furniture_plan(plan: ObjectPlan, obj: SceneObject, graph: VariableSet,
                   moving: bool = True) -> ObjectPlan:
    """The plan of a cabinet (with its number of bays), a drawer (its handle where
    its level puts it), a microwave, a door or a shelf (its panels beside its
    levels; a level is a plain fixed box), from the stand-alone plan of its kind.

    Args:
        plan: The plan :func:`~factask.sim.build.parts.plan_object` made.
        obj: The scene object it is of.
        graph: The task graph (a cabinet's drawers, a drawer's seat).
        moving: A drawer's (door's) own body (False: its goal marker).
    """
    if obj.kind == "cabinet":
        bays = len(drawers_of(graph.variables, obj.variable))
        return replace(plan, geoms=_geoms(plan, cabinet_boxes(obj.size, max(bays, 1)), None))
    if obj.kind == "microwave":
        return replace(plan, geoms=_geoms(plan, microwave_boxes(obj.size), None))
    if obj.kind == "shelf":  # its panels beside its levels (each level a body of its own)
        levels = len(drawers_of(graph.variables, obj.variable))
        return replace(plan, geoms=_geoms(plan, shelf_boxes(obj.size, max(levels, 1)), None))
    if obj.kind == "door":
        boxes = door_boxes(obj.size)
    else:
        seat = drawer_seat(graph, obj.variable)
        boxes = drawer_boxes(obj.size, seat.bays, seat.level)
    if not moving:
        return replace(plan, geoms=_geoms(plan, boxes, None))
    return replace(plan, mocap=False, geoms=_geoms(plan, boxes, obj.mass))


def add_drawer(spec: mujoco.MjSpec, plan: ObjectPlan, obj: SceneObject, graph: VariableSet,
               cabinet: BodyHandles, cabinet_obj: SceneObject,
               obj_cls: mujoco.MjsDefault) -> BodyHandles:
    """Add a drawer's body inside its cabinet's, with its slide joint.

    Args:
        spec: The scene's spec.
        plan: The drawer's plan (:func:`furniture_plan`).
        obj: The drawer.
        graph: The task graph.
        cabinet: Its cabinet's body.
        cabinet_obj: Its cabinet.
        obj_cls: The spec's default class of object geoms.

    Returns:
        Handles of the body, its geoms and its slide joint.
    """
    seat = drawer_seat(graph, obj.variable)
    closed = drawer_closed_offset(cabinet_obj.size, seat.bays, seat.level)
    body = cabinet.body.add_body(name=plan.name, pos=list(fmt(closed)))
    joint = body.add_joint(name=f"{plan.name}{GEOM_SEPARATOR}slide",
                           type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[-1.0, 0.0, 0.0],
                           range=[0.0, drawer_travel(obj.size)],
                           limited=mujoco.mjtLimited.mjLIMITED_TRUE, damping=SLIDE_DAMPING,
                           frictionloss=SLIDE_FRICTION, armature=SLIDE_ARMATURE)
    return BodyHandles(body, add_plan_geoms(body, plan, obj_cls), joint)


def slide_handle(model: mujoco.MjModel, obj: SceneObject, graph: VariableSet,
                 drawer: BodyHandles, cabinet_obj: SceneObject,
                 cabinet: BodyHandles) -> SlideHandle:
    """The :class:`SlideHandle` of a compiled drawer."""
    assert drawer.joint is not None
    seat = drawer_seat(graph, obj.variable)
    return SlideHandle(int(model.jnt_qposadr[drawer.joint.id]),
                       int(model.jnt_dofadr[drawer.joint.id]),
                       int(model.body_mocapid[cabinet.body.id]),
                       drawer_closed_offset(cabinet_obj.size, seat.bays, seat.level),
                       drawer_travel(obj.size))
