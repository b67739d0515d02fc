"""Asset kinds and the single size convention shared by every part of factask.

Size convention (one for every kind): ``size = (sx, sy, sz)`` are the **full
extents in metres of the object's axis-aligned bounding box in its own frame**
(x, y horizontal, z up, object resting upright). A cylinder of diameter 4 cm and
height 6 cm is ``(0.04, 0.04, 0.06)``; the same cylinder lying on its side (a
``log``, its axis along x) is ``(0.06, 0.04, 0.04)``; a ball of diameter 4 cm is
``(0.04, 0.04, 0.04)``; a bowl is ``(outer diameter, outer diameter, height)``;
a flat marker such as a zone is ``(length, width, thickness)``. An object's
position is the centre of that box. No kind uses radii or half extents in a graph.

Each kind's facts (default size, whether it moves, whether it collides, what
can be done with it) live in :data:`ASSET_KINDS` and nowhere else.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType
from typing import Literal, get_args

from factask.vocabulary.errors import FactaskError

AssetKind = Literal[
    "block",
    "box",
    "cylinder",
    "ball",
    "log",
    "bowl",
    "container",
    "zone",
    "pallet",
    "stand",
    "corner",
    "line",
    "ell",
    "fixture",
    "kit",
    "holed_box",
    "pile",
    "rope",
    "cabinet",
    "drawer",
    "stove",
    "lamp",
    "switch",
    "microwave",
    "door",
    "shelf",
    "shelf_level",
]

KIND_NAMES: tuple[str, ...] = get_args(AssetKind)


@dataclass(frozen=True)
class KindSpec:
    """What factask knows about one asset kind.

    Attributes:
        name: The kind's name as used in graphs.
        description: One line for docs and LLM prompts.
        default_size: Full extents (x, y, z) in metres.
        movable: Free (pickable) by default; otherwise fixed to the table.
        collides: Has collision geometry (markers such as zones do not).
        round: Footprint is round: yaw never matters.
        asymmetric: Footprint has no rotational symmetry below 360 degrees.
        support: Other objects can rest on its top face.
        receptacle: Objects can be put *inside* it (``inside`` relation).
        region: Marks an area of the table (``in_zone`` relation).
        density: kg/m^3 used when a variable gives no mass (solid bounding box).
    """

    name: str
    description: str
    default_size: tuple[float, float, float]
    movable: bool
    collides: bool = True
    round: bool = False
    asymmetric: bool = False
    support: bool = False
    receptacle: bool = False
    region: bool = False
    density: float = 500.0


_SPECS = [
    KindSpec("block", "solid cube-like block (Ravens block: 4 cm cube)",
             (0.04, 0.04, 0.04), movable=True, support=True),
    KindSpec("box", "solid cuboid of any size", (0.06, 0.06, 0.06), movable=True, support=True,
             density=250.0),
    KindSpec("cylinder", "upright solid cylinder; size = (diameter, diameter, height)",
             (0.04, 0.04, 0.06), movable=True, round=True, support=True),
    KindSpec("ball", "solid sphere; size = (diameter, diameter, diameter)",
             (0.04, 0.04, 0.04), movable=True, round=True),
    KindSpec("log", "solid cylinder lying on its side, its axis along x (it can roll "
             "across it); size = (length, diameter, diameter)",
             (0.12, 0.04, 0.04), movable=True),
    KindSpec("bowl", "open round bowl; size = (outer diameter, outer diameter, height)",
             (0.12, 0.12, 0.05), movable=False, round=True, receptacle=True, region=True),
    KindSpec("container", "open-top box with thin walls; size = outer extents",
             (0.16, 0.16, 0.05), movable=False, receptacle=True, region=True),
    KindSpec("zone", "flat coloured marker on the table (no collision)",
             (0.12, 0.12, 0.001), movable=False, collides=False, region=True),
    KindSpec("pallet", "low flat platform that objects are stacked on",
             (0.30, 0.25, 0.0375), movable=False, support=True, region=True),
    KindSpec("stand", "thin base plate (Ravens stand: 3 plates of 5 x 5 x 0.5 cm in a row)",
             (0.15, 0.05, 0.005), movable=False, support=True, region=True),
    KindSpec("corner", "L-shaped flat marker of a corner (arms 5.5 cm, no collision)",
             (0.055, 0.055, 0.001), movable=False, collides=False, asymmetric=True),
    KindSpec("line", "flat straight line marker (no collision)", (0.30, 0.01, 0.001),
             movable=False, collides=False, region=True),
    KindSpec("ell", "L-shaped piece made of two bars (Ravens ell); size = L's bounding box",
             (0.08, 0.08, 0.04), movable=True, asymmetric=True),
    KindSpec("fixture", "open frame whose hollow matches an ell or block; walls 4 cm high",
             (0.12, 0.12, 0.04), movable=False, receptacle=True, region=True),
    KindSpec("kit", "flat kitting plate", (0.28, 0.20, 0.005), movable=False, support=True,
             region=True),
    KindSpec("holed_box", "box fixed to the table with a square hole in the middle of its +x "
             "side (a log is lined up with it: 'aligned' mode 'hole'); size = outer extents",
             (0.08, 0.08, 0.05), movable=False, asymmetric=True),
    KindSpec("pile", "pile of small blocks pushed as one (Ravens small block: 1 cm cube); "
             "size = one block, count = number of blocks, spawned in a cluster",
             (0.01, 0.01, 0.01), movable=True),
    KindSpec("rope", "rope of count segments linked in a chain (Ravens' bead chain); size = "
             "one segment: (length along the rope, diameter, diameter)",
             (0.014, 0.01, 0.01), movable=True),
    KindSpec("cabinet", "cabinet fixed to the table, its drawers stacked in it and opening "
             "towards its -x side (their handles stick out there); things can stand on "
             "its top; size = outer extents",
             (0.22, 0.28, 0.10), movable=False, asymmetric=True, support=True),
    KindSpec("drawer", "open-top drawer sliding along -x out of its cabinet (starts "
             "'in_cabinet'; its size follows from the cabinet's); its handle sticks out "
             "of its -x face inside its size", (0.20, 0.26, 0.08), movable=False,
             asymmetric=True, receptacle=True),
    KindSpec("stove", "low cooktop fixed to the table; things can stand on its top behind "
             "its control strip (the -x strip of its top, where its switch stands); size = "
             "outer extents", (0.22, 0.24, 0.04), movable=False, asymmetric=True,
             support=True),
    KindSpec("lamp", "lamp base fixed to the table with a switch on the -x strip of its "
             "top; size = outer extents", (0.12, 0.14, 0.05), movable=False,
             asymmetric=True),
    KindSpec("switch", "push button of a switchable fixture (stove, lamp), standing on the "
             "-x strip of its top (starts 'mounted_on' it; its size follows from the "
             "host's): pressed down it is on, pulled back up it is off",
             (0.03, 0.03, 0.02), movable=False),
    KindSpec("microwave", "microwave-like box fixed to the table, open at its -x side behind "
             "its hinged door (and, for top-down suction cups, at the top); things go "
             "inside it once the door is open; size = outer extents",
             (0.18, 0.22, 0.12), movable=False, asymmetric=True, receptacle=True),
    KindSpec("door", "a microwave's door, swinging outwards about a vertical hinge at its "
             "-y edge (starts 'in_cabinet' of its microwave; its size follows from the "
             "microwave's); a handle tab sticks out of its -x face at the top of its +y "
             "end", (0.045, 0.22, 0.12), movable=False, asymmetric=True),
    KindSpec("shelf", "stepped shelf fixed to the table: its levels rise from its -x side "
             "towards its back panel at +x, each level's top open to the sky (a top-down "
             "robot reaches every one), side panels a lip above each level; things go on "
             "its levels (kind shelf_level), not on the shelf; size = outer extents",
             (0.30, 0.34, 0.13), movable=False, asymmetric=True),
    KindSpec("shelf_level", "one level of a shelf: a solid step whose top things stand on "
             "(starts 'in_cabinet' of its shelf with its level, 0 the lowest, at the shelf's "
             "-x side; its size follows from the shelf's: shelf_level_size)",
             (0.145, 0.32, 0.05), movable=False, support=True),
]

#: Kind name -> :class:`KindSpec`. Read-only.
ASSET_KINDS = MappingProxyType({s.name: s for s in _SPECS})
assert tuple(ASSET_KINDS) == KIND_NAMES, "AssetKind literal and ASSET_KINDS must agree"

#: Width of an ell's bar as a fraction of the ell's x extent (Ravens: 0.03 of 0.08).
ELL_BAR_FRACTION = 0.375
#: Wall thickness of containers and fixtures, metres.
WALL_THICKNESS = 0.01
#: The side of a ``holed_box``'s square hole as a fraction of its +x face's smaller
#: extent (a "small hole": half the face's height on a box lower than it is wide).
HOLE_FRACTION = 0.5
#: A drawer's handle: how far it sticks out of the drawer's front wall (x), how wide
#: (y) and how thick (z) it is, metres. It is a flat tab the suction cup holds from
#: above; the handles of a cabinet's drawers are side by side, one per drawer, so
#: none lies under another (a top-down cup reaches each).
HANDLE_DEPTH = 0.035
HANDLE_WIDTH = 0.035
HANDLE_THICKNESS = 0.01
#: Gap (m) between a drawer and its cabinet's panels, on every side.
DRAWER_GAP = 0.004
#: How far a drawer slides out, as a fraction of its depth (its joint's range).
DRAWER_TRAVEL_FRACTION = 0.8
#: Kinds whose variables move on a joint in a host variable rather than freely: a
#: drawer slides in its cabinet, a door swings on its microwave, a switch's button
#: slides in its stove or lamp. They are fixed (never picked) yet moved by goals;
#: their bodies are built inside their hosts', after them.
JOINTED_KINDS = frozenset({"drawer", "door", "switch"})
#: Drawers one cabinet holds at most.
MAX_DRAWERS = 3
#: Levels one shelf has at most (its levels start ``in_cabinet`` of it, whose level
#: field allows as many as a cabinet's drawers).
MAX_SHELF_LEVELS = MAX_DRAWERS
#: How far (m) a shelf's back panel stands above its top level, and each side
#: panel above its own level: a lip that keeps what stands there from sliding off
#: sideways, low enough for a top-down cup and an arm's wrist to pass over it.
SHELF_RISE = 0.03
SHELF_LIP = 0.015
#: A microwave door's panel thickness (m); its handle is a drawer's (above).
DOOR_THICKNESS = 0.01
#: How far (rad) a door swings open about its hinge: its joint's range.
DOOR_RANGE = math.pi / 2
#: How far (m) a door's handle sits in from its free (+y) edge: room for the cup.
DOOR_HANDLE_INSET = 0.03


@dataclass(frozen=True)
class SwitchMount:
    """Where a switchable kind carries its switch: a push button standing in the
    middle of the -x strip of its top (the strip is kept clear of what is put on the
    host, so the button stays reachable from above).

    Attributes:
        strip: Depth (x, m) of the control strip along the host's -x side.
        clear: Depth (x, m) of the host's top kept free behind the strip, so that
            what stands on the host leaves room round the button for the cup.
        button: Full extents (x, y, z) of the button, metres.
    """

    strip: float = 0.05
    clear: float = 0.02
    button: tuple[float, float, float] = (0.03, 0.03, 0.02)


#: Switchable kind -> its switch mount. A new switchable fixture is one entry here
#: (and its :class:`KindSpec`): validation, building, the relations and the oracle
#: read this table.
SWITCH_HOSTS: dict[str, SwitchMount] = {
    "stove": SwitchMount(),
    "lamp": SwitchMount(strip=0.045),
}
#: How far a switch's button stands above its host's top when off (m); pressed all
#: the way down (on) it stands :data:`SWITCH_RISE_OFF` - travel above it.
SWITCH_RISE_OFF = 0.016
#: Fraction of :data:`SWITCH_RISE_OFF` a button travels down: its joint's range (a
#: pressed button still sticks out, so the cup can take it to pull it back up).
SWITCH_TRAVEL_FRACTION = 0.75


def switch_size(host_kind: str) -> tuple[float, float, float]:
    """The size a switch of a host of kind ``host_kind`` has (its mount's button).

    Args:
        host_kind: A switchable kind (a key of :data:`SWITCH_HOSTS`).

    Returns:
        Full extents (x, y, z), metres.

    Raises:
        UnknownKindError: ``host_kind`` has no switch (validation says so first).
    """
    if host_kind not in SWITCH_HOSTS:
        raise UnknownKindError(f"a {host_kind} has no switch; switchable kinds: "
                               f"{', '.join(SWITCH_HOSTS)}")
    return SWITCH_HOSTS[host_kind].button


def switch_travel() -> float:
    """How far (m) a switch's button moves down from off to on: its joint's range."""
    return SWITCH_TRAVEL_FRACTION * SWITCH_RISE_OFF


def switch_off_offset(host_kind: str,
                      host_size: tuple[float, float, float]) -> tuple[float, float, float]:
    """Centre of the switch of a host of ``host_kind`` and ``host_size``, off, in the
    host's frame: in the middle of the -x strip, its top :data:`SWITCH_RISE_OFF`
    above the host's top (its lower part sunk in the host, which it never touches:
    MuJoCo leaves out contacts between a body and its parent).

    Args:
        host_kind: A switchable kind (a key of :data:`SWITCH_HOSTS`).
        host_size: The host's full extents, metres.

    Returns:
        The switch's centre (x, y, z) in the host's frame, metres.
    """
    mount = SWITCH_HOSTS[host_kind]
    return (-host_size[0] / 2 + mount.strip / 2, 0.0,
            host_size[2] / 2 + SWITCH_RISE_OFF - mount.button[2] / 2)


def side_hole(size: tuple[float, float, float]) -> tuple[float, float]:
    """A ``holed_box``'s hole: its side and its centre's height above the box's bottom
    (metres). The hole is square, in the middle of the +x face.
    """
    return HOLE_FRACTION * min(size[1], size[2]), size[2] / 2


def cabinet_bay(size: tuple[float, float, float], bays: int, level: int) -> tuple[float, float]:
    """Bay ``level`` (0: the bottom one) of a cabinet of ``size`` holding ``bays``
    drawers: the height of its floor above the cabinet's centre and its inner height
    (metres). The cabinet has a top, a bottom and a shelf between bays, each
    :data:`WALL_THICKNESS` thick."""
    inner = (size[2] - (bays + 1) * WALL_THICKNESS) / bays
    return -size[2] / 2 + WALL_THICKNESS + level * (inner + WALL_THICKNESS), inner


def drawer_size(cabinet_size: tuple[float, float, float],
                bays: int) -> tuple[float, float, float]:
    """The size a drawer of a cabinet of ``cabinet_size`` with ``bays`` drawers has:
    the cabinet's depth less its back panel and a gap, plus the handle that sticks
    out of the cabinet's front; its width less two side panels and gaps; its bay's
    height less two gaps."""
    _, inner = cabinet_bay(cabinet_size, bays, 0)
    return (cabinet_size[0] - WALL_THICKNESS - DRAWER_GAP + HANDLE_DEPTH,
            cabinet_size[1] - 2 * (WALL_THICKNESS + DRAWER_GAP), inner - 2 * DRAWER_GAP)


def drawer_closed_offset(cabinet_size: tuple[float, float, float], bays: int,
                         level: int) -> tuple[float, float, float]:
    """Centre of drawer ``level``, closed, in its cabinet's frame: its front wall flush
    with the cabinet's -x face (its handle out in front of it), a gap above its bay's
    floor."""
    size = drawer_size(cabinet_size, bays)
    floor, _ = cabinet_bay(cabinet_size, bays, level)
    return (-cabinet_size[0] / 2 - HANDLE_DEPTH + size[0] / 2, 0.0,
            floor + DRAWER_GAP + size[2] / 2)


def drawer_travel(size: tuple[float, float, float]) -> float:
    """How far (m) a drawer of ``size`` slides out: its joint's range."""
    return DRAWER_TRAVEL_FRACTION * (size[0] - HANDLE_DEPTH)


def handle_top(size: tuple[float, float, float], bays: int,
               level: int) -> tuple[float, float, float]:
    """Centre of the top face of drawer ``level``'s handle in the drawer's frame: at
    its -x end, flush with its rim, the cabinet's handles side by side along y."""
    pitch = (size[1] - 2 * WALL_THICKNESS) / bays
    return (-size[0] / 2 + HANDLE_DEPTH / 2, (level - (bays - 1) / 2) * pitch, size[2] / 2)


def shelf_level_top(shelf_size: tuple[float, float, float], levels: int,
                    level: int) -> float:
    """Height (m) of level ``level``'s top above the bottom of a shelf of
    ``shelf_size`` with ``levels`` levels: the levels' tops share the shelf's height
    less :data:`SHELF_RISE` in equal steps, level 0 (the lowest) at the first."""
    return (level + 1) * (shelf_size[2] - SHELF_RISE) / levels


def shelf_level_size(shelf_size: tuple[float, float, float], levels: int,
                     level: int) -> tuple[float, float, float]:
    """The size level ``level`` of a shelf of ``shelf_size`` with ``levels`` levels
    has: an equal share of the shelf's depth less its back panel (x), its width less
    two side panels (y), and from the table up to its top (z: a solid step).

    Args:
        shelf_size: The shelf's full extents, metres.
        levels: How many levels the shelf has (1 .. :data:`MAX_SHELF_LEVELS`).
        level: The level, 0 the lowest (at the shelf's -x side).

    Returns:
        Full extents (x, y, z), metres.
    """
    return ((shelf_size[0] - WALL_THICKNESS) / levels, shelf_size[1] - 2 * WALL_THICKNESS,
            shelf_level_top(shelf_size, levels, level))


def shelf_level_offset(shelf_size: tuple[float, float, float], levels: int,
                       level: int) -> tuple[float, float, float]:
    """Centre of level ``level`` in its shelf's frame: the ``level``-th step from the
    shelf's -x face, standing on the shelf's bottom (the table).

    Args:
        shelf_size: The shelf's full extents, metres.
        levels: How many levels the shelf has.
        level: The level, 0 the lowest.

    Returns:
        The level's centre (x, y, z) in the shelf's frame, metres.
    """
    depth, _, height = shelf_level_size(shelf_size, levels, level)
    return (-shelf_size[0] / 2 + (level + 0.5) * depth, 0.0, -shelf_size[2] / 2 + height / 2)


def door_size(microwave_size: tuple[float, float, float]) -> tuple[float, float, float]:
    """The size the door of a microwave of ``microwave_size`` has: its panel and the
    handle sticking out of it (x), the microwave's front (y, z)."""
    return (DOOR_THICKNESS + HANDLE_DEPTH, microwave_size[1], microwave_size[2])


def door_closed_offset(microwave_size: tuple[float, float, float]) -> tuple[float, float, float]:
    """Centre of a microwave's door, closed, in the microwave's frame: its panel on
    the microwave's -x face, its handle out in front of it."""
    return (-microwave_size[0] / 2 - (DOOR_THICKNESS + HANDLE_DEPTH) / 2, 0.0, 0.0)


def door_hinge(microwave_size: tuple[float, float, float]) -> tuple[float, float, float]:
    """The hinge's axis point (at the door's mid-height) in the microwave's frame: the
    outer corner of the door's panel at its -y edge, so the panel swings out without
    sweeping into the microwave's side wall."""
    return (-microwave_size[0] / 2 - DOOR_THICKNESS, -microwave_size[1] / 2, 0.0)


def door_handle_top(size: tuple[float, float, float]) -> tuple[float, float, float]:
    """Centre of the top face of a door's handle in the door's frame: out of its -x
    face, flush with its top, :data:`DOOR_HANDLE_INSET` plus half a handle in from its
    free (+y) edge."""
    return (-size[0] / 2 + HANDLE_DEPTH / 2, size[1] / 2 - DOOR_HANDLE_INSET - HANDLE_WIDTH / 2,
            size[2] / 2)


class UnknownKindError(FactaskError, ValueError):
    """An asset kind that factask does not have."""


def kind_spec(kind: str) -> KindSpec:
    """The :class:`KindSpec` of ``kind``.

    Raises:
        UnknownKindError: not a known kind; the message lists the valid kinds.
    """
    try:
        return ASSET_KINDS[kind]
    except KeyError:
        raise UnknownKindError(
            f"unknown asset kind {kind!r}; valid kinds: {', '.join(KIND_NAMES)}"
        ) from None


def yaw_symmetry_deg(kind: str, size: tuple[float, float, float]) -> float:
    """Smallest yaw rotation (degrees) that maps the object's footprint onto itself.

    Returns 0 for round objects (any yaw is equivalent: yaw is never checked),
    90 for square footprints, 180 for rectangles and logs (whose axis lies in the
    plane) and 360 for asymmetric shapes.
    """
    spec = kind_spec(kind)
    if spec.round:
        return 0.0
    if spec.asymmetric:
        return 360.0
    if kind == "log":  # its axis has a direction in the plane, even when as long as thick
        return 180.0
    if math.isclose(size[0], size[1], rel_tol=1e-6, abs_tol=1e-9):
        return 90.0
    return 180.0


def default_mass(kind: str, size: tuple[float, float, float]) -> float:
    """Mass (kg) of a solid bounding box of ``size`` at the kind's density, >= 10 g."""
    spec = kind_spec(kind)
    volume = size[0] * size[1] * size[2]
    if spec.round and kind == "ball":
        volume *= math.pi / 6.0
    elif spec.round or kind == "log":  # a disk's area: across z upright, across x lying
        volume *= math.pi / 4.0
    return max(0.01, spec.density * volume)


#: Relative tolerance for "x equals y" of round footprints.
ROUND_RTOL = 1e-6


def shape_problem(kind: str, size: tuple[float, float, float]) -> tuple[str, str] | None:
    """Why an object of ``kind`` cannot have ``size``, as (message, fix), or None.

    The rules every builder relies on: round kinds have equal x and y, a ball is
    (d, d, d), receptacles have room inside their walls, an ell's bar fits its
    other arm. (Sizes are already positive and finite.)
    """
    x, y, z = size
    spec = kind_spec(kind)
    if kind == "log" and not math.isclose(y, z, rel_tol=ROUND_RTOL):
        return (f"a log's size y and z are both its diameter, got {tuple(size)}",
                "give (length, d, d)")
    if kind == "ball":
        if not (math.isclose(x, y, rel_tol=ROUND_RTOL) and math.isclose(x, z, rel_tol=ROUND_RTOL)):
            return (f"a ball's size must be its diameter three times, got {tuple(size)}",
                    "give (d, d, d)")
    elif spec.round and not math.isclose(x, y, rel_tol=ROUND_RTOL):
        return (f"a {kind} has a round footprint but size x {x} != size y {y}",
                "give the diameter as both size x and size y")
    if kind in ("bowl", "container", "fixture", "holed_box"):
        walls = 2 * WALL_THICKNESS
        if not (x > walls and y > walls and z > WALL_THICKNESS):
            return (f"a {kind} of size {tuple(size)} has no room inside its walls "
                    f"({WALL_THICKNESS} m thick)",
                    f"make size x and y larger than {walls:.3f} and z larger than "
                    f"{WALL_THICKNESS}")
    if kind == "cabinet" and not (x > 0.1 and y > 3 * HANDLE_WIDTH and z > 0.05):
        return (f"a cabinet of size {tuple(size)} has no room for a drawer",
                "make size x larger than 0.1, y larger than "
                f"{3 * HANDLE_WIDTH:.3f} and z larger than 0.05")
    if kind == "drawer" and not (x > HANDLE_DEPTH + 4 * WALL_THICKNESS
                                 and y > 2 * WALL_THICKNESS and z > 2 * WALL_THICKNESS):
        return (f"a drawer of size {tuple(size)} has no room inside its walls and handle",
                f"make size x larger than {HANDLE_DEPTH + 4 * WALL_THICKNESS:.3f}")
    if kind in SWITCH_HOSTS:
        mount = SWITCH_HOSTS[kind]
        if not (x > mount.strip + mount.clear + 0.04 and y > mount.button[1] + 0.01
                and z > mount.button[2] - SWITCH_RISE_OFF + switch_travel() + 0.005):
            return (f"a {kind} of size {tuple(size)} has no room for its switch (a "
                    f"{mount.strip} m control strip and a button of {mount.button})",
                    f"make size x larger than {mount.strip + mount.clear + 0.04:.3f}, "
                    f"y larger than {mount.button[1] + 0.01:.3f} and z larger than "
                    f"{mount.button[2] - SWITCH_RISE_OFF + switch_travel() + 0.005:.3f}")
    if kind == "microwave" and not (x > 2 * WALL_THICKNESS and y > 2 * DOOR_HANDLE_INSET
                                    + 2 * HANDLE_WIDTH and z > 2 * WALL_THICKNESS):
        return (f"a microwave of size {tuple(size)} has no room inside its walls or for its "
                "door's handle", f"make size x larger than {2 * WALL_THICKNESS:.3f}, y larger "
                f"than {2 * DOOR_HANDLE_INSET + 2 * HANDLE_WIDTH:.3f} and z larger than "
                f"{2 * WALL_THICKNESS:.3f}")
    if kind == "door" and not (x > HANDLE_DEPTH and y > DOOR_HANDLE_INSET + HANDLE_WIDTH
                               and z > HANDLE_THICKNESS):
        return (f"a door of size {tuple(size)} has no room for its panel and handle",
                f"give the size its microwave gives it (door_size): x = "
                f"{DOOR_THICKNESS + HANDLE_DEPTH:.3f}")
    if kind == "shelf" and not (x > 0.1 and y > 0.06 and z > SHELF_RISE + 0.02):
        return (f"a shelf of size {tuple(size)} has no room for a level",
                f"make size x larger than 0.1, y larger than 0.06 and z larger than "
                f"{SHELF_RISE + 0.02:.3f}")
    if kind == "holed_box":
        side, _ = side_hole(size)
        if side > min(y, z) - 2 * WALL_THICKNESS:
            return (f"a holed_box of size {tuple(size)} has no room for its hole ({side:.3f} m "
                    f"square) inside its walls ({WALL_THICKNESS} m thick)",
                    f"make size y and z at least {4 * WALL_THICKNESS:.2f}")
    if kind == "ell" and not ELL_BAR_FRACTION * x < y:
        return (f"an ell's bar width {ELL_BAR_FRACTION * x:.4f} m ({ELL_BAR_FRACTION} x size "
                f"x) must be less than size y {y}", "make size y larger than the bar width")
    return None
