"""LIBERO's object and fixture types → factask stand-ins: one table, :data:`LIBERO_KINDS`.

LIBERO's scenes use meshes (scanned groceries, a porcelain ramekin, a wooden
cabinet); factask has primitive kinds. Every type a shipped BDDL file names maps
here to a kind, a size (full extents in metres, the one size convention of
:mod:`factask.vocabulary.kinds`; real-ish sizes of the real things) and a palette
colour. These are **stand-ins**: the graph keeps what the task is about (what is
picked, what it goes on or in, which objects are in the way), not the look or
the exact shape of LIBERO's meshes. The choices worth knowing:

* ``plate`` → a ``kit`` (factask's flat plate): a 16 x 16 x 1 cm square support.
  factask has no round flat support; the kit is flat, can be stood on (``on``) and
  is fixed, unless a goal moves the plate (the importer then makes it movable).
* ``basket`` → a fixed ``container`` (open box, thin walls). LIBERO's basket is an
  object, but no shipped goal moves it.
* bowls (``akita_black_bowl``) and the ``glazed_rim_porcelain_ramekin`` → ``bowl``
  (the ramekin a small one), movable: LIBERO's tasks pick the bowl up.
* food boxes → ``box`` (the cookie box lying flat: a bowl starts on it); cans,
  bottles and cartons → an upright ``cylinder`` of their diameter and height.
* fixtures: ``table`` and ``floor`` are factask's table (no variable). A
  ``flat_stove`` is a fixed low box (its cook region is its top), a
  ``wooden_cabinet`` a ``cabinet`` of three drawers on slide joints (its bottom,
  middle and top regions; 7 cm deep inside, so a bowl fits and the drawer still
  shuts) whose top things can stand on, a ``wine_rack`` a fixed box (its top region
  is its top). Goals on those top regions are ``on`` the stand-in; ``Open`` and
  ``Close`` of a drawer are ``open`` / ``closed``; ``Turnon`` / ``Turnoff`` (the
  stove's knob) are refused by the importer: switches are not in factask yet.

An unknown type is a :class:`UnknownLiberoType`.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType

from factask.vocabulary.errors import FactaskError


class LiberoUnsupported(FactaskError):
    """A LIBERO task uses something factask does not model (an articulated fixture,
    a fixture's region in the goal, a predicate with no factask relation). The
    message names the predicate or object and says why."""


class UnknownLiberoType(LiberoUnsupported):
    """An object or fixture type with no entry in :data:`LIBERO_KINDS`."""


@dataclass(frozen=True)
class LiberoKind:
    """The factask stand-in of one LIBERO type.

    Attributes:
        kind: factask asset kind; None for the table itself (no variable).
        size: Full extents (x, y, z) in metres; None with ``kind`` None.
        color: Palette colour name.
        fixed: Fixed to the table (None: the kind's default).
        fixture: LIBERO declares it under ``:fixtures``.
        note: What it is and why this stand-in.
        drawers: For a cabinet: the LIBERO regions that are its drawers, bottom
            first (each becomes a ``drawer`` variable on a slide joint).
    """

    kind: str | None
    size: tuple[float, float, float] | None
    color: str = "gray"
    fixed: bool | None = None
    fixture: bool = False
    note: str = ""
    drawers: tuple[str, ...] = ()


def _can(d: float, h: float, color: str, note: str) -> LiberoKind:
    return LiberoKind("cylinder", (d, d, h), color, note=note)


def _box(size: tuple[float, float, float], color: str, note: str) -> LiberoKind:
    return LiberoKind("box", size, color, note=note)


_TABLE: dict[str, LiberoKind] = {
    # fixtures
    "table": LiberoKind(None, None, fixture=True, note="the table itself"),
    "floor": LiberoKind(None, None, fixture=True, note="the floor scene's ground: the table"),
    "flat_stove": LiberoKind("box", (0.18, 0.18, 0.03), "silver", fixed=True, fixture=True,
                             note="flat stove: a fixed low box; its cook region is its top "
                                  "(no burner, no knob)"),
    "wooden_cabinet": LiberoKind("cabinet", (0.22, 0.24, 0.27), "brown", fixed=True,
                                 fixture=True, note="wooden cabinet: a cabinet of three "
                                 "drawers (its bottom, middle and top regions) whose top "
                                 "side things can stand on",
                                 drawers=("bottom_region", "middle_region", "top_region")),
    "wine_rack": LiberoKind("box", (0.12, 0.20, 0.09), "tan", fixed=True, fixture=True,
                            note="wine rack: a fixed low box (no slots); 9 cm high, so "
                                 "that the cabinet's middle drawer slides out over it (the "
                                 "0.75 map puts the rack 4 cm in front of the cabinet)"),
    # receptacles and supports
    "akita_black_bowl": LiberoKind("bowl", (0.12, 0.12, 0.05), "black", fixed=False,
                                   note="black bowl, 12 cm across"),
    "glazed_rim_porcelain_ramekin": LiberoKind("bowl", (0.09, 0.09, 0.045), "white",
                                               fixed=False, note="ramekin: a small bowl"),
    "plate": LiberoKind("kit", (0.16, 0.16, 0.01), "white", fixed=True,
                        note="plate: factask's flat plate (kit), square, fixed"),
    "basket": LiberoKind("container", (0.24, 0.17, 0.08), "brown", fixed=True,
                         note="basket: an open fixed container"),
    # food boxes
    "cookies": _box((0.14, 0.08, 0.05), "orange", "cookie box, lying flat"),
    "cream_cheese": _box((0.075, 0.045, 0.03), "silver", "cream cheese pack"),
    "butter": _box((0.10, 0.05, 0.04), "yellow", "butter pack"),
    "chocolate_pudding": _box((0.09, 0.06, 0.03), "brown", "chocolate pudding mix box"),
    # cans, bottles, cartons: upright cylinders
    "alphabet_soup": _can(0.066, 0.10, "red", "alphabet soup can"),
    "tomato_sauce": _can(0.066, 0.085, "maroon", "tomato sauce can"),
    "ketchup": _can(0.055, 0.15, "pink", "ketchup bottle"),
    "bbq_sauce": _can(0.055, 0.15, "brown", "barbecue sauce bottle"),
    "salad_dressing": _can(0.05, 0.16, "green", "salad dressing bottle"),
    "milk": _can(0.065, 0.15, "white", "milk carton, as an upright cylinder"),
    "orange_juice": _can(0.065, 0.15, "orange", "orange juice carton, as an upright cylinder"),
    "wine_bottle": _can(0.075, 0.30, "olive", "wine bottle"),
}

#: LIBERO type name → its factask stand-in. Read-only.
LIBERO_KINDS = MappingProxyType(_TABLE)


def libero_kind(type_name: str, name: str = "") -> LiberoKind:
    """The stand-in of LIBERO type ``type_name``.

    Args:
        type_name: The type as a BDDL file declares it (``akita_black_bowl``).
        name: The object or fixture of that type, for the message.

    Raises:
        UnknownLiberoType: no stand-in for the type; the message lists the known ones.
    """
    try:
        return LIBERO_KINDS[type_name.lower()]
    except KeyError:
        who = f"{name} of type {type_name!r}" if name else f"type {type_name!r}"
        raise UnknownLiberoType(
            f"{who}: no factask stand-in for this LIBERO type (known: "
            f"{', '.join(sorted(LIBERO_KINDS))}); add it to factask.compat.libero.kinds"
        ) from None
