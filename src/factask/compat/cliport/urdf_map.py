"""The one table that maps CLIPort/GenSim URDF assets to factask kinds and sizes.

Every size here is a factask size: the **full extents** (x, y, z) in metres of
the object's bounding box (:mod:`factask.vocabulary.kinds`). Sizes were read from the
URDFs and meshes in GenSim's ``cliport/environments/assets`` (mesh extents times
the URDF's ``scale``). Where factask has no exact kind the closest primitive is
used and the entry's ``note`` says what is lost; the import report repeats the
note once per asset. ``docs/compat.md`` shows the same table.

Templates (``*-template.urdf``) are sized from the replacements the task passed
to ``fill_template`` (``DIM``, ``HALF``, ``DIMR``/``DIMH``, ``SCALE``):

* ``DIM`` with three values is taken as the full extents the author meant (the
  size they also pass to ``get_random_pose``), for boxes, containers, cylinders
  and balls alike. The PyBullet templates read ``DIM0`` as a *radius* for
  cylinders and balls (and the cylinder's collision swaps radius and length),
  so those objects were twice as wide in PyBullet as their authors wrote; the
  import keeps the authors' numbers and says so in a note.
* ``DIM`` with a single value on a round template is the radius the template
  literally reads: the diameter is twice it.
"""

from __future__ import annotations

import posixpath
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from factask.compat.cliport.errors import Unsupported
from factask.sim.build.parts import fixture_size_for
from factask.vocabulary.kinds import kind_spec

Size = tuple[float, float, float]

#: Range GenSim fills an unfilled template's DIM fields with (``fill_dummy_template``).
DUMMY_DIM_RANGE = (0.03, 0.05)
#: Thickness given to flat markers (zones, lines, outlines), metres.
MARKER_THICKNESS = 0.001
#: Kitting shapes: mesh extent in mesh units (the .obj files span 20 units).
KIT_SHAPE_MESH_EXTENT = 20.0
#: Default kitting-object SCALE of Ravens' ``make_kitting_objects``.
KIT_SHAPE_DEFAULT_SCALE = (0.003, 0.003, 0.001)


@dataclass(frozen=True)
class AssetSpec:
    """What a URDF becomes in factask.

    Attributes:
        kind: factask asset kind.
        size: Full extents in metres.
        color: Palette colour used when the task gives none (the URDF's own colour).
        note: The approximation made, "" if the mapping is exact.
    """

    kind: str
    size: Size
    color: str = "gray"
    note: str = ""


@dataclass(frozen=True)
class _Entry:
    kind: str
    size: Size | Callable[[Mapping[str, Sequence[float]]], Size]
    color: str
    note: str
    doc_size: str
    fields: tuple[str, ...] = ()


def _values(replace: Mapping[str, Any], field: str) -> list[float]:
    raw = replace.get(field)
    if raw is None:
        return []
    if isinstance(raw, (str, bytes)):
        raise Unsupported(f"template field {field} must be numbers, got {raw!r}")
    if not hasattr(raw, "__len__"):
        raw = (raw,)
    return [float(v) for v in np.asarray(raw, dtype=float).reshape(-1)]


def _need(replace: Mapping[str, Any], field: str, n: int) -> list[float]:
    vals = _values(replace, field)
    if len(vals) < n:
        raise Unsupported(f"template field {field} needs {n} value(s), got {vals}")
    return vals


def _box_dim(replace: Mapping[str, Any]) -> Size:
    d = _need(replace, "DIM", 3)
    return (d[0], d[1], d[2])


def _round_dim(replace: Mapping[str, Any]) -> Size:
    if "DIMR" in replace or "DIMH" in replace:
        r = _need(replace, "DIMR", 1)[0]
        h = _need(replace, "DIMH", 1)[0]
        return (2 * r, 2 * r, h)
    d = _need(replace, "DIM", 1)
    if len(d) >= 3:
        diameter = max(d[0], d[1])
        return (diameter, diameter, d[2])
    return (2 * d[0], 2 * d[0], 2 * d[0])


def _cylinder_dim(replace: Mapping[str, Any]) -> Size:
    if "DIMR" in replace or "DIMH" in replace:
        return _round_dim(replace)
    d = _need(replace, "DIM", 1)
    if len(d) >= 3:
        diameter = max(d[0], d[1])
        return (diameter, diameter, d[2])
    return (2 * d[0], 2 * d[0], 2 * d[0])


def _ball_dim(replace: Mapping[str, Any]) -> Size:
    d = _need(replace, "DIM", 1)
    diameter = max(d[:3]) if len(d) >= 3 else 2 * d[0]
    return (diameter, diameter, diameter)


def _line_dim(replace: Mapping[str, Any]) -> Size:
    return (_need(replace, "DIM", 1)[0], 0.01, MARKER_THICKNESS)


def _square_dim(replace: Mapping[str, Any]) -> Size:
    d = _need(replace, "DIM", 1)[0]
    return (d + 0.01, d + 0.01, MARKER_THICKNESS)


def _rectangle_dim(replace: Mapping[str, Any]) -> Size:
    d = _need(replace, "DIM", 2)
    return (d[0] + 0.01, d[1] + 0.01, MARKER_THICKNESS)


def _kit_shape_dim(replace: Mapping[str, Any]) -> Size:
    s = _values(replace, "SCALE") or list(KIT_SHAPE_DEFAULT_SCALE)
    if len(s) < 3:
        s = [s[0]] * 3
    return (s[0] * KIT_SHAPE_MESH_EXTENT, s[1] * KIT_SHAPE_MESH_EXTENT,
            s[2] * KIT_SHAPE_MESH_EXTENT)


_AUTHOR_DIM_NOTE = ("size = the DIM the task passed, read as full extents (PyBullet's "
                    "template reads DIM0 as a radius, so it drew it twice as wide)")
_HANOI_DISK_NOTE = "Hanoi disk (a ring with a hole for the peg) modelled as a solid cylinder"
_KIT_NOTE = ("kitting shape (a mesh) modelled as a flat block of the shape's "
             "bounding box; its own yaw symmetry is kept from the goal")

#: Ravens' ell: bars 0.08 long, 0.03 wide, 0.04 high.
_ELL_SIZE: Size = (0.08, 0.08, 0.04)

#: URDF path (relative to CLIPort's assets folder) -> factask asset.
URDF_TABLE: dict[str, _Entry] = {
    "block/block.urdf": _Entry("block", (0.04, 0.04, 0.04), "red", "", "0.04 cube"),
    "stacking/block.urdf": _Entry("block", (0.04, 0.04, 0.04), "red", "", "0.04 cube"),
    "hanoi/block.urdf": _Entry("block", (0.04, 0.04, 0.04), "red", "", "0.04 cube"),
    "block/block_for_anchors.urdf": _Entry("block", (0.04, 0.04, 0.04), "red", "",
                                           "0.04 cube"),
    "block/small.urdf": _Entry("block", (0.01, 0.01, 0.01), "red", "", "0.01 cube"),
    "box/box-template.urdf": _Entry("box", _box_dim, "red", "", "DIM", ("DIM",)),
    "container/container-template.urdf": _Entry(
        "container", _box_dim, "brown", "", "DIM (outer extents; HALF is ignored)", ("DIM",)),
    "zone/zone.urdf": _Entry("zone", (0.12, 0.12, MARKER_THICKNESS), "green", "",
                             "0.12 x 0.12"),
    "pallet/pallet.urdf": _Entry("pallet", (0.30, 0.25, 0.0375), "brown", "",
                                 "0.30 x 0.25 x 0.0375"),
    "bowl/bowl.urdf": _Entry("bowl", (0.12, 0.12, 0.035), "gray", "",
                             "0.12 across, 0.035 high"),
    "insertion/ell.urdf": _Entry(
        "ell", _ELL_SIZE, "red",
        "the URDF origin is the bars' crossing, factask's is the bounding-box centre "
        "(2.5 cm apart along each bar); ell and fixture are shifted alike", "0.08 x 0.08 x 0.04"),
    "insertion/fixture.urdf": _Entry(
        "fixture", fixture_size_for(_ELL_SIZE), "brown",
        "factask's fixture is sized to take its ell: 1 cm walls, 5 mm play (URDF walls "
        "span 0.10 x 0.105; the kind's default 0.12 frame overlapped fixtures an author "
        "put 10 cm apart, and an ell came to rest tilted on its neighbour's wall)",
        "0.11 x 0.11 x 0.04"),
    "kitting/kit.urdf": _Entry("kit", (0.28, 0.20, 0.005), "gray", "", "0.28 x 0.2 x 0.005"),
    "kitting/object-template.urdf": _Entry("block", _kit_shape_dim, "red", _KIT_NOTE,
                                           "20 x SCALE (default 0.06 x 0.06 x 0.02)"),
    "kitting/object-template-nocollision.urdf": _Entry(
        "zone", _kit_shape_dim, "gray",
        "kit target marker (a shape outline, no collision) modelled as a flat zone",
        "20 x SCALE (default 0.06 x 0.06 x 0.02)"),
    "corner/corner-template.urdf": _Entry(
        "corner", kind_spec("corner").default_size, "green",
        "DIMX/DIMY arm offsets are ignored", "arms 0.055"),
    "line/line-template.urdf": _Entry("line", _line_dim, "green", "", "DIM0 x 0.01", ("DIM",)),
    "line/single-green-line-template.urdf": _Entry("line", _line_dim, "green", "",
                                                   "DIM0 x 0.01", ("DIM",)),
    "square/square-template.urdf": _Entry(
        "zone", _square_dim, "gray", "square outline modelled as a flat zone of its extent",
        "(DIM0 + 0.01) square", ("DIM",)),
    "stacking/stand.urdf": _Entry(
        "stand", (0.05, 0.15, 0.005), "brown",
        "3 plates of 0.05 x 0.05 in a row along y, as in the URDF", "0.05 x 0.15 x 0.005"),
    "hanoi/stand.urdf": _Entry(
        "stand", (0.12, 0.36, 0.01), "brown",
        "three 0.12 plates along y; the three pegs are not modelled", "0.12 x 0.36 x 0.01"),
    "hanoi/disk0.urdf": _Entry("cylinder", (0.06, 0.06, 0.01), "red", _HANOI_DISK_NOTE,
                               "0.06 across, 0.01 high"),
    "hanoi/disk1.urdf": _Entry("cylinder", (0.07, 0.07, 0.01), "red", _HANOI_DISK_NOTE,
                               "0.07 across, 0.01 high"),
    "hanoi/disk2.urdf": _Entry("cylinder", (0.08, 0.08, 0.01), "red", _HANOI_DISK_NOTE,
                               "0.08 across, 0.01 high"),
    "hanoi/disk3.urdf": _Entry("cylinder", (0.09, 0.09, 0.01), "red", _HANOI_DISK_NOTE,
                               "0.09 across, 0.01 high"),
    "hanoi/slimdisk.urdf": _Entry("cylinder", (0.09, 0.09, 0.005), "green", _HANOI_DISK_NOTE,
                                  "0.09 across, 0.005 high"),
    "cylinder/cylinder-template.urdf": _Entry(
        "cylinder", _cylinder_dim, "red", _AUTHOR_DIM_NOTE,
        "DIM = (diameter, diameter, height); DIMR/DIMH = radius/height", ("DIM",)),
    "ball/ball-template.urdf": _Entry("ball", _ball_dim, "red", _AUTHOR_DIM_NOTE,
                                      "DIM = diameter (3 values) or radius (1 value)",
                                      ("DIM",)),
    "sphere/sphere-template.urdf": _Entry("ball", _ball_dim, "red", _AUTHOR_DIM_NOTE,
                                          "DIM = diameter (3 values) or radius (1 value)",
                                          ("DIM",)),
    "ball/ball.urdf": _Entry("ball", (0.06, 0.06, 0.06), "red", "", "0.06 sphere"),
    "sphere/sphere.urdf": _Entry("ball", (0.06, 0.06, 0.06), "red", "", "0.06 sphere"),
}

#: Families of files named by prefix (colour variants of outlines).
URDF_PREFIXES: dict[str, _Entry] = {
    "square/square-template-allsides": _Entry(
        "zone", _square_dim, "blue", "square outline modelled as a flat zone of its extent",
        "(DIM0 + 0.01) square", ("DIM",)),
    "rectangle/rectangle-template-sides": _Entry(
        "zone", _rectangle_dim, "green",
        "rectangle outline modelled as a flat zone of its extent",
        "(DIM0 + 0.01) x (DIM1 + 0.01)", ("DIM",)),
}

#: Asset folders factask cannot model, with the reason.
UNSUPPORTED_PREFIXES: dict[str, str] = {
    "cable/": "cables/ropes are deformable",
    "sphere/sphere_rope": "rope beads are deformable",
    "bags/": "bags are deformable",
    "cloth/": "cloth is deformable",
    "google/": "Google scanned objects are not available",
    "ur5/": "robot parts are not task objects",
    "plane/": "the ground plane is part of every scene already",
}


def asset_key(path: str, assets_root: str | None = None) -> str:
    """The table key of a URDF path: ``folder/file.urdf`` relative to the assets.

    Args:
        path: What the task passed (relative, or joined onto ``assets_root``).
        assets_root: The task's assets root, stripped if ``path`` starts with it.
    """
    p = str(path).replace("\\", "/")
    if assets_root:
        root = str(assets_root).replace("\\", "/").rstrip("/") + "/"
        if p.startswith(root):
            p = p[len(root):]
    parts = [s for s in posixpath.normpath(p).split("/") if s not in ("", ".")]
    return "/".join(parts[-2:])


def _lookup(key: str) -> _Entry | None:
    if key in URDF_TABLE:
        return URDF_TABLE[key]
    for prefix, entry in URDF_PREFIXES.items():
        if key.startswith(prefix):
            return entry
    # GenSim's env.add_object falls back from "x-template.urdf" to "x.urdf".
    if "-template" in key:
        return URDF_TABLE.get(key.replace("-template", ""))
    return None


def resolve_asset(
    key: str,
    replace: Mapping[str, Any] | None = None,
    rng: np.random.Generator | None = None,
) -> tuple[AssetSpec, list[str]]:
    """The factask asset of a URDF.

    Args:
        key: Table key (see :func:`asset_key`).
        replace: ``fill_template`` replacements, if the URDF came from one.
        rng: Generator for GenSim's dummy fill of an unfilled template.

    Returns:
        The asset and warnings (approximations, dummy fills).

    Raises:
        Unsupported: unknown URDF, an unsupported asset family, or template fields
            that cannot be read.
    """
    for prefix, why in UNSUPPORTED_PREFIXES.items():
        if key.startswith(prefix):
            raise Unsupported(f"URDF {key!r} is not supported: {why}")
    entry = _lookup(key)
    if entry is None:
        raise Unsupported(
            f"unknown URDF {key!r}: factask has no mapping for it (known: "
            f"{', '.join(sorted(URDF_TABLE))}; see docs/compat.md)"
        )
    warnings: list[str] = []
    fields = dict(replace or {})
    missing = [f for f in entry.fields if f not in fields]
    if missing:
        gen = rng if rng is not None else np.random.default_rng(0)
        for f in missing:
            fields[f] = tuple(float(v) for v in gen.uniform(*DUMMY_DIM_RANGE, size=3))
        warnings.append(f"template {key!r} used without {'/'.join(missing)}: filled with "
                        f"random values in {DUMMY_DIM_RANGE} m as GenSim does")
    size = entry.size(fields) if callable(entry.size) else entry.size
    if not all(np.isfinite(size)) or min(size) <= 0:
        raise Unsupported(f"URDF {key!r}: size {size} from {fields} is not positive")
    spec = AssetSpec(entry.kind, tuple(float(s) for s in size), entry.color,  # type: ignore[arg-type]
                     entry.note)
    return spec, warnings


def mapping_rows() -> list[tuple[str, str, str, str]]:
    """(URDF, kind, size, note) rows of the whole table, for docs and the CLI."""
    rows = [(k, e.kind, e.doc_size, e.note) for k, e in URDF_TABLE.items()]
    rows += [(f"{k}*", e.kind, e.doc_size, e.note) for k, e in URDF_PREFIXES.items()]
    return rows
