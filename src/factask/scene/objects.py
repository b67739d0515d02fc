"""Scene objects and their honest footprints (pure numpy; never imports MuJoCo).

A :class:`SceneObject` is one *instance* of a state variable (a variable with
count n stands for ``v__0 .. v__{n-1}``) with everything layout, solving and
checks need: kind, full extents, fixed or free, yaw symmetry, mass and whether it
collides. The helpers below give its geometry for a given :class:`Pose`:

* the 3-D box corners (tilt included), its top and bottom heights;
* its XY footprint, an oriented box (OBB) about the pose's yaw, and a
  separating-axis overlap test between footprints;
* for receptacles (containers, bowls, fixtures): the inner area and the floor;
* for regions (zones, pallets, lines, ...): the area an object must lie in;
* for the corner marker: the inner vertex an object's corner goes into.

Conventions fixed here (shared with the MJCF asset builders):

* Containers and bowls have walls **and a floor** of thickness
  :data:`factask.vocabulary.kinds.WALL_THICKNESS`; a fixture is an open frame of walls
  with no floor (what goes in it rests on the table).
* Corner marker: its pose is the centre of its bounding box (as for every kind);
  the L's two arms, each :func:`corner_arm_width` wide, lie along the box's
  -y edge (arm along the marker's +x) and its -x edge (arm along +y). The L's
  *inner vertex* is at local ``(-sx/2 + w, -sy/2 + w)``; an object aligned to the
  corner has the marker's yaw and its own local (-x, -y) corner on that vertex.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from factask.geometry import Pose, rotation_matrix
from factask.vocabulary.kinds import (
    HANDLE_DEPTH,
    SWITCH_HOSTS,
    WALL_THICKNESS,
    KindSpec,
    kind_spec,
)
from factask.vocabulary.variables import VariableSet
from factask.vocabulary.world import TABLE_Z

#: Small slack (metres) for "inside" tests so a point on a boundary counts as inside.
GEOMETRY_EPS = 1e-9
#: Kinds of receptacle that have a floor (objects inside rest on it, not on the table).
FLOORED_RECEPTACLES = ("container", "bowl", "drawer", "microwave")
#: Kinds whose shape is a sphere: rotation changes neither footprint nor height.
SPHERE_KINDS = ("ball",)
#: Line marker whose default width the corner marker's arms share (one definition).
_LINE_KIND = "line"


@dataclass(frozen=True)
class SceneObject:
    """One object instance in the scene.

    Attributes:
        name: Instance name (``blocks__2``, or the variable's name if count is 1).
        variable: The variable it belongs to.
        index: Its index among the variable's instances.
        kind: Asset kind.
        size: Full extents (x, y, z) in metres.
        color: Palette colour name.
        fixed: Fixed to the table (never moved by the robot).
        symmetry_deg: Yaw symmetry in degrees (0: yaw never matters).
        mass: Mass in kg.
        collides: Has collision geometry (flat markers do not).
    """

    name: str
    variable: str
    index: int
    kind: str
    size: tuple[float, float, float]
    color: str
    fixed: bool
    symmetry_deg: float
    mass: float
    collides: bool

    @property
    def spec(self) -> KindSpec:
        """The kind's :class:`KindSpec`."""
        return kind_spec(self.kind)

    @property
    def half(self) -> np.ndarray:
        """Half extents (3,)."""
        return np.asarray(self.size, dtype=float) / 2.0

    @property
    def half_xy(self) -> np.ndarray:
        """Footprint half extents (2,) in the object's own frame."""
        return np.asarray(self.size[:2], dtype=float) / 2.0

    @property
    def height(self) -> float:
        """Full height (z extent)."""
        return float(self.size[2])

    @property
    def footprint_area(self) -> float:
        """Area of the footprint box, m^2."""
        return float(self.size[0] * self.size[1])

    @property
    def is_receptacle(self) -> bool:
        return self.spec.receptacle

    @property
    def is_round(self) -> bool:
        return self.spec.round


def scene_objects(graph: VariableSet) -> list[SceneObject]:
    """Every object instance of ``graph``, in variable order then instance index.

    Args:
        graph: A task graph (individually valid variables).

    Returns:
        One :class:`SceneObject` per instance; the order is deterministic.
    """
    out: list[SceneObject] = []
    for v in graph.variables:
        spec = kind_spec(v.kind)
        for i, inst in enumerate(v.instances):
            out.append(SceneObject(
                name=inst, variable=v.name, index=i, kind=v.kind,
                size=tuple(float(s) for s in v.extents),  # type: ignore[arg-type]
                color=v.color, fixed=v.is_fixed, symmetry_deg=float(v.symmetry),
                mass=float(v.object_mass), collides=spec.collides,
            ))
    return out


def objects_by_name(graph: VariableSet) -> dict[str, SceneObject]:
    """:func:`scene_objects` keyed by instance name (same order)."""
    return {o.name: o for o in scene_objects(graph)}


# --------------------------------------------------------------------- frames
def yaw_rotation_2d(yaw: float) -> np.ndarray:
    """2x2 rotation by ``yaw`` radians."""
    c, s = math.cos(yaw), math.sin(yaw)
    return np.array([[c, -s], [s, c]])


# ------------------------------------------------------------------ 3-D box
def box_corners_3d(obj: SceneObject, pose: Pose) -> np.ndarray:
    """The 8 corners (8, 3) of the object's box at ``pose`` (tilt included)."""
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    local = signs * obj.half
    return pose.pos + local @ rotation_matrix(pose.quat).T


def top_z(obj: SceneObject, pose: Pose) -> float:
    """Height of the highest point of the object at ``pose`` (its box, tilt included;
    a ball's top whatever its rotation)."""
    if obj.kind in SPHERE_KINDS:
        return float(pose.pos[2] + obj.half[2])
    return float(box_corners_3d(obj, pose)[:, 2].max())


def bottom_z(obj: SceneObject, pose: Pose) -> float:
    """Height of the lowest point of the object at ``pose`` (see :func:`top_z`)."""
    if obj.kind in SPHERE_KINDS:
        return float(pose.pos[2] - obj.half[2])
    return float(box_corners_3d(obj, pose)[:, 2].min())


def resting_pose(obj: SceneObject, x: float, y: float, surface_z: float, yaw: float) -> Pose:
    """Upright pose of ``obj`` with its bottom on a surface at height ``surface_z``."""
    return Pose.from_xyz_yaw(x, y, surface_z + obj.half[2], yaw)


# ---------------------------------------------------------------- footprints
def rect_corners(center_xy: np.ndarray, yaw: float, half_xy: np.ndarray) -> np.ndarray:
    """Corners (4, 2), counter-clockwise, of a rectangle of half extents ``half_xy``."""
    local = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], dtype=float) * np.asarray(half_xy)
    return np.asarray(center_xy, dtype=float)[:2] + local @ yaw_rotation_2d(yaw).T


def footprint_corners_batch(obj: SceneObject, xy: np.ndarray, yaw: np.ndarray,
                            margin: float = 0.0) -> np.ndarray:
    """Footprint corners (k, 4, 2) of ``obj`` at k centres ``xy`` (k, 2) and yaws (k,)."""
    local = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], dtype=float) * (obj.half_xy + margin)
    c, s = np.cos(yaw)[:, None], np.sin(yaw)[:, None]
    x = c * local[None, :, 0] - s * local[None, :, 1]
    y = s * local[None, :, 0] + c * local[None, :, 1]
    return np.stack([x, y], axis=-1) + np.asarray(xy, dtype=float)[:, None, :]


def footprint_corners(obj: SceneObject, pose: Pose, margin: float = 0.0) -> np.ndarray:
    """Corners (4, 2) of the object's footprint OBB at ``pose``, grown by ``margin``.

    The OBB is the object's own x/y box turned by the pose's yaw (round kinds are
    boxes too: conservative).
    """
    return rect_corners(pose.pos[:2], pose.yaw, obj.half_xy + margin)


#: Points sampled on the rim of a round object's footprint.
ROUND_SAMPLES = 8


def footprint_radius(obj: SceneObject) -> float:
    """Radius of the disk around the centre that covers the footprint."""
    if obj.is_round:
        return float(obj.half_xy.max())
    return float(np.linalg.norm(obj.half_xy))


def footprint_points(obj: SceneObject, pose: Pose, per_axis: int = 3,
                     covering: bool = False) -> np.ndarray:
    """XY sample points (k, 2) of the object's shape on its top and bottom faces,
    projected onto the table (so a tilted object is honest; a ball is sampled
    upright whatever its rotation). A box gives a ``per_axis`` grid per face, a
    round kind its centre and :data:`ROUND_SAMPLES` points on its rim.

    With ``covering``, a round kind's rim points span a polygon around the rim
    rather than inside it (a polygon of points on the rim cuts its bulges, up to
    1.5 mm on a 4 cm ball), so "all points inside a convex area" proves the whole
    disk is: what layout sampling needs; checks keep the rim itself."""
    grid = _unit_footprint(bool(obj.is_round), per_axis, covering)
    quat = np.array([1.0, 0.0, 0.0, 0.0]) if obj.kind in SPHERE_KINDS else pose.quat
    pts = pose.pos + (grid * obj.half) @ rotation_matrix(quat).T
    return pts[:, :2]


@functools.lru_cache(maxsize=32)
def _unit_footprint(round_: bool, per_axis: int, covering: bool) -> np.ndarray:
    """:func:`footprint_points`' sample points in half-extent units (read-only: built
    once, the layout search asks for them thousands of times)."""
    if round_:
        ang = np.linspace(0.0, 2 * math.pi, ROUND_SAMPLES, endpoint=False)
        rim = 1.0 / math.cos(math.pi / ROUND_SAMPLES) if covering else 1.0
        disk = np.concatenate([[[0.0, 0.0]], rim * np.stack([np.cos(ang), np.sin(ang)], 1)])
        grid = np.array([[x, y, c] for x, y in disk for c in (-1.0, 1.0)])
    else:
        t = np.linspace(-1.0, 1.0, per_axis)
        grid = np.array([[a, b, c] for a in t for b in t for c in (-1.0, 1.0)])
    grid.setflags(write=False)
    return grid


def _axes(corners: np.ndarray) -> np.ndarray:
    """Edge normals (..., 2, 2) of rectangles given by corners (..., 4, 2)."""
    e1 = corners[..., 1, :] - corners[..., 0, :]
    e2 = corners[..., 3, :] - corners[..., 0, :]
    axes = np.stack([e1, e2], axis=-2)
    norm = np.linalg.norm(axes, axis=-1, keepdims=True)
    return axes / np.where(norm > 0, norm, 1.0)


def obb_overlaps(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Separating-axis overlap test of every rectangle in ``a`` with every one in ``b``.

    Args:
        a: Corners (K, 4, 2) (or (4, 2)).
        b: Corners (P, 4, 2) (or (4, 2)).

    Returns:
        Bool array (K, P): True where the two rectangles overlap (touching
        edges do not count).
    """
    a = np.asarray(a, dtype=float).reshape(-1, 4, 2)
    b = np.asarray(b, dtype=float).reshape(-1, 4, 2)
    k, p = len(a), len(b)
    if k == 0 or p == 0:
        return np.zeros((k, p), dtype=bool)
    ax_a = np.broadcast_to(_axes(a)[:, None], (k, p, 2, 2))
    ax_b = np.broadcast_to(_axes(b)[None, :], (k, p, 2, 2))
    axes = np.concatenate([ax_a, ax_b], axis=2)  # (K, P, 4 axes, 2)
    pa = np.einsum("kpad,kcd->kpac", axes, a)  # (K, P, 4 axes, 4 corners)
    pb = np.einsum("kpad,pcd->kpac", axes, b)
    separated = (pa.max(-1) <= pb.min(-1) + GEOMETRY_EPS) | (
        pb.max(-1) <= pa.min(-1) + GEOMETRY_EPS
    )
    return ~separated.any(-1)


def obb_overlap(a: np.ndarray, b: np.ndarray) -> bool:
    """True if two rectangles (corners (4, 2) each) overlap."""
    return bool(obb_overlaps(a, b)[0, 0])


def points_in_rect(
    points: np.ndarray, center_xy: np.ndarray, yaw: float, half_xy: np.ndarray
) -> np.ndarray:
    """Bool (k,): which XY points lie inside the rectangle (boundary included)."""
    local = (np.asarray(points, dtype=float) - np.asarray(center_xy)[:2]) @ yaw_rotation_2d(yaw)
    return np.all(np.abs(local) <= np.asarray(half_xy) + GEOMETRY_EPS, axis=-1)


# ---------------------------------------------------------------- receptacles
def floor_thickness(obj: SceneObject | str) -> float:
    """Thickness of a receptacle's floor (0 for a floorless fixture and non-receptacles);
    ``obj`` is a scene object or a kind name."""
    kind = obj if isinstance(obj, str) else obj.kind
    return WALL_THICKNESS if kind in FLOORED_RECEPTACLES else 0.0


def inner_half_xy(obj: SceneObject) -> np.ndarray:
    """Half extents (2,) of a receptacle's inner area (inside its walls)."""
    return np.maximum(obj.half_xy - WALL_THICKNESS, 0.0)


def floor_top_z(obj: SceneObject, pose: Pose) -> float:
    """Height of a receptacle's floor top at ``pose`` (upright)."""
    return float(pose.pos[2] - obj.half[2] + floor_thickness(obj))


def rest_surface_z(obj: SceneObject, pose: Pose) -> float:
    """Height at which things put on / in ``obj`` rest.

    A flat non-colliding marker: the table. A receptacle: its floor top. Anything
    else: its top face.
    """
    if not obj.collides:
        return TABLE_Z
    if obj.is_receptacle:
        return floor_top_z(obj, pose)
    return float(pose.pos[2] + obj.half[2])


@dataclass(frozen=True)
class Area:
    """A horizontal area things are put into: a rectangle or (round kinds) a disk.

    Attributes:
        center: XY centre (2,).
        yaw: Rotation of the rectangle, radians.
        half: Half extents (2,) of the rectangle (for a disk: radius, radius).
        round: The area is the disk of radius ``half[0]``.
    """

    center: np.ndarray
    yaw: float
    half: np.ndarray
    round: bool = False

    def contains(self, points: np.ndarray) -> np.ndarray:
        """Bool (k,): which XY points are inside (boundary included)."""
        pts = np.asarray(points, dtype=float).reshape(-1, 2)
        if self.round:
            d = np.linalg.norm(pts - self.center, axis=-1)
            return d <= self.half[0] + GEOMETRY_EPS
        return points_in_rect(pts, self.center, self.yaw, self.half)

    def packing_half(self) -> np.ndarray:
        """Half extents of the rectangle used to pack objects (a disk's inscribed square)."""
        if self.round:
            return np.full(2, self.half[0] / math.sqrt(2.0))
        return self.half


def placement_area(obj: SceneObject, pose: Pose) -> Area:
    """The area objects put on / in / into ``obj`` must lie in.

    A receptacle: its inner area (a disk for round kinds). Anything else: its
    footprint (the top face of a support, the marked area of a zone).
    """
    if obj.kind in SWITCH_HOSTS:  # its top behind the control strip its switch stands on
        strip = SWITCH_HOSTS[obj.kind].strip + SWITCH_HOSTS[obj.kind].clear
        half = np.maximum(obj.half_xy - np.array([strip / 2, 0.0]), 0.0)
        centre = pose.pos[:2] + yaw_rotation_2d(pose.yaw) @ np.array([strip / 2, 0.0])
        return Area(centre, pose.yaw, half)
    if obj.kind == "drawer":  # inside its walls, behind its handle (at its -x end)
        half = np.maximum(obj.half_xy - WALL_THICKNESS - np.array([HANDLE_DEPTH / 2, 0.0]), 0.0)
        centre = pose.pos[:2] + yaw_rotation_2d(pose.yaw) @ np.array([HANDLE_DEPTH / 2, 0.0])
        return Area(centre, pose.yaw, half)
    if obj.is_receptacle:
        half = inner_half_xy(obj)
        if obj.is_round:
            return Area(pose.pos[:2].copy(), pose.yaw, np.full(2, float(half.min())), True)
        return Area(pose.pos[:2].copy(), pose.yaw, half)
    return Area(pose.pos[:2].copy(), pose.yaw, obj.half_xy)


# --------------------------------------------------------------------- corner
def corner_arm_width(size: tuple[float, float, float]) -> float:
    """Width of a corner marker's arms: a line marker's default width, at most a
    quarter of the marker's shorter side."""
    line_width = kind_spec(_LINE_KIND).default_size[1]
    return float(min(line_width, 0.25 * min(size[0], size[1])))


def corner_vertex(obj: SceneObject, pose: Pose) -> np.ndarray:
    """XY (2,) of the point an object's corner is aligned to.

    For a corner marker, the L's inner vertex (see the module docstring); for any
    other kind, the local (-x, -y) corner of its footprint.
    """
    w = corner_arm_width(obj.size) if obj.kind == "corner" else 0.0
    local = -obj.half_xy + w
    return pose.pos[:2] + yaw_rotation_2d(pose.yaw) @ local


def group_area(objects: list[SceneObject], poses: list[Pose]) -> Area:
    """The rectangle covering a group of objects (e.g. two pillars a bar bridges).

    Its axis is the group's principal axis (the line through the centres for
    two), its extent covers every footprint corner; a single object gives its
    own :func:`placement_area`.

    Args:
        objects: The group (at least one).
        poses: Their current poses, in the same order.

    Returns:
        The covering :class:`Area`.
    """
    if len(objects) == 1:
        return placement_area(objects[0], poses[0])
    centres = np.array([p.pos[:2] for p in poses])
    yaw = principal_yaw(centres)
    corners = np.concatenate([footprint_corners(o, p) for o, p in zip(objects, poses, strict=True)])
    local = (corners - centres.mean(axis=0)) @ yaw_rotation_2d(yaw)
    lo, hi = local.min(axis=0), local.max(axis=0)
    centre = centres.mean(axis=0) + yaw_rotation_2d(yaw) @ ((lo + hi) / 2.0)
    return Area(centre, yaw, (hi - lo) / 2.0)


def principal_yaw(points: np.ndarray) -> float:
    """Yaw (radians, in (-pi/2, pi/2]) of the principal axis of XY ``points`` (n >= 2).

    The sign is fixed so the axis points towards +x (or +y when it is along y):
    a row laid along it runs from its -x end to its +x end.
    """
    pts = np.asarray(points, dtype=float)
    centred = pts - pts.mean(axis=0)
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    d = vt[0]
    if d[0] < -GEOMETRY_EPS or (abs(d[0]) <= GEOMETRY_EPS and d[1] < 0):
        d = -d
    return float(math.atan2(d[1], d[0]))
