"""Switches in a compiled scene: a button's body inside its host's on a slide joint.

A switchable fixture (a stove, a lamp) is a mocap body like every fixed object; its
switch is a push button, a body *inside* the host's body moved by one slide joint
down the host's -z axis (range 0 .. :func:`~factask.vocabulary.kinds.switch_travel`),
so how far it is pressed is one number of ``qpos`` and the button goes wherever its
host is put. The joint's dry friction keeps the button where the cup leaves it
(down: on; pulled back up: off), its weight compensated; MuJoCo leaves out contacts between
a body and its parent, so the button sinks into its host's top without touching it.
Its pose is read and set through :class:`~factask.sim.build.cabinet.SlideHandle`,
as a drawer's is.
"""

from __future__ import annotations

import mujoco

from factask.scene.objects import SceneObject
from factask.scene.switch import switch_host
from factask.sim.build.cabinet import SlideHandle
from factask.sim.build.mjspec import BodyHandles, add_plan_geoms
from factask.sim.build.parts import GEOM_SEPARATOR, ObjectPlan, fmt
from factask.vocabulary.kinds import switch_off_offset, switch_travel
from factask.vocabulary.variables import VariableSet

#: The button's slide direction in its host's frame: pressed down.
PRESS_AXIS = (0.0, 0.0, -1.0)
#: Dry friction (N) of a button's slide: well above its weight (~0.1 N), so it stays
#: where it is left, yet a cup pushing at guarded speed moves it at once.
BUTTON_FRICTION = 1.0
#: Damping (N s/m) of the slide: the button stops within a millimetre once let go.
BUTTON_DAMPING = 5.0
#: Armature (kg) of the slide: steadies the joint under the cup's contact and weld.
BUTTON_ARMATURE = 0.02
#: Solver reference (time constant s, damping ratio) of the joint's limits: stiffer
#: than MuJoCo's default, so a cup pushing on the button does not sink it millimetres
#: past the end of its travel.
LIMIT_SOLREF = (0.005, 1.0)


def add_switch(plan: ObjectPlan, host: BodyHandles, host_obj: SceneObject,
               obj_cls: mujoco.MjsDefault) -> BodyHandles:
    """Add a switch's body inside its host's, with its slide joint.

    Args:
        plan: The switch's plan (a free body's: it has a mass).
        host: Its host's body.
        host_obj: Its host.
        obj_cls: The spec's default class of object geoms.

    Returns:
        Handles of the body, its geoms and its slide joint.
    """
    off = switch_off_offset(host_obj.kind, host_obj.size)
    # Its weight compensated (a real button's spring and detent): a joint's dry
    # friction is a soft constraint that lets a steady load creep, and the button
    # crept down millimetres while the robot worked elsewhere.
    body = host.body.add_body(name=plan.name, pos=list(fmt(off)), gravcomp=1.0)
    joint = body.add_joint(name=f"{plan.name}{GEOM_SEPARATOR}press",
                           type=mujoco.mjtJoint.mjJNT_SLIDE, axis=list(PRESS_AXIS),
                           range=[0.0, switch_travel()],
                           limited=mujoco.mjtLimited.mjLIMITED_TRUE, damping=BUTTON_DAMPING,
                           frictionloss=BUTTON_FRICTION, armature=BUTTON_ARMATURE,
                           solref_limit=list(LIMIT_SOLREF))
    return BodyHandles(body, add_plan_geoms(body, plan, obj_cls), joint)


def switch_handle(model: mujoco.MjModel, obj: SceneObject, graph: VariableSet,
                  switch: BodyHandles, host_obj: SceneObject,
                  host: BodyHandles) -> SlideHandle:
    """The :class:`~factask.sim.build.cabinet.SlideHandle` of a compiled switch.

    Args:
        model: The compiled model.
        obj: The switch.
        graph: The task graph (checked: the switch is mounted on ``host_obj``).
        switch: The switch's body handles.
        host_obj: Its host.
        host: The host's body handles.

    Returns:
        Where its press lives in ``qpos``, and how its pose follows from its host's.
    """
    assert switch.joint is not None and switch_host(graph, obj.variable) == host_obj.variable
    return SlideHandle(int(model.jnt_qposadr[switch.joint.id]),
                       int(model.jnt_dofadr[switch.joint.id]),
                       int(model.body_mocapid[host.body.id]),
                       switch_off_offset(host_obj.kind, host_obj.size), switch_travel(),
                       PRESS_AXIS)
