"""Scenes built in code with ``mujoco.MjSpec``: the options, the table, objects, markers.

This is the compile path (:func:`factask.sim.build.compile.compile_graph`): the spec is
built element by element from the plans of :mod:`factask.sim.build.parts` and compiled
in place; the element handles it returns give the ids after compilation, so no
id is looked up by name. No XML is written or parsed on the way (about ten times
faster than building a ``dm_control.mjcf`` tree and parsing its text); the MJCF
text of a scene is still available from ``spec.to_xml()``.

:mod:`factask.sim.build.mjcf` writes the same bodies as MJCF (the exported files);
``tests/test_compile.py`` compiles a graph both ways and compares the models.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass

import mujoco
import numpy as np

from factask.sim.build.parts import (
    BALL_FRICTION,
    OBJECT_CONDIM,
    OBJECT_FRICTION,
    OBJECT_SOLIMP,
    OBJECT_SOLREF,
    ROLLING_CONDIM,
    ObjectPlan,
)
from factask.sim.build.stage import (
    CAMERA_FOVY,
    FLOOR_POS,
    FLOOR_RGBA,
    FLOOR_SIZE,
    FRONT_CAMERA,
    FRONT_CAMERA_POS,
    HEADLIGHT_AMBIENT,
    HEADLIGHT_DIFFUSE,
    HEADLIGHT_SPECULAR,
    LIGHTS,
    OFFSCREEN_SIZE,
    SHADOW_SIZE,
    TABLE_RGBA,
    TOP_CAMERA,
    TOP_CAMERA_POS,
    TOP_CAMERA_XYAXES,
    WORKSPACE_CENTER,
    look_at_xyaxes,
    table_top,
)

#: MuJoCo geom type of each part type.
GEOM_TYPES = {
    "box": mujoco.mjtGeom.mjGEOM_BOX,
    "cylinder": mujoco.mjtGeom.mjGEOM_CYLINDER,
    "sphere": mujoco.mjtGeom.mjGEOM_SPHERE,
    "capsule": mujoco.mjtGeom.mjGEOM_CAPSULE,
    "plane": mujoco.mjtGeom.mjGEOM_PLANE,
}


@dataclass(frozen=True)
class BodyHandles:
    """The spec elements of one object body (their ``.id`` is valid after compile).

    Attributes:
        body: The body.
        geoms: Its geoms, in part order.
        joint: Its free joint, or None for a mocap body.
    """

    body: mujoco.MjsBody
    geoms: tuple[mujoco.MjsGeom, ...]
    joint: mujoco.MjsJoint | None


def size3(values: Sequence[float]) -> list[float]:
    """MuJoCo's three size slots from the 1-3 parameters a geom type uses.

    Args:
        values: Size parameters.

    Returns:
        Three numbers, zero-padded.
    """
    out = [float(v) for v in values][:3]
    return out + [0.0] * (3 - len(out))


@functools.lru_cache(maxsize=16)
def xyaxes_quat(xyaxes: tuple[float, ...]) -> tuple[float, ...]:
    """Orientation (w, x, y, z) of a frame given by its x and y axes (MJCF ``xyaxes``).

    Args:
        xyaxes: Six numbers: the frame's x axis, then (roughly) its y axis.

    Returns:
        The unit quaternion (cached: cameras are the same in every scene).
    """
    x = np.asarray(xyaxes[:3], float)
    x /= np.linalg.norm(x)
    y = np.asarray(xyaxes[3:6], float)
    y -= x * float(x @ y)
    y /= np.linalg.norm(y)
    mat = np.column_stack([x, y, np.cross(x, y)])
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, mat.reshape(-1))
    return tuple(quat.tolist())


#: Default classes of object geoms and of goal markers (:func:`_add_classes`).
OBJECT_CLASS = "object"
MARKER_CLASS = "marker"


def new_spec(model: str, timestep: float, gravity: Sequence[float], impratio: float,
             shadow_size: int = SHADOW_SIZE) -> mujoco.MjSpec:
    """An empty spec with factask's physics and rendering options.

    Args:
        model: The model's name.
        timestep: Physics timestep (s).
        gravity: Gravity vector (m/s^2).
        impratio: Frictional to normal constraint impedance ratio.
        shadow_size: Shadow map size in pixels.

    Returns:
        The spec (angles in radians).
    """
    spec = mujoco.MjSpec()
    spec.modelname = model
    spec.compiler.degree = False
    opt = spec.option
    opt.timestep = timestep
    opt.gravity = list(gravity)
    opt.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    opt.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    opt.impratio = impratio
    # Resting objects sleep: MuJoCo skips their collisions and constraint rows until
    # something touches them or their pose is written (it wakes them itself). Most of
    # a scene rests while one object is carried, so this halves a step's cost.
    opt.enableflags |= int(mujoco.mjtEnableBit.mjENBL_SLEEP)
    vis = spec.visual
    vis.quality.shadowsize = shadow_size
    vis.global_.offwidth, vis.global_.offheight = OFFSCREEN_SIZE
    vis.headlight.ambient = list(HEADLIGHT_AMBIENT)
    vis.headlight.diffuse = list(HEADLIGHT_DIFFUSE)
    vis.headlight.specular = list(HEADLIGHT_SPECULAR)
    _add_classes(spec)
    return spec


def _object_contacts(geom: mujoco.MjsGeom | mujoco.MjsDefault) -> None:
    """Contact parameters of colliding object geoms (the MJCF ``object`` class)."""
    target = geom.geom if isinstance(geom, mujoco.MjsDefault) else geom
    target.friction = list(OBJECT_FRICTION)
    target.condim = OBJECT_CONDIM
    target.solref = list(OBJECT_SOLREF)
    target.solimp = [*OBJECT_SOLIMP, 0.5, 2.0]


def _add_classes(spec: mujoco.MjSpec) -> None:
    """The default classes of object geoms (contact parameters) and of goal markers
    (no collision): set once per scene, not per geom."""
    _object_contacts(spec.add_default(OBJECT_CLASS, spec.default))
    marker = spec.add_default(MARKER_CLASS, spec.default).geom
    marker.contype = marker.conaffinity = 0


def add_table(spec: mujoco.MjSpec) -> mujoco.MjsGeom:
    """Add the table (top face at z = 0), the floor, lights and cameras.

    Args:
        spec: The scene's spec.

    Returns:
        The table top geom.
    """
    world = spec.worldbody
    size, pos = table_top()
    table = world.add_geom(name="table", type=mujoco.mjtGeom.mjGEOM_BOX, size=list(size),
                           pos=list(pos), rgba=list(TABLE_RGBA))
    _object_contacts(table)
    world.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=list(FLOOR_SIZE),
                   pos=list(FLOOR_POS), rgba=list(FLOOR_RGBA))
    for name, shadow, lpos, ldir, diffuse, specular in LIGHTS:
        world.add_light(name=name, type=mujoco.mjtLightType.mjLIGHT_DIRECTIONAL,
                        castshadow=shadow, pos=list(lpos), dir=list(ldir),
                        diffuse=list(diffuse), specular=list(specular))
    world.add_camera(name=TOP_CAMERA, pos=list(TOP_CAMERA_POS),
                     quat=list(xyaxes_quat(TOP_CAMERA_XYAXES)), fovy=CAMERA_FOVY)
    world.add_camera(name=FRONT_CAMERA, pos=list(FRONT_CAMERA_POS),
                     quat=list(xyaxes_quat(look_at_xyaxes(FRONT_CAMERA_POS, WORKSPACE_CENTER))),
                     fovy=CAMERA_FOVY)
    return table


def add_object(spec: mujoco.MjSpec, plan: ObjectPlan,
               classes: tuple[mujoco.MjsDefault, mujoco.MjsDefault] | None = None) -> BodyHandles:
    """Add one object body (see :func:`factask.sim.build.parts.plan_object`) to the world.

    Args:
        spec: The scene's spec (made by :func:`new_spec`: it holds the classes).
        plan: The object's plan.
        classes: The spec's (object, marker) default classes (:func:`default_classes`),
            looked up when not given.

    Returns:
        Handles of the body, its geoms and its free joint.
    """
    obj_cls, marker_cls = classes if classes is not None else default_classes(spec)
    body = spec.worldbody.add_body(name=plan.name, pos=plan.pos, mocap=plan.mocap)
    if plan.quat is not None:
        body.quat = plan.quat
    joint = None if plan.mocap else body.add_freejoint(name=plan.joint_name)
    cls = obj_cls if plan.collides else marker_cls
    return BodyHandles(body, add_plan_geoms(body, plan, cls), joint)


def add_plan_geoms(body: mujoco.MjsBody, plan: ObjectPlan,
                   cls: mujoco.MjsDefault) -> tuple[mujoco.MjsGeom, ...]:
    """Add a plan's geoms to ``body`` (an object's own body, or a drawer's inside its
    cabinet: :mod:`factask.sim.build.cabinet`) in default class ``cls``.

    Returns:
        The geoms, in the plan's order.
    """
    geoms = []
    # Sizes are zero-padded by MuJoCo and tuples are taken as they are: no conversions.
    for g in plan.geoms:
        geom = body.add_geom(cls, name=g.name, type=GEOM_TYPES[g.type], size=g.size,
                             pos=g.pos, rgba=g.rgba, group=g.group)
        if g.quat is not None:
            geom.quat = g.quat
        if plan.collides and g.rolls:
            geom.condim = ROLLING_CONDIM
            geom.friction = list(BALL_FRICTION)
        if g.mass is not None:
            geom.mass = g.mass
        geoms.append(geom)
    return tuple(geoms)


def default_classes(spec: mujoco.MjSpec) -> tuple[mujoco.MjsDefault, mujoco.MjsDefault]:
    """The (object, marker) default classes of a spec made by :func:`new_spec`."""
    return spec.find_default(OBJECT_CLASS), spec.find_default(MARKER_CLASS)
