"""What every asset is made of, as plain data: object parts and object plans.

Every kind is made of MuJoCo primitives (boxes, cylinders, spheres) so that its
collision shape is exact and cheap. The geometry of a kind is described as plain
data (:func:`kind_parts`: a list of :class:`Part`); :func:`plan_object` turns a
kind, size and colour into the geoms of one body (:class:`ObjectPlan`), checked
once. Two emitters read these plans: :mod:`factask.sim.build.mjspec` (``mujoco.MjSpec``,
the compile path) and :mod:`factask.sim.build.mjcf` (``dm_control.mjcf``, the MJCF
files of ``mjcf_assets/``), so both always build the same bodies.

Frames (see ``docs/assets.md``): for every kind the body origin is the centre of
the object's bounding box, so an object resting on the table has
``z = size_z / 2``. Shared conventions (floors, the corner marker's L, the
fixture's open frame) are those of :mod:`factask.scene.objects`.

Geom names are ``<instance>:<part>`` (``:`` never occurs in factask names), so a
geom maps back to its object by name as well as by id.

Why one file of ~590 lines: a kind's parts, the checks of its size and the plan
built from them change together, and both emitters must read one source so the
compiled and the exported scenes cannot drift apart.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from factask.geometry import quat_from_axis_angle, quat_from_yaw, quat_mul
from factask.scene.cabinet import cabinet_boxes, drawer_boxes
from factask.scene.microwave import door_boxes, microwave_boxes
from factask.scene.objects import corner_arm_width
from factask.scene.shelf import shelf_boxes
from factask.vocabulary.errors import SubjectError
from factask.vocabulary.kinds import (
    ELL_BAR_FRACTION,
    WALL_THICKNESS,
    UnknownKindError,
    default_mass,
    kind_spec,
    shape_problem,
    side_hole,
)
from factask.vocabulary.palette import UnknownColorError, rgba

# ----------------------------------------------------------------- constants
#: Separator between an instance name and a geom's part name.
GEOM_SEPARATOR = ":"
#: Sliding, torsional, rolling friction of object geoms: high sliding friction keeps
#: stacks and suction grasps from slipping; torsional friction stops spinning.
OBJECT_FRICTION = (1.0, 0.005, 0.0001)
#: Contact dimensionality of object geoms (4: sliding + torsional friction).
OBJECT_CONDIM = 4
#: ... of spheres (6: rolling friction too): a real ball on a table stops rolling;
#: without it the last mm/s of a release carries a ball out of its zone.
ROLLING_CONDIM = 6
#: Friction of sphere geoms: OBJECT_FRICTION with a real rolling coefficient. MuJoCo's
#: rolling coefficient is a length (resisting torque = coefficient x normal force;
#: a contact takes the larger of its two geoms' coefficients), so 0.5 mm on a 2 cm
#: radius is a rolling resistance of 0.025, a rubber or wooden ball on wood. With
#: the default 0.1 mm a ball let go on a 4 cm block's top at 20 mm/s rolls off it;
#: with 0.5 mm it stops within 1.5 mm (tests/test_ball_rolling.py).
BALL_FRICTION = (OBJECT_FRICTION[0], OBJECT_FRICTION[1], 0.0005)
#: Contact stiffness (time constant, damping ratio): stiffer than MuJoCo's default
#: (0.02) so resting objects sink < 1 mm; needs timestep <= 0.005.
OBJECT_SOLREF = (0.01, 1.0)
#: Contact impedance: near-rigid at rest, reached within 1 mm of penetration.
OBJECT_SOLIMP = (0.95, 0.99, 0.001)
#: Clearance (m) between a fixture's hollow and the piece it holds, on every side.
FIXTURE_CLEARANCE = 0.005
#: Number of wall segments of a bowl (a multiple of 4 keeps its bounding box exact).
BOWL_SEGMENTS = 16
#: Geom group of goal markers and other visual-only helpers (hidden by turning it off).
MARKER_GROUP = 2
#: Geom group of object geoms.
OBJECT_GROUP = 0
#: MJCF default classes of colliding object geoms and of visual-only geoms.
OBJECT_CLASS = "object"
VISUAL_CLASS = "visual"
#: Significant digits of numbers in MJCF text.
XML_PRECISION = 10

HollowShape = Literal["ell", "square"]
#: A quarter turn about y: a cylinder's own axis (z) onto x, as a log lies.
_ONTO_X = quat_from_axis_angle((0.0, 1.0, 0.0), math.pi / 2)
PartType = Literal["box", "cylinder", "sphere"]


class AssetError(SubjectError):
    """An object cannot be built as asked (size too small for its kind, bad colour, ...).

    Attributes:
        name: The object (instance) the problem is about.
    """

    @property
    def name(self) -> str:
        return self.subject


@dataclass(frozen=True)
class Part:
    """One primitive of an asset, in the object's body frame.

    Attributes:
        name: Part name, unique within the object (the geom is ``<instance>:<name>``).
        type: MuJoCo geom type.
        size: MuJoCo size parameters: box (half x, half y, half z); cylinder
            (radius, half height); sphere (radius,).
        pos: Centre in the body frame (m).
        yaw: Rotation about the body z axis (radians).
        axis: The body axis a cylinder's own axis lies along: "z" upright, "x" lying
            on its side (turned about y, then by ``yaw`` about z).
    """

    name: str
    type: PartType
    size: tuple[float, ...]
    pos: tuple[float, float, float]
    yaw: float = 0.0
    axis: Literal["z", "x"] = "z"

    @property
    def lying(self) -> bool:
        """A cylinder lying on its side (its axis horizontal)."""
        return self.type == "cylinder" and self.axis == "x"

    @property
    def rolls(self) -> bool:
        """Can roll on a flat surface (a sphere, a lying cylinder): its contacts get
        rolling friction (ROLLING_CONDIM, BALL_FRICTION)."""
        return self.type == "sphere" or self.lying

    @property
    def quat(self) -> tuple[float, ...] | None:
        """Orientation (w, x, y, z) in the body frame, None for the identity."""
        if self.lying:  # the cylinder's z axis turned onto x (about y), then the yaw
            return tuple(quat_mul(quat_from_yaw(self.yaw), _ONTO_X))
        return tuple(quat_from_yaw(self.yaw)) if self.yaw else None

    @property
    def half_extents(self) -> np.ndarray:
        """Half extents of the part's axis-aligned box in the body frame."""
        if self.type == "sphere":
            return np.full(3, self.size[0])
        if self.type == "cylinder" and not self.lying:
            return np.array([self.size[0], self.size[0], self.size[1]])
        # A box, or a lying cylinder's box: (half length, radius, radius) turned by yaw.
        hx, hy, hz = ((self.size[1], self.size[0], self.size[0]) if self.lying
                      else self.size)
        c, s = abs(math.cos(self.yaw)), abs(math.sin(self.yaw))
        return np.array([c * hx + s * hy, s * hx + c * hy, hz])

    @property
    def volume(self) -> float:
        """Volume (m^3), used to share an object's mass between its parts."""
        if self.type == "sphere":
            return 4.0 / 3.0 * math.pi * self.size[0] ** 3
        if self.type == "cylinder":  # upright or lying: the same volume
            return math.pi * self.size[0] ** 2 * 2 * self.size[1]
        return 8.0 * self.size[0] * self.size[1] * self.size[2]


def parts_aabb(parts: list[Part]) -> tuple[np.ndarray, np.ndarray]:
    """Axis-aligned bounding box (low, high corners) of parts in the body frame.

    Args:
        parts: At least one part.

    Returns:
        ``(low, high)``, each of shape (3,).
    """
    lows = [np.asarray(p.pos) - p.half_extents for p in parts]
    highs = [np.asarray(p.pos) + p.half_extents for p in parts]
    return np.min(lows, axis=0), np.max(highs, axis=0)


# ------------------------------------------------------------ kind geometry
def _box(name: str, lo: tuple[float, float, float], hi: tuple[float, float, float]) -> Part:
    """A box part spanning the corners ``lo``..``hi``."""
    half = tuple((h - low) / 2 for low, h in zip(lo, hi, strict=True))
    centre = tuple((h + low) / 2 for low, h in zip(lo, hi, strict=True))
    return Part(name, "box", half, centre)  # type: ignore[arg-type]


def _require(ok: bool, name: str, message: str, fix: str) -> None:
    if not ok:
        raise AssetError(name, message, fix)


def _walls_fit(name: str, kind: str, size: tuple[float, float, float], walls: float) -> None:
    _require(
        size[0] > walls and size[1] > walls and size[2] > WALL_THICKNESS,
        name,
        f"a {kind} of size {tuple(size)} has no room inside its walls "
        f"({WALL_THICKNESS} m thick)",
        f"make size x and y larger than {walls:.3f} and size z larger than {WALL_THICKNESS}",
    )


def _bowl_parts(size: tuple[float, float, float]) -> list[Part]:
    """Floor disk plus a ring of box segments whose outer faces form a regular
    polygon with apothem ``size x / 2`` (a face normal on each axis keeps the
    bounding box exact)."""
    r = size[0] / 2
    hz = size[2] / 2
    t = WALL_THICKNESS
    # Outer face length of a regular N-gon with apothem r; adjacent segments
    # share their outer vertices and overlap inside.
    half_len = r * math.tan(math.pi / BOWL_SEGMENTS)
    parts = [Part("floor", "cylinder", (r - t / 2, t / 2), (0.0, 0.0, -hz + t / 2))]
    for i in range(BOWL_SEGMENTS):
        a = 2 * math.pi * i / BOWL_SEGMENTS
        c = r - t / 2
        parts.append(
            Part(f"wall{i}", "box", (t / 2, half_len, hz), (c * math.cos(a), c * math.sin(a), 0.0),
                 yaw=a)
        )
    return parts


def _container_parts(size: tuple[float, float, float]) -> list[Part]:
    """Floor plate and four walls; outer extents equal ``size``."""
    x, y, z = (s / 2 for s in size)
    t = WALL_THICKNESS
    return [
        _box("floor", (-x + t, -y + t, -z), (x - t, y - t, -z + t)),
        _box("wall_px", (x - t, -y, -z), (x, y, z)),
        _box("wall_nx", (-x, -y, -z), (-x + t, y, z)),
        _box("wall_py", (-x + t, y - t, -z), (x - t, y, z)),
        _box("wall_ny", (-x + t, -y, -z), (x - t, -y + t, z)),
    ]


def _ell_parts(size: tuple[float, float, float], bar: float) -> list[Part]:
    """Two non-overlapping bars forming an L: one along x at the -y side, one along
    y at the -x side; the L's bounding box is centred on the origin."""
    x, y, z = (s / 2 for s in size)
    return [
        _box("bar_x", (-x, -y, -z), (x, -y + bar, z)),
        _box("bar_y", (-x, -y + bar, -z), (-x + bar, y, z)),
    ]


def fixture_hollow(size: tuple[float, float, float]) -> tuple[float, float]:
    """Inner x, y extents (m) of a fixture's hollow: the size less two walls."""
    return size[0] - 2 * WALL_THICKNESS, size[1] - 2 * WALL_THICKNESS


def fixture_fits(size: tuple[float, float, float]) -> tuple[float, float, float]:
    """Size of the ell (or block) a fixture of ``size`` holds with
    :data:`FIXTURE_CLEARANCE` on every side (same height as the fixture)."""
    hx, hy = fixture_hollow(size)
    return hx - 2 * FIXTURE_CLEARANCE, hy - 2 * FIXTURE_CLEARANCE, size[2]


def fixture_size_for(piece_size: tuple[float, float, float]) -> tuple[float, float, float]:
    """Size of the fixture that holds a piece (ell or block) of ``piece_size``:
    the inverse of :func:`fixture_fits`."""
    pad = 2 * (WALL_THICKNESS + FIXTURE_CLEARANCE)
    return piece_size[0] + pad, piece_size[1] + pad, piece_size[2]


def _fixture_parts(size: tuple[float, float, float], hollow: HollowShape) -> list[Part]:
    """A frame with full-height walls (no floor) around a hollow.

    ``square``: four walls of WALL_THICKNESS. ``ell``: the hollow is the ell of
    :func:`fixture_fits` grown by the clearance, placed like an ell (bars along
    the -y and -x sides); the rest of the box is solid.
    """
    x, y, z = (s / 2 for s in size)
    t = WALL_THICKNESS
    if hollow == "square":
        return _container_parts(size)[1:]
    ex, _, _ = fixture_fits(size)
    bar = ELL_BAR_FRACTION * ex + 2 * FIXTURE_CLEARANCE
    xb = -x + t + bar  # right edge of the hollow's y bar
    yb = -y + t + bar  # top edge of the hollow's x bar
    return [
        _box("wall_ny", (-x, -y, -z), (x, -y + t, z)),
        _box("wall_nx", (-x, -y + t, -z), (-x + t, y, z)),
        _box("wall_py", (-x + t, y - t, -z), (xb, y, z)),
        _box("wall_px", (x - t, -y + t, -z), (x, yb, z)),
        _box("inner", (xb, yb, -z), (x, y, z)),
    ]


def _holed_box_parts(size: tuple[float, float, float]) -> list[Part]:
    """A closed hollow box (no floor: it stands on the table) whose +x wall has a
    square hole in its middle (:func:`~factask.vocabulary.kinds.side_hole`): the wall is
    four pieces round the hole, and the dark inside shows through it."""
    x, y, z = (s / 2 for s in size)
    t = WALL_THICKNESS
    side, _ = side_hole(size)
    h = side / 2
    return [
        _box("top", (-x + t, -y + t, z - t), (x - t, y - t, z)),
        _box("wall_nx", (-x, -y, -z), (-x + t, y, z)),
        _box("wall_py", (-x + t, y - t, -z), (x - t, y, z)),
        _box("wall_ny", (-x + t, -y, -z), (x - t, -y + t, z)),
        _box("wall_px_left", (x - t, -y, -z), (x, -h, z)),
        _box("wall_px_right", (x - t, h, -z), (x, y, z)),
        _box("wall_px_over", (x - t, -h, h), (x, h, z)),
        _box("wall_px_under", (x - t, -h, -z), (x, h, -h)),
    ]


def _corner_parts(size: tuple[float, float, float]) -> list[Part]:
    """Two bars along the box's -y edge (arm along +x) and -x edge (arm along +y);
    the L's inner vertex is at (-sx/2 + w, -sy/2 + w) (``factask.scene.objects``)."""
    w = corner_arm_width(size)
    x, y, z = (s / 2 for s in size)
    return [
        _box("arm_x", (-x, -y, -z), (x, -y + w, z)),
        _box("arm_y", (-x, -y + w, -z), (-x + w, y, z)),
    ]


def _pallet_parts(size: tuple[float, float, float]) -> list[Part]:
    """Top plate (a third of the height) on three runners along y."""
    x, y, z = (s / 2 for s in size)
    top = size[2] / 3
    runner = min(0.03, size[0] / 6)
    parts = [_box("top", (-x, -y, z - top), (x, y, z))]
    for i, cx in enumerate((-x + runner / 2, 0.0, x - runner / 2)):
        parts.append(_box(f"runner{i}", (cx - runner / 2, -y, -z), (cx + runner / 2, y, z - top)))
    return parts


def kind_parts(
    kind: str,
    size: tuple[float, float, float],
    *,
    name: str = "object",
    hollow: HollowShape = "ell",
) -> list[Part]:
    """The primitives an asset of ``kind`` and ``size`` is made of.

    Args:
        kind: Asset kind (:data:`factask.vocabulary.kinds.ASSET_KINDS`).
        size: Full extents (x, y, z) in metres.
        name: Object name, only used in error messages.
        hollow: Shape of a fixture's hollow ("ell" or "square"); other kinds ignore it.

    Returns:
        The parts in the body frame; their bounding box spans ``size`` (centred on
        the origin.

    Raises:
        AssetError: unknown kind, non-positive size, or a size the kind cannot
            have (a cylinder whose x and y differ, walls that do not fit, ...).
    """
    try:
        kind_spec(kind)
    except UnknownKindError as exc:
        raise AssetError(name, str(exc), "use one of the listed kinds") from None
    size = tuple(float(s) for s in size)  # type: ignore[assignment]
    _require(len(size) == 3 and all(math.isfinite(s) and s > 0 for s in size), name,
             f"size must be three positive lengths in metres, got {size}",
             "give full extents (x, y, z), e.g. (0.04, 0.04, 0.04)")
    problem = shape_problem(kind, size)
    if problem is not None:
        raise AssetError(name, *problem)
    x, y, z = (s / 2 for s in size)
    if kind == "cylinder":
        # MuJoCo cylinder size is (radius, half-height): not (half-height, radius).
        return [Part("body", "cylinder", (x, z), (0.0, 0.0, 0.0))]
    if kind == "ball":
        return [Part("body", "sphere", (x,), (0.0, 0.0, 0.0))]
    if kind == "log":  # a cylinder on its side, its axis along x: (radius, half length)
        return [Part("body", "cylinder", (z, x), (0.0, 0.0, 0.0), axis="x")]
    if kind == "bowl":
        return _bowl_parts(size)
    if kind == "container":
        return _container_parts(size)
    if kind == "fixture":
        # The hollow must hold a piece of positive size after walls and clearance.
        _walls_fit(name, kind, size, 2 * (WALL_THICKNESS + FIXTURE_CLEARANCE) + 0.002)
        if hollow == "ell":
            ex, ey, _ = fixture_fits(size)
            _require(ELL_BAR_FRACTION * ex < ey, name,
                     f"the ell hollow's bar ({ELL_BAR_FRACTION} x {ex:.4f} m) is wider than "
                     f"the hollow's y extent {ey:.4f} m", "make size y closer to size x")
        return _fixture_parts(size, hollow)
    if kind == "ell":
        return _ell_parts(size, ELL_BAR_FRACTION * size[0])
    if kind == "corner":
        return _corner_parts(size)
    if kind == "holed_box":
        return _holed_box_parts(size)
    if kind == "pallet":
        return _pallet_parts(size)
    if kind in ("cabinet", "drawer"):  # alone: one bay (compile builds a cabinet's own)
        boxes = cabinet_boxes(size, 1) if kind == "cabinet" else drawer_boxes(size, 1, 0)
        return [_box(*b) for b in boxes]
    if kind in ("microwave", "door"):
        return [_box(*b) for b in (microwave_boxes(size) if kind == "microwave"
                                   else door_boxes(size))]
    if kind == "shelf":  # alone: two levels (compile builds a shelf's own)
        return [_box(*b) for b in shelf_boxes(size, 2)]
    # block, box, zone, line, stand, kit: one box of the full extents.
    return [_box("body", (-x, -y, -z), (x, y, z))]


# -------------------------------------------------------------------- plans
def fmt(values: object) -> tuple[float, ...]:
    """Round to 1e-9 so numbers never depend on float noise (and never say -0).

    Args:
        values: A number or a sequence of numbers.

    Returns:
        The rounded numbers.
    """
    if isinstance(values, (int, float, np.floating)):
        values = (values,)
    # Plain Python floats: this runs for every number of every compiled scene.
    return tuple(round(float(v), 9) + 0.0 for v in values)  # type: ignore[attr-defined]


_Shape = tuple[str, PartType, tuple[float, ...], tuple[float, ...], tuple[float, ...] | None,
               float, bool]


@functools.lru_cache(maxsize=4096)
def _shapes(kind: str, size: tuple[float, ...], hollow: HollowShape) -> tuple[_Shape, ...]:
    """(part name, type, size, pos, quat or None, share of the volume, rolls) of each
    part, rounded; cached, since scenes repeat the same kinds and sizes."""
    parts = kind_parts(kind, size, hollow=hollow)  # type: ignore[arg-type]
    volume = sum(p.volume for p in parts)
    return tuple(
        (p.name, p.type, fmt(p.size), fmt(p.pos), None if p.quat is None else fmt(p.quat),
         p.volume / volume, p.rolls)
        for p in parts
    )


@dataclass(frozen=True)
class GeomPlan:
    """One geom of an object body, ready for either emitter.

    Attributes:
        name: ``<instance>:<part>``.
        type: MuJoCo geom type name ("box", "cylinder", "sphere").
        size: MuJoCo size parameters.
        pos: Centre in the body frame.
        quat: Orientation in the body frame (w, x, y, z), or None for identity.
        rgba: Colour.
        group: Geom group.
        mass: Mass (kg) of a free body's geom, None on mocap bodies.
        rolls: A sphere or lying cylinder: its contacts get rolling friction.
    """

    name: str
    type: PartType
    size: tuple[float, ...]
    pos: tuple[float, ...]
    quat: tuple[float, ...] | None
    rgba: tuple[float, ...]
    group: int
    mass: float | None
    rolls: bool = False


@dataclass(frozen=True)
class ObjectPlan:
    """One object body: where it starts, whether it moves, its geoms.

    Attributes:
        name: Instance name (the body's name).
        pos: Initial body position.
        quat: Initial orientation (w, x, y, z), or None for identity.
        mocap: True for a mocap body (fixed objects, visual-only markers).
        collides: False for visual-only bodies (no contacts).
        geoms: The geoms in part order.
    """

    name: str
    pos: tuple[float, ...]
    quat: tuple[float, ...] | None
    mocap: bool
    collides: bool
    geoms: tuple[GeomPlan, ...]

    @property
    def joint_name(self) -> str:
        """Name of the free joint of a non-mocap body."""
        return f"{self.name}{GEOM_SEPARATOR}free"


def plan_object(
    name: str,
    kind: str,
    size: tuple[float, float, float],
    color: str = "gray",
    mass: float | None = None,
    fixed: bool | None = None,
    *,
    hollow: HollowShape = "ell",
    pos: tuple[float, float, float] | None = None,
    quat: tuple[float, float, float, float] | None = None,
    visual_only: bool = False,
    alpha: float = 1.0,
    group: int | None = None,
) -> ObjectPlan:
    """Check an object's description and lay out its body and geoms.

    Args:
        name: Instance name; the body is called ``name`` and its geoms
            ``name:<part>``.
        kind: Asset kind.
        size: Full extents (x, y, z) in metres.
        color: Palette colour name.
        mass: Mass in kg; defaults from the kind's density.
        fixed: Fixed objects become mocap bodies (they collide but never move unless
            the caller moves them); free ones get a free joint. Defaults to the
            kind's default. Kinds without collision (markers) are always fixed.
        hollow: Fixture hollow shape ("ell" or "square").
        pos: Initial body position; default: resting at the world origin.
        quat: Initial orientation (w, x, y, z).
        visual_only: A collision-free, massless look-alike (goal markers); the body
            is a mocap body.
        alpha: Opacity of the colour.
        group: Geom group; default OBJECT_GROUP, or MARKER_GROUP for visual-only.

    Returns:
        The plan.

    Raises:
        AssetError: bad kind, size, colour or mass.
    """
    mocap, collides, geoms = _body_plan(name, kind, size, color, mass, fixed, hollow,
                                        visual_only, alpha, group)
    return ObjectPlan(
        name=name, pos=fmt(pos if pos is not None else (0.0, 0.0, size[2] / 2)),
        quat=None if quat is None else fmt(quat), mocap=mocap, collides=collides,
        geoms=tuple(GeomPlan(f"{name}{GEOM_SEPARATOR}{part}", *rest) for part, *rest in geoms),
    )


def _body_plan(name: str, kind: str, size: Any, color: str, mass: float | None,
               fixed: bool | None, hollow: HollowShape, visual_only: bool, alpha: float,
               group: int | None) -> tuple[bool, bool, tuple[tuple[Any, ...], ...]]:
    """(mocap, collides, geoms as (part, type, size, pos, quat, rgba, group, mass, rolls)) of
    an object: everything of its plan but the names and the pose. Scenes repeat the
    same objects (a row of blocks), so the checked result is cached; a failure is
    never cached and names ``name``."""
    try:
        return _body_plan_cached(kind, tuple(float(v) for v in size), color, mass, fixed,
                                 hollow, visual_only, alpha, group)
    except _PlanError as exc:
        raise AssetError(name, exc.message, exc.fix) from None
    except (AssetError, TypeError, ValueError):
        kind_parts(kind, size, name=name, hollow=hollow)  # raises, naming the object
        raise


class _PlanError(Exception):
    """An object description that cannot be planned (turned into AssetError with its name)."""

    def __init__(self, message: str, fix: str) -> None:
        super().__init__(message)
        self.message, self.fix = message, fix


@functools.lru_cache(maxsize=4096)
def _body_plan_cached(kind: str, size: tuple[float, ...], color: str, mass: float | None,
                      fixed: bool | None, hollow: HollowShape, visual_only: bool, alpha: float,
                      group: int | None) -> tuple[bool, bool, tuple[tuple[Any, ...], ...]]:
    try:
        spec = kind_spec(kind)
    except UnknownKindError as exc:
        raise _PlanError(str(exc), "use one of the listed kinds") from None
    shapes = _shapes(kind, size, hollow)
    try:
        color_rgba = fmt(rgba(color, alpha))
    except UnknownColorError as exc:
        raise _PlanError(str(exc), "use a palette colour") from None
    collides = spec.collides and not visual_only
    is_fixed = (not spec.movable) if fixed is None else bool(fixed)
    mocap = is_fixed or not collides
    total_mass = default_mass(kind, size) if mass is None else float(mass)
    if not (math.isfinite(total_mass) and total_mass > 0):
        raise _PlanError(f"mass must be a positive number of kg, got {mass}",
                         "give a mass such as 0.05")
    if group is None:
        group = MARKER_GROUP if visual_only else OBJECT_GROUP
    geoms = tuple(
        # Share the object's mass by volume so its centre of mass is right.
        (part, gtype, gsize, gpos, gquat, color_rgba, group,
         None if mocap else round(total_mass * share, 12), rolls)
        for part, gtype, gsize, gpos, gquat, share, rolls in shapes
    )
    return mocap, collides, geoms


