"""The recording environment a CLIPort task's ``reset(env)`` runs against.

Nothing is simulated: ``env.add_object`` resolves the URDF to a factask asset
(:mod:`factask.compat.cliport.urdf_map`), stores the object with its pose, colour
and category, and hands back a fresh integer id, as PyBullet would. The one
:class:`Session` of a load also holds what the stand-in modules share (the
random generator, the ``fill_template`` registry, the warnings), because
``fill_template`` and ``pybullet`` calls receive no env.
"""

from __future__ import annotations

import contextlib
import os
import random
import shutil
import string
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from factask.compat.cliport.errors import Unsupported, UnsupportedAttribute
from factask.compat.cliport.transforms import split_pose
from factask.compat.cliport.urdf_map import asset_key, resolve_asset
from factask.vocabulary.limits import MAX_OBJECTS
from factask.vocabulary.palette import COLORS as PALETTE
from factask.vocabulary.palette import nearest_color, normalize_color

#: First id handed out; PyBullet's plane, workspace and robot take the ones below.
FIRST_OBJECT_ID = 5
#: Assets root a loaded task sees (a name only: nothing is read from it).
FAKE_ASSETS_ROOT = "cliport/environments/assets"
#: RGB distance above which a colour tuple's nearest palette name is reported.
COLOR_MATCH_WARN_DISTANCE = 0.15
#: Categories of ``env.add_object`` factask models.
CATEGORIES = ("rigid", "fixed")
#: Objects a task may add before recording stops: more than a scene holds, since a
#: pile's pieces and a rope's beads become one variable each, yet bounded, so a task
#: adding objects in an endless loop stops at once.
MAX_RECORDED_OBJECTS = 5 * MAX_OBJECTS


@dataclass
class TemplateFill:
    """What ``fill_template`` was asked: the template and its replacements."""

    template: str
    replace: dict[str, Any]


@dataclass
class RecordedObject:
    """One object the task added.

    Attributes:
        obj_id: The id ``add_object`` returned.
        urdf: Table key of its URDF (``folder/file.urdf``).
        kind: factask kind.
        size: Full extents, metres.
        color: Palette colour name.
        category: ``rigid`` or ``fixed``.
        pos: Position (x, y, z) of the URDF origin, metres.
        quat: Orientation, x, y, z, w.
        note: Approximation note of the asset mapping ("" if exact).
        random_start: Its pose is one ``get_random_pose`` returned (a random free spot).
        placed_top: Height of its top as the author placed it, where factask's asset
            is taller (a sunk asset started on the table): what the author's targets
            on it are measured against. None: its top.
        checked_size: For a marker region (a zone), the x, y size a zone goal checks
            it at (Ravens' ``zone_size``), once a goal has named it. None: not yet.
    """

    obj_id: int
    urdf: str
    kind: str
    size: tuple[float, float, float]
    color: str
    category: str
    pos: np.ndarray
    quat: np.ndarray
    note: str = ""
    random_start: bool = False
    placed_top: float | None = None
    checked_size: tuple[float, float] | None = None


@dataclass
class Session:
    """State shared by the stand-in modules while one task file is loaded.

    Attributes:
        seed: Seed of every random generator of the load.
        rng: Generator used by ``get_random_pose`` and dummy template fills.
        tmpdir: Folder of ``fill_template``'s token files (removed at close).
        templates: Token path -> what was filled.
        objects: Recorded objects by id, in the order they were added.
        warnings: Everything approximated or dropped, for the import report.
        random_spots: Positions ``get_random_pose`` returned (rounded keys).
        shapes: PyBullet shape id -> what ``createCollisionShape`` /
            ``createVisualShape`` was asked (:mod:`factask.compat.cliport.bodies`).
        constraints: Constraint id -> what ``createConstraint`` was asked.
    """

    seed: int = 0
    rng: np.random.Generator = field(default_factory=lambda: np.random.default_rng(0))
    tmpdir: str = ""
    templates: dict[str, TemplateFill] = field(default_factory=dict)
    objects: dict[int, RecordedObject] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    random_spots: set[tuple[float, ...]] = field(default_factory=set)
    shapes: dict[int, Any] = field(default_factory=dict)
    constraints: dict[int, Any] = field(default_factory=dict)
    _next_id: int = FIRST_OBJECT_ID

    def warn(self, message: str) -> None:
        """Record a warning once."""
        if message not in self.warnings:
            self.warnings.append(message)

    @staticmethod
    def spot_key(pos: Any) -> tuple[float, ...]:
        """Key of a position for :attr:`random_spots` (rounded to 1 micrometre)."""
        return tuple(round(float(c), 6) for c in np.asarray(pos, dtype=float).reshape(-1)[:3])

    def new_id(self) -> int:
        """A fresh object id."""
        oid = self._next_id
        self._next_id += 1
        return oid

    def register_template(self, template: str, replace: dict[str, Any]) -> str:
        """Write a token file for a filled template and return its path.

        The token is a real file (task code often ``os.remove``-s the filled URDF
        after loading it); its name ends like GenSim's (``<template>.<random>``).
        """
        base = self.templates.get(str(template))
        if base is not None:
            # Filling an already filled URDF (GenSim code does this in loops): its
            # fields are already replaced, so only a new COLOR takes effect there.
            template, merged = base.template, dict(base.replace)
            if "COLOR" in replace:
                merged["COLOR"] = replace["COLOR"]
            replace = merged
        if not self.tmpdir:
            self.tmpdir = tempfile.mkdtemp(prefix="factask-cliport-")
        alphabet = string.ascii_lowercase + string.digits
        name = "".join(random.Random(len(self.templates) + self.seed).choices(alphabet, k=16))
        path = os.path.join(self.tmpdir, f"{os.path.basename(template)}.{name}")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(f"factask fill_template token for {template}\n")
        self.templates[path] = TemplateFill(template, dict(replace))
        return path

    def obj(self, obj_id: Any) -> RecordedObject:
        """The recorded object of ``obj_id``.

        Raises:
            Unsupported: no object with that id was added with ``env.add_object``.
        """
        try:
            return self.objects[int(obj_id)]
        except (KeyError, TypeError, ValueError):
            raise Unsupported(
                f"object id {obj_id!r} was not created with env.add_object"
            ) from None

    def close(self) -> None:
        """Remove the token files."""
        if self.tmpdir:
            shutil.rmtree(self.tmpdir, ignore_errors=True)
            self.tmpdir = ""


_ACTIVE: list[Session] = []


def active_session() -> Session:
    """The session of the load in progress.

    Raises:
        Unsupported: called outside a load (the stand-ins are only meaningful there).
    """
    if not _ACTIVE:
        raise Unsupported("CLIPort stand-ins used outside factask.compat.cliport's loader")
    return _ACTIVE[-1]


@contextlib.contextmanager
def session_scope(session: Session) -> Iterator[Session]:
    """Make ``session`` the active one for the duration of the block."""
    _ACTIVE.append(session)
    try:
        yield session
    finally:
        _ACTIVE.remove(session)


def color_name(color: Any, session: Session | None = None) -> str:
    """Palette name of a CLIPort colour: a name, or an RGB/RGBA sequence.

    Raises:
        factask.vocabulary.palette.UnknownColorError: a name not in the palette.
    """
    if isinstance(color, str):
        return normalize_color(color)
    vals = [float(c) for c in np.asarray(color, dtype=float).reshape(-1)[:3]]
    name = nearest_color(vals)
    scale = 255.0 if any(v > 1.0 for v in vals) else 1.0
    dist = float(np.linalg.norm(np.array(vals) / scale - np.array(PALETTE[name])))
    if session is not None and dist > COLOR_MATCH_WARN_DISTANCE:
        session.warn(f"colour {tuple(round(v, 3) for v in vals)} is far from every palette "
                     f"colour; using the nearest, {name!r}")
    return name


class RecordingEnv:
    """Stands in for CLIPort's ``Environment`` during ``task.reset(env)``.

    Attributes:
        task: The task being reset.
        obj_ids: Ids by category, as CLIPort keeps them.
        assets_root: The (fake) assets root.
    """

    def __init__(self, session: Session, task: Any = None) -> None:
        self._session = session
        self.task = task
        self.obj_ids: dict[str, list[int]] = {"fixed": [], "rigid": [], "deformable": []}
        self.objects = self.obj_ids
        self.assets_root = FAKE_ASSETS_ROOT
        self.record_cfg: dict[str, Any] = {}

    def add_object(self, urdf: str, pose: Any, category: str = "rigid",
                   color: Any = None, **kwargs: Any) -> int:
        """Record an object and return its id (CLIPort's ``add_object``).

        Args:
            urdf: Asset path or a ``fill_template`` token.
            pose: ``(position, quaternion xyzw)`` or a bare position.
            category: ``rigid`` or ``fixed`` (``deformable`` is unsupported).
            color: Palette name or RGB/RGBA; default: the URDF's own colour.

        Returns:
            The new object's id.

        Raises:
            Unsupported: deformable category, an unknown URDF, or more objects than
                :data:`MAX_RECORDED_OBJECTS`.
        """
        s = self._session
        if len(s.objects) >= MAX_RECORDED_OBJECTS:
            raise Unsupported(f"the task adds more than {MAX_RECORDED_OBJECTS} objects; a "
                              f"factask scene holds at most {MAX_OBJECTS} (a pile or a rope "
                              "counts as one) (fix: add fewer objects)")
        if category not in CATEGORIES:
            raise Unsupported(f"env.add_object(category={category!r}): only 'rigid' and "
                              "'fixed' objects are supported (no deformables)")
        fill = s.templates.get(str(urdf))
        if fill is not None:
            key, replace = asset_key(fill.template, FAKE_ASSETS_ROOT), fill.replace
        else:
            key, replace = asset_key(str(urdf), FAKE_ASSETS_ROOT), {}
        spec, warnings = resolve_asset(key, replace, s.rng)
        for w in warnings:
            s.warn(w)
        if spec.note:
            s.warn(f"{key}: {spec.note}")
        if color is None and "COLOR" in replace:
            color = replace["COLOR"]
        name = color_name(color, s) if color is not None else spec.color
        try:
            pos, quat = split_pose(pose)
        except (TypeError, ValueError) as exc:
            raise Unsupported(f"env.add_object({key!r}): bad pose {pose!r}: {exc}") from None
        oid = s.new_id()
        s.objects[oid] = RecordedObject(oid, key, spec.kind, spec.size, name, category,
                                        pos, quat, spec.note,
                                        s.spot_key(pos) in s.random_spots)
        self.obj_ids[category].append(oid)
        return oid

    def get_object_pose(self, obj_id: int) -> tuple[tuple[float, ...], tuple[float, ...]]:
        """Recorded pose of an object."""
        o = self._session.obj(obj_id)
        return tuple(map(float, o.pos)), tuple(map(float, o.quat))

    def get_object_size(self, obj_id: int) -> float:
        """Bounding-box volume, as GenSim's ``get_object_size`` returns."""
        sx, sy, sz = self._session.obj(obj_id).size
        return sx * sy * sz

    def set_color(self, obj_id: int, color: Any) -> None:
        """Change an object's colour."""
        self._session.obj(obj_id).color = color_name(color, self._session)

    set_object_color = set_color

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        raise UnsupportedAttribute(f"env.{name} is not available while recording a task's reset "
                          "(factask records objects and goals only)")
