"""Ropes in the scene: neighbouring segments linked by ``connect`` equalities.

Each segment of a rope variable is a free body of its own (:mod:`factask.sim.layout.rope`
lays them out); here each gets a site at both ends, a little damping and armature on
its free joint, and neighbours are joined head to tail (a ball joint as a constraint,
as Ravens links its beads) with their mutual contacts excluded. Both build paths (the
``MjSpec`` compile and the MJCF export) add the same elements.
"""

from __future__ import annotations

import itertools
from typing import Any

import mujoco

from factask.graph.taskgraph import TaskGraph
from factask.sim.layout.rope import is_rope

#: Damping (N s/m, N m s/rad) of each segment's free joint: a rope comes to rest.
ROPE_DAMPING = 0.002
#: Armature (kg, kg m^2) of each segment's free joint: a 1 cm segment's own rotational
#: inertia (~1e-7 kg m^2) is too small for a chain of constraints held by a weld.
ROPE_ARMATURE = 1e-4
#: Solver reference of the links (time constant, damping ratio): stiff, no bounce.
LINK_SOLREF = (0.004, 1.0)



def link_site(inst: str, end: str) -> str:
    """Name of the site at a segment's ``end`` ("head": +x, "tail": -x)."""
    return f"{inst}:{end}"


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
