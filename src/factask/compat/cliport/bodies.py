"""Bodies a task builds from PyBullet shapes: ``createMultiBody`` and ``createConstraint``.

Ravens' rope tasks (and GenSim's ``make_ropes``) build a rope as beads:
``createCollisionShape`` / ``createVisualShape`` make a small box or sphere,
``createMultiBody`` makes each bead from them, and ``createConstraint``
(point-to-point) links each bead to the one before. The stand-ins here record
all of it: a multibody becomes a :class:`~factask.compat.cliport.recorder.RecordedObject`
like any ``add_object`` (kind and size from its shape: a box is a ``block``, a
sphere a ``ball``, a cylinder or capsule a ``cylinder``; mass 0 makes it fixed),
and a constraint a :class:`RecordedConstraint`. Which bodies form a rope is
decided when the graph is built (:mod:`factask.compat.cliport.ropes`), from the
constraints alone, whatever the file or function that made them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from factask.compat.cliport.errors import Unsupported
from factask.compat.cliport.recorder import RecordedObject, Session, color_name
from factask.compat.cliport.transforms import split_pose

#: PyBullet's geometry constants (the stand-in module exports the same values).
GEOM_SPHERE, GEOM_BOX, GEOM_CYLINDER, GEOM_MESH, GEOM_PLANE, GEOM_CAPSULE = 2, 3, 4, 5, 6, 7
#: Joint types of constraints that link two bodies as a rope's beads are linked.
JOINT_SPHERICAL, JOINT_FIXED, JOINT_POINT2POINT = 2, 4, 5
LINK_JOINTS = (JOINT_SPHERICAL, JOINT_FIXED, JOINT_POINT2POINT)
#: ``urdf`` of a recorded multibody (it has no URDF).
MULTIBODY = "pybullet.createMultiBody"
#: PyBullet's defaults for a shape's dimensions.
DEFAULT_RADIUS = 0.5
DEFAULT_HALF_EXTENTS = (0.5, 0.5, 0.5)
DEFAULT_HEIGHT = 1.0
#: Colour of a multibody whose visual shape gives none (PyBullet draws it white).
DEFAULT_COLOR = "white"
_KINDS = {GEOM_BOX: "block", GEOM_SPHERE: "ball", GEOM_CYLINDER: "cylinder",
          GEOM_CAPSULE: "cylinder"}
_NAMES = {GEOM_BOX: "box", GEOM_SPHERE: "sphere", GEOM_CYLINDER: "cylinder",
          GEOM_CAPSULE: "capsule", GEOM_MESH: "mesh", GEOM_PLANE: "plane"}


@dataclass(frozen=True)
class ShapeSpec:
    """One ``createCollisionShape`` / ``createVisualShape`` call.

    Attributes:
        geom: PyBullet geometry type.
        size: Full extents (x, y, z), metres.
        rgba: The visual shape's colour, if it gave one.
    """

    geom: int
    size: tuple[float, float, float]
    rgba: tuple[float, ...] | None = None


@dataclass
class RecordedConstraint:
    """One ``createConstraint`` call.

    Attributes:
        parent: Parent body id.
        child: Child body id (-1: the world).
        joint: PyBullet joint type.
        parent_frame: Link point in the parent's frame (metres).
        child_frame: Link point in the child's frame (metres).
        links: The parent's and child's link indices (-1: the base).
    """

    parent: int
    child: int
    joint: int
    parent_frame: np.ndarray
    child_frame: np.ndarray
    links: tuple[int, int] = (-1, -1)


def _size(geom: int, radius: float, half_extents: Any, height: float) -> tuple[float, ...]:
    if geom == GEOM_BOX:
        half = np.asarray(half_extents, dtype=float).reshape(-1)
        if half.size == 1:
            half = np.repeat(half, 3)
        return tuple(float(2 * h) for h in half[:3])
    d = 2 * float(radius)
    if geom == GEOM_SPHERE:
        return (d, d, d)
    if geom == GEOM_CYLINDER:
        return (d, d, float(height))
    if geom == GEOM_CAPSULE:
        return (d, d, float(height) + d)
    raise Unsupported(f"pybullet shape type {_NAMES.get(geom, geom)!r}: only boxes, "
                      "spheres, cylinders and capsules can be built from shapes")


def add_shape(session: Session, geom: int, radius: float = DEFAULT_RADIUS,
              half_extents: Any = DEFAULT_HALF_EXTENTS, height: float = DEFAULT_HEIGHT,
              rgba: Any = None) -> int:
    """Record a shape; returns its id (``createCollisionShape`` / ``createVisualShape``).

    Raises:
        Unsupported: a mesh, plane or heightfield.
    """
    size = _size(int(geom), radius, half_extents, height)
    color = None if rgba is None else tuple(float(c) for c in np.asarray(rgba).reshape(-1))
    sid = len(session.shapes)
    session.shapes[sid] = ShapeSpec(int(geom), size, color)  # type: ignore[arg-type]
    return sid


def add_multibody(session: Session, mass: float, collision: int, visual: int,
                  position: Any, orientation: Any) -> int:
    """Record a single-link multibody; returns its object id (``createMultiBody``).

    Raises:
        Unsupported: neither shape was recorded here.
    """
    shape = session.shapes.get(int(collision)) or session.shapes.get(int(visual))
    if shape is None:
        raise Unsupported("pybullet.createMultiBody without a shape made by "
                          "createCollisionShape / createVisualShape")
    look = session.shapes.get(int(visual))
    rgba = look.rgba if look is not None and look.rgba is not None else shape.rgba
    color = color_name(rgba, session) if rgba is not None else DEFAULT_COLOR
    pos, quat = split_pose((position, orientation))
    oid = session.new_id()
    category = "fixed" if float(mass) <= 0 else "rigid"
    kind = _KINDS[shape.geom]
    note = "" if shape.geom != GEOM_CAPSULE else "capsule modelled as a cylinder"
    session.objects[oid] = RecordedObject(
        oid, MULTIBODY, kind, shape.size, color, category, pos, quat, note,
        Session.spot_key(pos) in session.random_spots)
    return oid


def add_constraint(session: Session, parent: int, parent_link: int, child: int,
                   child_link: int, joint: int, parent_frame: Any, child_frame: Any) -> int:
    """Record a constraint; returns its id (``createConstraint``)."""
    cid = len(session.constraints) + 1
    while cid in session.constraints:
        cid += 1
    session.constraints[cid] = RecordedConstraint(
        int(parent), int(child), int(joint),
        np.asarray(parent_frame if parent_frame is not None else (0, 0, 0), float).reshape(3),
        np.asarray(child_frame if child_frame is not None else (0, 0, 0), float).reshape(3),
        (int(parent_link), int(child_link)))
    return cid


__all__ = ["LINK_JOINTS", "MULTIBODY", "RecordedConstraint", "ShapeSpec", "add_constraint",
           "add_multibody", "add_shape"]
