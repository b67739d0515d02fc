"""Ropes in the layout: a chain of segments (Ravens' bead chain) laid out straight.

A rope variable (kind ``rope``) stands for ``count`` segments, each a free box
of the variable's size (length along the rope, diameter, diameter). In the
scene neighbouring segments are joined where their ends meet by a ``connect``
equality between two sites (a ball joint as a constraint: Ravens links its
beads with point-to-point constraints), their contacts with each other are
excluded, and their free joints carry a little damping so a dragged rope comes
to rest. Every segment stays an object of its own: poses, suction, checks and
scoring see segments, as Ravens sees beads.
The links themselves are built with the scene (:mod:`factask.sim.build.rope_links`).

The layout (:func:`place_rope`) lays a rope out straight, in one piece, at a
random free spot and direction (or centred on an ``AtFixedPose``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from factask.geometry import Pose
from factask.relations.rope import ROPE_KIND
from factask.scene.collision import WORKSPACE_CENTER, WORKSPACE_HALF, Occupancy, in_workspace
from factask.scene.objects import SceneObject, resting_pose
from factask.vocabulary.variables import AtFixedPose, InRegion, StateVariable
from factask.vocabulary.world import TABLE_Z


def is_rope(var: StateVariable) -> bool:
    """True when ``var`` is a rope."""
    return var.kind == ROPE_KIND


def rope_length(var: StateVariable) -> float:
    """Length (m) of the whole rope laid straight."""
    return var.count * var.extents[0]


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
