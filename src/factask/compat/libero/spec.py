"""The shape of one LIBERO type's factask stand-in (:class:`LiberoKind`), the roles
a LIBERO region can play, the typed errors, and the category builders the type
table (:mod:`factask.compat.libero.catalog`) is written with.

A category builder is the general rule of one family of LIBERO's objects: every
bowl is a ``bowl``, every can, bottle and jar an upright ``cylinder``, every mug a
``cylinder`` of a mug's size, every food box a ``box`` lying flat, every book a flat
``box``, every basket, tray, caddy or drainer a ``container``. The catalogue names
each registered type once with its builder and its real-ish size; the same
builders type a name LIBERO does not register (:func:`factask.compat.libero.kinds.
category_kind`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from factask.vocabulary.errors import FactaskError


class LiberoUnsupported(FactaskError):
    """A LIBERO task uses something factask does not model (an articulated fixture,
    a fixture's region in the goal, a predicate with no factask relation). The
    message names the predicate or object and says why."""


class UnknownLiberoType(LiberoUnsupported):
    """An object or fixture type with no entry in ``LIBERO_KINDS`` and no category
    rule that types it."""


class UnknownLiberoRegion(LiberoUnsupported):
    """A region of a fixture or object that no rule maps (not its top, inside, a
    drawer, a shelf level, a door's inside or a side)."""


#: What a fixture's or object's region is, for factask:
#: ``top``: its top face: ``On`` it is ``on`` the stand-in;
#: ``inside``: inside it (a basket's ``contain_region``, a caddy's compartment):
#: ``inside`` the stand-in;
#: ``door``: behind a hinged or sliding door factask does not model (a fridge's
#: shelves), refused;
#: ``side``: a side face (a storage box's left side): no factask relation, refused;
#: ``open_top``: the top of a stand-in open at the top (factask's microwave has no
#: roof, so that top-down cups can put things in): nothing stands on it, refused.
#: A cabinet's drawer regions are listed in :attr:`LiberoKind.drawers` instead, a
#: shelf's level regions in :attr:`LiberoKind.levels`.
RegionRole = Literal["top", "inside", "door", "side", "open_top"]
REGION_ROLES: tuple[RegionRole, ...] = ("top", "inside", "door", "side", "open_top")


@dataclass(frozen=True)
class LiberoKind:
    """The factask stand-in of one LIBERO type.

    Attributes:
        kind: factask asset kind; None for the table (or floor) itself (no variable).
        size: Full extents (x, y, z) in metres; None with ``kind`` None.
        color: Palette colour name.
        fixed: Fixed to the table (None: the kind's default).
        fixture: LIBERO declares it under ``:fixtures`` (it gets a fixed pose).
        note: What it is and why this stand-in.
        drawers: For a cabinet: the LIBERO regions that are its drawers, bottom
            first (each becomes a ``drawer`` variable on a slide joint).
        levels: For a shelf: its LIBERO level regions and the level of factask's
            stepped shelf each is, as ``(region name, level)`` pairs (level 0 the
            lowest, at the shelf's front); each level becomes one ``shelf_level``
            variable, whatever number of regions name it.
        regions: The type's own regions (LIBERO's asset sites) and their roles, as
            ``(region name, role)`` pairs; see :data:`RegionRole`.
        articulation: What moves on the real fixture that factask does not model
            and why (``"sliding door"``), "" when nothing or when factask models it
            (a cabinet's drawers, a microwave's door, a stove's switch):
            ``Open``, ``Close``, ``Turnon``, ``Turnoff`` of it are refused naming this.
        category: The category rule it was made by (``"bowl"``, ``"can"``, ...).
        plain: The stand-in used when a file touches none of the moving part this
            one models (a microwave whose door, ``Open`` / ``Close`` and
            ``heating_region`` the file never names: a fixed box whose top is a
            support); None: this stand-in always.
    """

    kind: str | None
    size: tuple[float, float, float] | None
    color: str = "gray"
    fixed: bool | None = None
    fixture: bool = False
    note: str = ""
    drawers: tuple[str, ...] = ()
    levels: tuple[tuple[str, int], ...] = ()
    regions: tuple[tuple[str, RegionRole], ...] = ()
    articulation: str = ""
    category: str = ""
    plain: LiberoKind | None = None

    @property
    def level_count(self) -> int:
        """How many levels a shelf's stand-in has (0: no shelf)."""
        return max((k for _, k in self.levels), default=-1) + 1

    def level_of(self, region: str) -> int | None:
        """The level of a shelf's level region ``region``, or None.

        Args:
            region: A region's own name (``bottom_region``).

        Returns:
            The level, 0 the lowest, or None when ``region`` is no level region.
        """
        return dict(self.levels).get(region)

    def role_of(self, region: str) -> RegionRole | None:
        """The role of the type's own region ``region`` (``top_side``), or None when
        the type does not list it (drawer regions are not listed: see
        :attr:`drawers`).

        Args:
            region: A region's own name, as its ``(:regions ...)`` entry names it.

        Returns:
            The role, or None.
        """
        return dict(self.regions).get(region)


Size = tuple[float, float, float]


def scene_table(note: str) -> LiberoKind:
    """A scene's table (or floor): factask's table, no variable.

    Args:
        note: What it is.

    Returns:
        The stand-in.
    """
    return LiberoKind(None, None, fixture=True, note=note, category="table")


def bowl(size: Size, color: str, note: str) -> LiberoKind:
    """A movable ``bowl`` (bowls, ramekins, a frying pan: open, round, things go in).

    Args:
        size: (diameter, diameter, height), metres.
        color: Palette colour.
        note: What it is.

    Returns:
        The stand-in.
    """
    return LiberoKind("bowl", size, color, fixed=False, note=note, category="bowl",
                      regions=(("contain_region", "inside"),))


def can(d: float, h: float, color: str, note: str, category: str = "can") -> LiberoKind:
    """An upright ``cylinder``: cans, bottles, jars, cartons, mugs, a moka pot.

    Args:
        d: Diameter, metres.
        h: Height, metres.
        color: Palette colour.
        note: What it is.
        category: The category's name (``can``, ``bottle``, ``mug``, ...).

    Returns:
        The stand-in.
    """
    return LiberoKind("cylinder", (d, d, h), color, note=note, category=category)


def box(size: Size, color: str, note: str, category: str = "box") -> LiberoKind:
    """A movable ``box`` lying flat: food boxes and packs, books.

    Args:
        size: Full extents, metres (its largest face down).
        color: Palette colour.
        note: What it is.
        category: The category's name (``box``, ``book``).

    Returns:
        The stand-in.
    """
    return LiberoKind("box", size, color, note=note, category=category,
                      regions=(("top_side", "top"),))


def container(size: Size, color: str, note: str, inside: tuple[str, ...] = ("contain_region",),
              fixed: bool = True, fixture: bool = False) -> LiberoKind:
    """An open ``container``: baskets, trays, a desk caddy, a bowl drainer. Every
    region in ``inside`` is its inside (a caddy's compartments are one inside).

    Args:
        size: Outer extents, metres.
        color: Palette colour.
        note: What it is.
        inside: Its regions that are its inside.
        fixed: Fixed to the table unless a goal moves it.
        fixture: LIBERO uses it as a fixture.

    Returns:
        The stand-in.
    """
    return LiberoKind("container", size, color, fixed=fixed, fixture=fixture, note=note,
                      category="container", regions=tuple((r, "inside") for r in inside))


def fixed_box(size: Size, color: str, note: str, regions: tuple[tuple[str, RegionRole], ...]
              = (("top_side", "top"),), articulation: str = "") -> LiberoKind:
    """A fixture as a fixed ``box`` (a rack, a fridge, a plain microwave): things
    stand on its top; its other regions have the roles given.

    Args:
        size: Outer extents, metres.
        color: Palette colour.
        note: What it is.
        regions: Its regions' roles.
        articulation: What moves on it that factask does not model.

    Returns:
        The stand-in.
    """
    return LiberoKind("box", size, color, fixed=True, fixture=True, note=note,
                      regions=regions, articulation=articulation, category="fixture")


def cabinet(size: Size, color: str, note: str) -> LiberoKind:
    """A cabinet of three drawers on slide joints (LIBERO's ``bottom_region``,
    ``middle_region``, ``top_region``) whose top (``top_side``) things stand on.

    Args:
        size: Outer extents, metres.
        color: Palette colour.
        note: What it is.

    Returns:
        The stand-in.
    """
    return LiberoKind("cabinet", size, color, fixed=True, fixture=True, note=note,
                      drawers=("bottom_region", "middle_region", "top_region"),
                      regions=(("top_side", "top"),), category="cabinet")


def shelf(size: Size, color: str, note: str, levels: tuple[tuple[str, int], ...]
          ) -> LiberoKind:
    """A shelf of stacked boards as factask's stepped ``shelf``: its level regions
    (``levels``: region name → level, 0 the lowest) are the steps of a staircase
    rising away from the robot, each open from above (a top-down suction cup cannot
    reach a level under the board above it, so the stacked shelf becomes a stepped
    one: a documented adaptation, warned about on import).

    Args:
        size: Outer extents of the stepped stand-in (deeper than LIBERO's shelf, so
            that each step holds a bowl), metres.
        color: Palette colour.
        note: What it is.
        levels: Its level regions and their levels.

    Returns:
        The stand-in.
    """
    return LiberoKind("shelf", size, color, fixed=True, fixture=True, note=note,
                      levels=levels, category="shelf")
