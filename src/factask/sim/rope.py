"""Ropes: a chain of segments (Ravens' bead chain) in the layout and in the scene.

A rope variable (kind ``rope``) stands for ``count`` segments, each a free box
of the variable's size (length along the rope, diameter, diameter). In the
scene neighbouring segments are joined where their ends meet by a ``connect``
equality between two sites (a ball joint as a constraint: Ravens links its
beads with point-to-point constraints), their contacts with each other are
excluded, and their free joints carry a little damping so a dragged rope comes
to rest. Every segment stays an object of its own: poses, suction, checks and
scoring see segments, as Ravens sees beads.

The layout (:func:`place_rope`) lays a rope out straight, in one piece, at a
random free spot and direction (or centred on an ``AtFixedPose``).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import mujoco
import numpy as np

from factask.geometry import Pose
from factask.model.graph import TaskGraph
from factask.model.variables import AtFixedPose, InRegion, StateVariable
from factask.model.world import TABLE_Z
from factask.scene.collision import WORKSPACE_CENTER, WORKSPACE_HALF, Occupancy, in_workspace
from factask.scene.objects import SceneObject, resting_pose

#: The kind whose variables are ropes.
ROPE_KIND = "rope"
#: Damping (N s/m, N m s/rad) of each segment's free joint: a rope comes to rest.
ROPE_DAMPING = 0.002
#: Armature (kg, kg m^2) of each segment's free joint: a 1 cm segment's own rotational
#: inertia (~1e-7 kg m^2) is too small for a chain of constraints held by a weld.
ROPE_ARMATURE = 1e-4
#: Solver reference of the links (time constant, damping ratio): stiff, no bounce.
LINK_SOLREF = (0.004, 1.0)


def is_rope(var: StateVariable) -> bool:
    """True when ``var`` is a rope."""
    return var.kind == ROPE_KIND


def rope_length(var: StateVariable) -> float:
    """Length (m) of the whole rope laid straight."""
    return var.count * var.extents[0]


def link_site(inst: str, end: str) -> str:
    """Name of the site at a segment's ``end`` ("head": +x, "tail": -x)."""
    return f"{inst}:{end}"


def place_rope(var: StateVariable, objs: Mapping[str, SceneObject], occ: Occupancy,
               rng: np.random.Generator, tries: int) -> dict[str, Pose] | None:
    """Start poses of every segment of rope ``var``: straight, free of ``occ``.

    Args:
        var: The rope variable.
        objs: Scene objects by instance name.
        occ: What is already placed (the segments are added when placed).
        rng: Random generator.
        tries: Centres and directions to try.

    Returns:
        Instance -> pose, or None when no try gave a free straight rope.
    """
    insts = var.instances
    seg = var.extents[0]
    half = rope_length(var) / 2
    if isinstance(var.initial, AtFixedPose):
        lo = hi = np.array([var.initial.x, var.initial.y])
    elif isinstance(var.initial, InRegion):
        lo = np.array([var.initial.x[0], var.initial.y[0]])
        hi = np.array([var.initial.x[1], var.initial.y[1]])
    else:
        lo, hi = WORKSPACE_CENTER - WORKSPACE_HALF, WORKSPACE_CENTER + WORKSPACE_HALF
    offsets = (np.arange(len(insts)) - (len(insts) - 1) / 2) * seg
    for _ in range(tries):
        centre = rng.uniform(lo, hi)
        yaw = float(rng.uniform(-math.pi, math.pi))
        d = np.array([math.cos(yaw), math.sin(yaw)])
        if not (np.all(centre - half * np.abs(d) >= WORKSPACE_CENTER - WORKSPACE_HALF)
                and np.all(centre + half * np.abs(d) <= WORKSPACE_CENTER + WORKSPACE_HALF)):
            continue
        poses = [resting_pose(objs[i], *(centre + o * d), TABLE_Z, yaw)
                 for i, o in zip(insts, offsets, strict=True)]
        if not all(in_workspace(objs[i], p) for i, p in zip(insts, poses, strict=True)):
            continue
        if not occ.free_mask(objs[insts[0]], poses).all():
            continue
        for inst, pose in zip(insts, poses, strict=True):
            occ.put(inst, objs[inst], pose)
        return dict(zip(insts, poses, strict=True))
    return None


def add_rope_links(spec: mujoco.MjSpec, graph: TaskGraph) -> int:
    """Link the segments of every rope of ``graph`` in ``spec`` (built, not compiled).

    Args:
        spec: The scene's spec, with one body per object instance.
        graph: Its task graph.

    Returns:
        The number of links added.
    """
    links = 0
    for var in graph.variables:
        if not is_rope(var):
            continue
        half = var.extents[0] / 2
        insts = var.instances
        for inst in insts:
            body = spec.body(inst)
            body.add_site(name=link_site(inst, "head"), pos=[half, 0.0, 0.0], size=[0.001, 0, 0],
                          group=4)
            body.add_site(name=link_site(inst, "tail"), pos=[-half, 0.0, 0.0],
                          size=[0.001, 0, 0], group=4)
            joint = spec.joint(f"{inst}:free")
            joint.damping = [ROPE_DAMPING] * 3
            joint.armature = ROPE_ARMATURE
        for a, b in itertools.pairwise(insts):
            spec.add_equality(type=mujoco.mjtEq.mjEQ_CONNECT, objtype=mujoco.mjtObj.mjOBJ_SITE,
                              name1=link_site(a, "head"), name2=link_site(b, "tail"),
                              solref=list(LINK_SOLREF))
            spec.add_exclude(bodyname1=a, bodyname2=b)
            links += 1
    return links


def add_rope_links_mjcf(root: Any, graph: TaskGraph) -> int:
    """:func:`add_rope_links` for the MJCF export (a ``dm_control.mjcf`` root), so
    both paths build the same model: sites, links, excluded contacts, and each
    segment's free joint as a ``joint type="free"`` with the damping and armature
    (``freejoint`` takes neither).

    Args:
        root: The MJCF root, with one body per object instance.
        graph: Its task graph.

    Returns:
        The number of links added.
    """
    links = 0
    for var in graph.variables:
        if not is_rope(var):
            continue
        half = var.extents[0] / 2
        insts = var.instances
        for inst in insts:
            body = root.find("body", inst)
            body.freejoint.remove()
            body.insert("joint", 0, name=f"{inst}:free", type="free",
                        damping=ROPE_DAMPING, armature=ROPE_ARMATURE)
            for end, x in (("head", half), ("tail", -half)):
                body.add("site", name=link_site(inst, end), pos=[x, 0.0, 0.0],
                         size=[0.001], group=4)
        for a, b in itertools.pairwise(insts):
            root.equality.add("connect", site1=link_site(a, "head"),
                              site2=link_site(b, "tail"), solref=list(LINK_SOLREF))
            root.contact.add("exclude", body1=a, body2=b)
            links += 1
    return links
