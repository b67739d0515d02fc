"""LIBERO's object and fixture types → factask stand-ins: one table, :data:`LIBERO_KINDS`.

LIBERO's scenes use meshes (scanned groceries, a porcelain ramekin, a wooden
cabinet); factask has primitive kinds. Every type LIBERO registers maps here
(the data: :mod:`factask.compat.libero.catalog`) to a kind, a size (full extents
in metres, the one size convention of :mod:`factask.vocabulary.kinds`; real-ish
sizes of the real things) and a palette colour. These are **stand-ins**: the graph
keeps what the task is about (what is picked, what it goes on or in, which objects
are in the way), not the look or the exact shape of LIBERO's meshes. The rules,
one per category (:mod:`factask.compat.libero.spec`):

* bowls, the ramekin and the frying pan → a movable ``bowl``; the plate and the
  dining set → a fixed flat ``kit`` (made movable when a goal moves it); baskets,
  trays, the desk caddy (its four compartments one inside) and the bowl drainer → an
  open ``container``;
* food boxes, packs and books → a ``box`` lying flat; cans, bottles, jars, cartons,
  mugs and the moka pot → an upright ``cylinder`` of their diameter and height;
* fixtures: the scenes' tables and the floor are factask's table (no variable);
  cabinets (wooden, white, short) are a ``cabinet`` of three drawers on slide joints
  whose top side things stand on; the flat stove is a ``stove`` with a push-button
  switch, its cook region its top; the microwave is a ``microwave`` with a hinged
  door, its heating region its inside (a plain fixed box where a file never names
  its door: :attr:`LiberoKind.plain`); the shelves are factask's stepped ``shelf``
  whose level regions are its ``shelf_level`` variables (:attr:`LiberoKind.levels`:
  LIBERO's levels under boards become steps open from above, rising away from the
  robot); the fridge and racks are fixed ``box``es whose top side is a support.
  What moves on them and factask does not model (a fridge's hinged door, a slide
  cabinet's sliding door, a faucet's handle)
  is :attr:`LiberoKind.articulation`: the importer refuses ``Open``, ``Close``,
  ``Turnon``, ``Turnoff`` of it naming it
  (:mod:`factask.compat.libero.articulated`).

A type LIBERO does not register is typed by the category rule of its name
(:func:`category_kind`: ``red_bowl``, ``soup_can``) where one fits; else it is an
:class:`UnknownLiberoType`. A region is typed by :func:`region_role`.
"""

from __future__ import annotations

import re
from dataclasses import replace
from types import MappingProxyType

from factask.compat.libero.catalog import SCENES, TYPES, LiberoScene
from factask.compat.libero.spec import (
    REGION_ROLES,
    LiberoKind,
    LiberoUnsupported,
    RegionRole,
    UnknownLiberoRegion,
    UnknownLiberoType,
    bowl,
    box,
    can,
    container,
)

__all__ = [
    "LIBERO_KINDS", "LIBERO_SCENES", "REGION_ROLES", "LiberoKind", "LiberoScene",
    "LiberoUnsupported", "RegionRole", "UnknownLiberoRegion", "UnknownLiberoType",
    "category_kind", "libero_kind", "region_role", "scene_of",
]

#: LIBERO type name → its factask stand-in. Read-only.
LIBERO_KINDS = MappingProxyType(TYPES)
#: LIBERO problem name (lower-cased) → its scene. Read-only.
LIBERO_SCENES = MappingProxyType(SCENES)

#: The category rules for a type LIBERO does not register: a word of its name →
#: the stand-in of that category (first match wins; the words are whole words of the
#: snake_case name).
_CATEGORY_RULES: tuple[tuple[frozenset[str], LiberoKind], ...] = (
    (frozenset({"bowl", "ramekin", "frypan", "pan", "skillet"}),
     bowl((0.12, 0.12, 0.05), "gray", "a bowl (by its name)")),
    (frozenset({"mug", "cup"}), can(0.08, 0.09, "gray", "a mug (by its name)", "mug")),
    (frozenset({"plate", "dish", "saucer"}),
     LiberoKind("kit", (0.16, 0.16, 0.01), "white", fixed=True,
                note="a plate (by its name)", category="plate")),
    (frozenset({"basket", "tray", "caddy", "drainer", "bin", "crate"}),
     container((0.20, 0.16, 0.07), "gray", "an open container (by its name)")),
    (frozenset({"book", "notebook"}),
     box((0.15, 0.10, 0.03), "gray", "a book lying flat (by its name)", "book")),
    (frozenset({"can", "soup", "sauce", "bottle", "jar", "juice", "milk", "ketchup",
                "dressing", "mayo", "mustard", "carton", "pot", "canister"}),
     can(0.066, 0.12, "gray", "an upright cylinder: can, bottle or jar (by its name)")),
    (frozenset({"box", "pack", "cheese", "butter", "cookies", "pudding", "cereal",
                "popcorn", "macaroni"}),
     box((0.10, 0.06, 0.04), "gray", "a food box lying flat (by its name)")),
)


def category_kind(type_name: str) -> LiberoKind | None:
    """The stand-in of a type LIBERO does not register, by the category rule its
    name's words match (``red_bowl`` → a bowl; ``tuna_can`` → a cylinder).

    Args:
        type_name: The type as a BDDL file declares it.

    Returns:
        The stand-in (its note says it was typed by name), or None when no rule fits.
    """
    words = set(re.split(r"[_\W\d]+", type_name.lower())) - {""}
    color = next((w for w in words if w in _COLOR_WORDS), None)
    for keys, spec in _CATEGORY_RULES:
        if words & keys:
            return replace(spec, color=color or spec.color,
                           note=f"{type_name}: {spec.note}")
    return None


_COLOR_WORDS = frozenset({"red", "green", "blue", "yellow", "white", "black", "orange",
                          "brown", "pink", "purple", "gray", "silver"})


def libero_kind(type_name: str, name: str = "") -> LiberoKind:
    """The stand-in of LIBERO type ``type_name``: its entry in :data:`LIBERO_KINDS`,
    else the category rule its name matches (:func:`category_kind`).

    Args:
        type_name: The type as a BDDL file declares it (``akita_black_bowl``).
        name: The object or fixture of that type, for the message.

    Returns:
        The stand-in.

    Raises:
        UnknownLiberoType: no stand-in for the type and no category rule fits it.
    """
    key = type_name.lower()
    if key in LIBERO_KINDS:
        return LIBERO_KINDS[key]
    by_name = category_kind(key)
    if by_name is not None:
        return by_name
    who = f"{name} of type {type_name!r}" if name else f"type {type_name!r}"
    raise UnknownLiberoType(
        f"{who}: no factask stand-in for this LIBERO type and no category rule fits its "
        f"name (known: {', '.join(sorted(LIBERO_KINDS))}); add it to "
        "factask.compat.libero.catalog")


def region_role(spec: LiberoKind, region: str) -> RegionRole | None:
    """The role of a fixture's or object's own region, by the general rule: the type's
    own listing (:attr:`LiberoKind.regions`) first, then the region's name:
    ``*contain_region`` is the inside of a receptacle, ``top_side`` / ``top_region``
    the top of a support. Drawer and shelf level regions are not roles
    (:attr:`LiberoKind.drawers`, :attr:`LiberoKind.levels`).

    Args:
        spec: The stand-in of the region's target.
        region: The region's own name (``back_contain_region``).

    Returns:
        The role, or None when no rule types the region.
    """
    listed = spec.role_of(region)
    if listed is not None:
        return listed
    if spec.kind is None:
        return None
    from factask.vocabulary.kinds import kind_spec

    facts = kind_spec(spec.kind)
    if region.endswith("contain_region") and facts.receptacle:
        return "inside"
    if region in ("top_side", "top_region") and facts.support and not spec.drawers \
            and not spec.levels:
        return "top"
    return None


def scene_of(problem_name: str) -> LiberoScene | None:
    """The scene of a problem name (``LIBERO_Kitchen_Tabletop_Manipulation``).

    Args:
        problem_name: The problem's name as the BDDL file writes it.

    Returns:
        The scene, or None for a name LIBERO does not register.
    """
    return LIBERO_SCENES.get(problem_name.lower())
