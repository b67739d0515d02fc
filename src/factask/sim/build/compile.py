"""Compile a task graph into a MuJoCo scene: graph -> ``mujoco.MjSpec`` -> ``MjModel``.

The scene holds the table, one body per object instance (free objects have a
free joint; fixed ones are mocap bodies so they can be moved at every reset
without recompiling), one translucent goal marker per moved object instance per
factor (a collision-free mocap look-alike in geom group
:data:`~factask.sim.build.mjcf.MARKER_GROUP`) and, optionally, the robot.

The scene is built in code through ``mujoco.MjSpec`` (:mod:`factask.sim.build.mjspec`)
and compiled in place; ids come from the spec's element handles. The same graph
always gives the same model and byte-identical XML (``CompiledScene.xml``): every
element is named, numbers are rounded, and nothing global is cached.
:func:`build_mjcf` writes the same scene (without a robot) as a
``dm_control.mjcf`` tree, for export.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import mujoco
import numpy as np

from factask.geometry import Pose, without_roll
from factask.graph.taskgraph import TaskGraph
from factask.relations.drawer import host_of
from factask.scene.objects import SceneObject, objects_by_name, points_in_rect, scene_objects
from factask.scene.switch import switch_host
from factask.sim.build.cabinet import (
    FURNITURE_KINDS,
    SlideHandle,
    add_drawer,
    furniture_plan,
    slide_handle,
)
from factask.sim.build.microwave import HingeHandle, add_door, hinge_handle
from factask.sim.build.mjspec import BodyHandles, add_object, add_table, default_classes, new_spec
from factask.sim.build.parts import (
    GEOM_SEPARATOR,
    MARKER_GROUP,
    AssetError,
    HollowShape,
    ObjectPlan,
    plan_object,
)
from factask.sim.build.rope_links import add_rope_links, add_rope_links_mjcf
from factask.sim.build.stage import TABLE_HEIGHT
from factask.sim.build.switch import add_switch, switch_handle
from factask.sim.robots.attach import attach_robot
from factask.sim.robots.registry import ROBOT_NAMES
from factask.sim.robots.spatula import add_spatula, needs_spatula
from factask.vocabulary.errors import SubjectError
from factask.vocabulary.kinds import JOINTED_KINDS
from factask.vocabulary.world import WORKSPACE_X, WORKSPACE_Y

#: Physics timestep (s) of a compiled scene unless asked otherwise.
DEFAULT_TIMESTEP = 0.002
#: Largest timestep (s) that keeps the contacts of small objects stable.
MAX_TIMESTEP = 0.01
#: Earth's gravity (m/s^2), straight down.
GRAVITY = (0.0, 0.0, -9.81)
#: Ratio of frictional to normal constraint impedance: > 1 makes friction hard,
#: which keeps stacks and suction-held objects from creeping (MuJoCo docs).
IMPRATIO = 10.0
#: Opacity of goal markers.
MARKER_ALPHA = 0.3
#: Gap (m) between objects in the default (pre-reset) grid layout.
GRID_GAP = 0.02
#: Prefix of goal marker bodies: ``goal:<factor>:<slot>`` (``:`` never occurs in names).
MARKER_PREFIX = "goal"


class CompileError(SubjectError):
    """A graph cannot be compiled into a MuJoCo scene.

    Attributes:
        variable: The variable (or "" for the scene as a whole) at fault.
    """

    @property
    def variable(self) -> str:
        return self.subject


@dataclass(frozen=True)
class ObjectHandle:
    """Where one object instance lives in a compiled model.

    Attributes:
        name: Instance name (also the body's name).
        variable: The variable the instance belongs to.
        kind: Asset kind.
        size: Full extents (x, y, z), metres.
        body_id: MuJoCo body id.
        geom_ids: Ids of the object's geoms.
        qpos_adr: Address of its free joint in ``qpos`` (7 numbers), or None if fixed.
        qvel_adr: Address of its free joint in ``qvel`` (6 numbers), or None if fixed.
        mocap_id: Index into ``mocap_pos``/``mocap_quat`` if fixed, else None.
        slide: A drawer's slide joint in its cabinet, a switch's in its host or a
            door's hinge on its microwave (its pose follows from it), else None.
    """

    name: str
    variable: str
    kind: str
    size: tuple[float, float, float]
    body_id: int
    geom_ids: tuple[int, ...]
    qpos_adr: int | None
    qvel_adr: int | None
    mocap_id: int | None
    slide: SlideHandle | HingeHandle | None = None

    @property
    def fixed(self) -> bool:
        """True for a mocap (fixed) object."""
        return self.mocap_id is not None


@dataclass
class CompiledScene:
    """A compiled scene and the maps from graph names to MuJoCo ids.

    Attributes:
        graph: The graph it was compiled from.
        spec: The ``mujoco.MjSpec`` the model was compiled from.
        model: The MuJoCo model.
        objects: Instance name -> :class:`ObjectHandle`, in graph order.
        markers: (factor name, slot index) -> mocap id of the goal marker of the
            factor's slot-th moved object instance.
        marker_objects: (factor name, slot index) -> the instance it stands for.
        robot: Robot kind, or None.
        geom_object: Geom id -> index into ``list(objects)``, -1 for other geoms.
    """

    graph: TaskGraph
    spec: mujoco.MjSpec = field(repr=False)
    model: mujoco.MjModel
    objects: dict[str, ObjectHandle]
    markers: dict[tuple[str, int], int]
    marker_objects: dict[tuple[str, int], str]
    robot: str | None
    geom_object: np.ndarray = field(repr=False)

    @property
    def xml(self) -> str:
        """The scene's MJCF text (written on demand; the same graph and robot give the
        same text)."""
        return str(self.spec.to_xml())

    @property
    def object_names(self) -> list[str]:
        """Instance names in the order :attr:`geom_object` indexes them."""
        return list(self.objects)

    def make_data(self) -> mujoco.MjData:
        """A fresh ``MjData`` with positions computed (``mj_forward``)."""
        data = mujoco.MjData(self.model)
        mujoco.mj_forward(self.model, data)
        return data


# ----------------------------------------------------------------- helpers
def _check_args(graph: TaskGraph, robot: str | None, timestep: float,
                validate: bool = True) -> None:
    if validate:
        graph.ensure_valid()
    not_a_task = graph.task_problems()
    if not_a_task:
        raise CompileError("", not_a_task[0].message, not_a_task[0].fix)
    if robot is not None and robot not in ROBOT_NAMES:
        raise CompileError("", f"unknown robot {robot!r}",
                           f"use one of {', '.join(ROBOT_NAMES)} or None")
    if not (isinstance(timestep, (int, float)) and math.isfinite(timestep)
            and 0 < timestep <= MAX_TIMESTEP):
        raise CompileError("", f"timestep {timestep!r} must be in (0, {MAX_TIMESTEP}] s",
                           "use 0.002")


def _fixtures_under_targets(graph: TaskGraph, goal: Any) -> set[str]:
    """The fixtures (at given poses) inside whose footprint a world-frame ``at_pose``
    goal puts a target: "each block into the fixture of its colour" as one goal with
    targets at the fixtures' poses names them without an anchor field."""
    if getattr(goal, "type", None) != "at_pose" or goal.frame is not None:
        return set()
    out = set()
    for v in graph.variables:
        start = v.initial
        if v.kind != "fixture" or getattr(start, "type", None) != "pose":
            continue
        targets = np.array([[pose.x, pose.y] for pose in goal.poses])
        if points_in_rect(targets, np.array([start.x, start.y]), math.radians(start.yaw_deg),
                          np.array(v.extents[:2]) / 2).any():
            out.add(v.name)
    return out


def fixture_hollows(graph: TaskGraph) -> dict[str, HollowShape]:
    """Hollow shape of each fixture variable: "ell" if any factor puts an ell into
    it (or aligns one with it) or nothing names it, else "square". A factor puts
    something into a fixture when it names it as an anchor, or when it is an
    ``at_pose`` goal in world coordinates with a target inside the footprint of a
    fixture at a given pose.

    Args:
        graph: The task graph.

    Returns:
        Fixture variable name -> hollow shape.
    """
    kinds = {v.name: v.kind for v in graph.variables}
    out: dict[str, HollowShape] = {}
    for f in graph.factors:
        for anchor in [*f.anchors(), *sorted(_fixtures_under_targets(graph, f.goal))]:
            if kinds.get(anchor) != "fixture":
                continue
            has_ell = any(kinds.get(o) == "ell" for o in f.goal.objects)
            if has_ell or out.get(anchor) == "ell":
                out[anchor] = "ell"
            else:
                out[anchor] = "square"
    for name, kind in kinds.items():
        if kind == "fixture":
            out.setdefault(name, "ell")
    return out


def grid_positions(objects: list[SceneObject]) -> list[tuple[float, float, float]]:
    """Default resting positions before any reset: a row-major grid over the
    workspace (continuing beyond it if needed), one cell per object.

    Args:
        objects: The scene's objects.

    Returns:
        One (x, y, z) per object, z = half its height (resting on the table).
    """
    if not objects:
        return []
    cell = max(max(o.size[0], o.size[1]) for o in objects) + GRID_GAP
    per_row = max(1, int((WORKSPACE_Y[1] - WORKSPACE_Y[0]) // cell))
    out = []
    for i, o in enumerate(objects):
        row, col = divmod(i, per_row)
        x = WORKSPACE_X[0] + cell / 2 + row * cell
        y = WORKSPACE_Y[0] + cell / 2 + col * cell
        out.append((round(x, 9), round(y, 9), o.size[2] / 2))
    return out


def _marker_slots(graph: TaskGraph) -> list[tuple[str, int, str]]:
    """(factor, slot index, moved instance) for every moved instance of every factor."""
    instances = {v.name: v.instances for v in graph.variables}
    slots = []
    for f in graph.factors:
        k = 0
        for var in f.goal.objects:
            for inst in instances.get(var, []):
                slots.append((f.name, k, inst))
                k += 1
    return slots


def drawer_cabinet(graph: TaskGraph, drawer: SceneObject) -> SceneObject:
    """The scene object of the cabinet a drawer sits in (the microwave a door hangs on)."""
    return objects_by_name(graph)[host_of(graph, drawer.variable)]


def switch_host_object(graph: TaskGraph, switch: SceneObject) -> SceneObject:
    """The scene object of the fixture a switch is mounted on."""
    return objects_by_name(graph)[switch_host(graph, switch.variable)]


_NAME_IN_ERROR = re.compile(r"name '([^']+)'")


def _variable_of_error(message: str, objects: list[SceneObject]) -> str:
    """The variable a MuJoCo compiler message is about, or "" if it names none."""
    owner = {o.name: o.variable for o in objects}
    for name in _NAME_IN_ERROR.findall(message):
        inst = name.split(GEOM_SEPARATOR)[0]
        if inst in owner:
            return owner[inst]
    return ""


# ------------------------------------------------------------------ compile
def _scene_plans(graph: TaskGraph) -> tuple[list[SceneObject], list[ObjectPlan], list[ObjectPlan]]:
    """The scene objects and the plans of their bodies and of the goal markers.

    Raises:
        CompileError: an object cannot be built (names the variable).
    """
    objects = scene_objects(graph)
    hollows = fixture_hollows(graph)
    positions = grid_positions(objects)
    plans = []
    for obj, pos in zip(objects, positions, strict=True):
        try:
            # A switch's button is fixed to its host but moves on a joint: it has a mass.
            plan = plan_object(obj.name, obj.kind, obj.size, obj.color, obj.mass,
                               obj.fixed and obj.kind != "switch",
                               hollow=hollows.get(obj.variable, "ell"), pos=pos)
            if obj.kind == "switch":
                plan = replace(plan, mocap=False)
        except AssetError as exc:
            raise CompileError(obj.variable, exc.message, exc.fix) from None
        plans.append(furniture_plan(plan, obj, graph) if obj.kind in FURNITURE_KINDS else plan)
    index = {o.name: i for i, o in enumerate(objects)}
    markers = []
    for factor, slot, inst in _marker_slots(graph):
        obj = objects[index[inst]]
        pos = positions[index[inst]]
        # Hidden under the table top until the environment moves it to the target.
        marker = plan_object(
            f"{MARKER_PREFIX}:{factor}:{slot}", obj.kind, obj.size, obj.color,
            hollow=hollows.get(obj.variable, "ell"), pos=(pos[0], pos[1], -TABLE_HEIGHT / 2),
            visual_only=True, alpha=MARKER_ALPHA, group=MARKER_GROUP)
        if obj.kind in FURNITURE_KINDS:
            marker = furniture_plan(marker, obj, graph, moving=False)
        markers.append(marker)
    return objects, plans, markers


def build_mjcf(graph: TaskGraph, timestep: float = DEFAULT_TIMESTEP
               ) -> tuple[Any, list[SceneObject]]:
    """The MJCF tree of a graph's scene without a robot (``dm_control.mjcf``).

    This is the export path: :func:`compile_graph` builds the same bodies through
    ``mujoco.MjSpec`` (and ``CompiledScene.xml`` gives its MJCF text, robot
    included).

    Args:
        graph: A task graph; it is validated first.
        timestep: Physics timestep in seconds.

    Returns:
        The ``dm_control.mjcf`` root and the scene objects in body order.

    Raises:
        GraphValidationError: the graph is not valid.
        CompileError: no factors, a bad timestep, or an object that cannot be built
            (names the variable).
    """
    from factask.sim.build.mjcf import build_object, build_table, new_root  # dm_control: lazily

    _check_args(graph, None, timestep)
    objects, plans, markers = _scene_plans(graph)
    root = new_root(graph.name)
    root.option.timestep = timestep
    root.option.gravity = list(GRAVITY)
    root.option.integrator = "implicitfast"
    root.option.cone = "elliptic"
    root.option.impratio = IMPRATIO
    build_table(root.worldbody)
    hollows = fixture_hollows(graph)
    for obj, plan in zip(objects, plans, strict=True):
        build_object(root.worldbody, obj.name, obj.kind, obj.size, obj.color, obj.mass,
                     obj.fixed, hollow=hollows.get(obj.variable, "ell"), pos=plan.pos)
    by_name = {o.name: o for o in objects}
    for (_, _, inst), plan in zip(_marker_slots(graph), markers, strict=True):
        obj = by_name[inst]
        build_object(root.worldbody, plan.name, obj.kind, obj.size, obj.color,
                     hollow=hollows.get(obj.variable, "ell"), pos=plan.pos, visual_only=True,
                     alpha=MARKER_ALPHA, group=MARKER_GROUP)
    add_rope_links_mjcf(root, graph)  # as build_spec links a rope's segments
    return root, objects


def build_spec(graph: TaskGraph, robot: str | None = "floating",
               timestep: float = DEFAULT_TIMESTEP,
               validate: bool = True) -> tuple[mujoco.MjSpec, list[SceneObject], list[BodyHandles],
                          list[BodyHandles]]:
    """Build (not compile) the ``mujoco.MjSpec`` of a graph's scene.

    Args:
        graph: A task graph; it is validated first.
        robot: A name of the robot registry (:mod:`factask.sim.robots.registry`) or None.
        timestep: Physics timestep in seconds.
        validate: Check the graph first (False: benchmarks of scenes beyond the graph
            model's size limits; an invalid graph may then fail anywhere).

    Returns:
        The spec, the scene objects in body order, their handles, and the goal
        markers' handles in :func:`_marker_slots` order.

    Raises:
        GraphValidationError: the graph is not valid.
        CompileError: no factors, a bad robot or timestep, or an object that cannot
            be built (names the variable).
    """
    _check_args(graph, robot, timestep, validate)
    objects, plans, marker_plans = _scene_plans(graph)
    spec = new_spec(graph.name, timestep, GRAVITY, IMPRATIO)
    add_table(spec)
    classes = default_classes(spec)
    # A drawer's (door's, switch's) body goes inside its cabinet's (microwave's,
    # host's): hosts first.
    by_name: dict[str, BodyHandles] = {}
    for obj, plan in sorted(zip(objects, plans, strict=True),
                            key=lambda p: p[0].kind in JOINTED_KINDS):
        if obj.kind == "drawer":
            cab = drawer_cabinet(graph, obj)
            by_name[obj.name] = add_drawer(spec, plan, obj, graph, by_name[cab.name], cab,
                                           classes[0])
        elif obj.kind == "switch":
            host = switch_host_object(graph, obj)
            by_name[obj.name] = add_switch(plan, by_name[host.name], host, classes[0])
        elif obj.kind == "door":
            mw = drawer_cabinet(graph, obj)
            by_name[obj.name] = add_door(spec, plan, obj, by_name[mw.name], mw, classes[0])
        else:
            by_name[obj.name] = add_object(spec, plan, classes)
    handles = [by_name[o.name] for o in objects]
    markers = [add_object(spec, plan, classes) for plan in marker_plans]
    add_rope_links(spec, graph)  # a rope's segments, linked in a chain
    if robot is not None:
        attach_robot(spec, robot)
        if needs_spatula(graph):  # Ravens' ee = Spatula: tasks that push
            add_spatula(spec)
    return spec, objects, handles, markers


def compile_graph(graph: TaskGraph, robot: str | None = "floating",
                  timestep: float = DEFAULT_TIMESTEP, *, validate: bool = True) -> CompiledScene:
    """Compile a task graph into a MuJoCo model (through ``mujoco.MjSpec``).

    Args:
        graph: A task graph with at least one factor; validated first.
        robot: A name of the robot registry (:mod:`factask.sim.robots.registry`: "floating",
            "ur10e" alias "arm", "ur5e"), or None for no robot.
        timestep: Physics timestep in seconds, in (0, 0.01].
        validate: Check the graph first (see :func:`build_spec`).

    Returns:
        The :class:`CompiledScene`.

    Raises:
        GraphValidationError: the graph is not valid (every problem listed).
        CompileError: no factors, a bad robot or timestep, an object that cannot be
            built, or MuJoCo rejected the model (the variable is named when known).
    """
    spec, objects, bodies, marker_bodies = build_spec(graph, robot, timestep, validate)
    try:
        model = spec.compile()
    except ValueError as exc:
        raise CompileError(_variable_of_error(str(exc), objects),
                           f"MuJoCo rejected the scene: {exc}") from None
    handles: dict[str, ObjectHandle] = {}
    geom_object = np.full(model.ngeom, -1, dtype=np.int64)
    # Ids from the spec's elements; the model's address arrays read once, not per object.
    body_ids = [h.body.id for h in bodies]
    geom_ids = [tuple(g.id for g in h.geoms) for h in bodies]
    joint_ids = [-1 if h.joint is None else h.joint.id for h in bodies]
    mocap_ids = model.body_mocapid[body_ids].tolist()
    jnt = np.asarray(joint_ids, dtype=np.int64)
    qpos_adrs = np.where(jnt >= 0, model.jnt_qposadr[jnt], -1).tolist()
    dof_adrs = np.where(jnt >= 0, model.jnt_dofadr[jnt], -1).tolist()
    bodies_of = {o.name: h for o, h in zip(objects, bodies, strict=True)}
    for index, obj in enumerate(objects):
        geoms = geom_ids[index]
        if obj.kind in ("drawer", "door"):  # on a joint inside its cabinet (microwave)
            geom_object[list(geoms)] = index
            cab = drawer_cabinet(graph, obj)
            joint = (slide_handle(model, obj, graph, bodies[index], cab, bodies_of[cab.name])
                     if obj.kind == "drawer"
                     else hinge_handle(model, bodies[index], cab, bodies_of[cab.name]))
            handles[obj.name] = ObjectHandle(
                name=obj.name, variable=obj.variable, kind=obj.kind, size=obj.size,
                body_id=body_ids[index], geom_ids=geoms, qpos_adr=None, qvel_adr=None,
                mocap_id=None, slide=joint)
            continue
        if obj.kind == "switch":  # a button on a slide joint inside its host
            geom_object[list(geoms)] = index
            host = switch_host_object(graph, obj)
            handles[obj.name] = ObjectHandle(
                name=obj.name, variable=obj.variable, kind=obj.kind, size=obj.size,
                body_id=body_ids[index], geom_ids=geoms, qpos_adr=None, qvel_adr=None,
                mocap_id=None, slide=switch_handle(model, obj, graph, bodies[index], host,
                                                   bodies_of[host.name]))
            continue
        geom_object[list(geoms)] = index
        mocap, qpos_adr, dof_adr = mocap_ids[index], qpos_adrs[index], dof_adrs[index]
        handles[obj.name] = ObjectHandle(
            name=obj.name, variable=obj.variable, kind=obj.kind, size=obj.size,
            body_id=body_ids[index], geom_ids=geoms,
            qpos_adr=qpos_adr if qpos_adr >= 0 else None,
            qvel_adr=dof_adr if dof_adr >= 0 else None,
            mocap_id=mocap if mocap >= 0 else None,
        )
    marker_mocaps = model.body_mocapid[[h.body.id for h in marker_bodies]].tolist()
    markers: dict[tuple[str, int], int] = {}
    marker_objects: dict[tuple[str, int], str] = {}
    for (factor, slot, inst), mocap in zip(_marker_slots(graph), marker_mocaps, strict=True):
        markers[(factor, slot)] = mocap
        marker_objects[(factor, slot)] = inst
    return CompiledScene(graph=graph, spec=spec, model=model, objects=handles, markers=markers,
                         marker_objects=marker_objects, robot=robot, geom_object=geom_object)


# -------------------------------------------------------------------- poses
def set_object_pose(model: mujoco.MjModel, data: mujoco.MjData, handle: ObjectHandle,
                    pose: Pose) -> None:
    """Put an object at ``pose`` (its bounding-box centre) and stop it.

    Free objects: writes the free joint's qpos and zeroes its qvel. Fixed objects:
    writes the mocap pose. Call ``mujoco.mj_forward`` afterwards to update derived
    quantities.

    Args:
        model: The compiled model (checked against the handle).
        data: Its data.
        handle: The object.
        pose: World pose.

    Raises:
        CompileError: the handle does not belong to ``model``.
    """
    if handle.body_id >= model.nbody:
        raise CompileError(handle.variable, f"object {handle.name!r} is not in this model",
                           "use a handle from the CompiledScene of this model")
    if handle.slide is not None:  # its cabinet's pose must be set first
        handle.slide.set_pose(data, pose)
        return
    if handle.mocap_id is not None:
        data.mocap_pos[handle.mocap_id] = pose.pos
        data.mocap_quat[handle.mocap_id] = pose.quat
        return
    assert handle.qpos_adr is not None and handle.qvel_adr is not None
    data.qpos[handle.qpos_adr:handle.qpos_adr + 3] = pose.pos
    data.qpos[handle.qpos_adr + 3:handle.qpos_adr + 7] = pose.quat
    data.qvel[handle.qvel_adr:handle.qvel_adr + 6] = 0.0



def set_object_poses(model: mujoco.MjModel, data: mujoco.MjData,
                     handles: Mapping[str, ObjectHandle], poses: Mapping[str, Pose]) -> None:
    """Put every object of ``handles`` at its pose in ``poses`` (by name), each stopped.

    A drawer's or a door's pose is set along its joint from its cabinet's or
    microwave's current pose, so every fixed and free object is set first and the
    jointed ones after (one at a time, :func:`set_object_pose`, would read a stale
    cabinet pose if the drawer came first). Call ``mujoco.mj_forward`` afterwards.

    Args:
        model: The compiled model.
        data: Its data.
        handles: The objects by name (``CompiledScene.objects``).
        poses: World pose of each of them.

    Raises:
        CompileError: a handle does not belong to ``model``.
        KeyError: an object has no pose in ``poses``.
    """
    for name, handle in sorted(handles.items(), key=lambda item: item[1].slide is not None):
        set_object_pose(model, data, handle, poses[name])

def get_object_pose(data: mujoco.MjData, handle: ObjectHandle) -> Pose:
    """Current pose of an object (from qpos or the mocap pose: no mj_forward needed).

    Args:
        data: The model's data.
        handle: The object.

    Returns:
        Its world pose (bounding-box centre and orientation; a log's orientation
        without its roll about its axis, :func:`~factask.geometry.without_roll`).
    """
    if handle.slide is not None:
        return handle.slide.pose(data)
    if handle.mocap_id is not None:
        return Pose(data.mocap_pos[handle.mocap_id].copy(),
                    data.mocap_quat[handle.mocap_id].copy())
    assert handle.qpos_adr is not None
    q = data.qpos[handle.qpos_adr:handle.qpos_adr + 7]
    if handle.kind == "log":  # symmetric about its axis: read modulo how far it rolled
        return Pose(q[:3].copy(), without_roll(q[3:7]))
    return Pose(q[:3].copy(), q[3:7].copy())


def set_marker(data: mujoco.MjData, mocap_id: int, pose: Pose) -> None:
    """Move a goal marker (see :attr:`CompiledScene.markers`) to ``pose``.

    Args:
        data: The model's data.
        mocap_id: The marker's mocap id.
        pose: World pose of the marked object's bounding-box centre.
    """
    data.mocap_pos[mocap_id] = pose.pos
    data.mocap_quat[mocap_id] = pose.quat

