"""State variables: the named, typed things in a scene."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Annotated, ClassVar, Literal, Protocol

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from factask.vocabulary.errors import InvalidValueError, Problem
from factask.vocabulary.kinds import (
    MAX_DRAWERS,
    MAX_SHELF_LEVELS,
    SWITCH_HOSTS,
    AssetKind,
    default_mass,
    door_size,
    drawer_size,
    kind_spec,
    shelf_level_size,
    switch_size,
    yaw_symmetry_deg,
)
from factask.vocabulary.limits import MAX_COUNT, MAX_HORIZONTAL, MIN_LENGTH, Text
from factask.vocabulary.names import Name, instance_names
from factask.vocabulary.palette import normalize_color
from factask.vocabulary.world import WORKSPACE_X, WORKSPACE_Y

PositiveLength = Annotated[float, Field(ge=MIN_LENGTH, le=MAX_HORIZONTAL, allow_inf_nan=False)]


class OnTable(BaseModel):
    """Start at a random free spot of the workspace (the default)."""

    model_config = ConfigDict(extra="forbid")
    type: Literal["table"] = "table"


class InRegion(BaseModel):
    """Start at a random free spot inside an x/y box of the table (metres)."""

    model_config = ConfigDict(extra="forbid")
    type: Literal["region"] = "region"
    x: tuple[float, float] = Field(WORKSPACE_X)
    y: tuple[float, float] = Field(WORKSPACE_Y)

    @model_validator(mode="after")
    def _ordered(self) -> InRegion:
        for axis, (lo, hi), (wlo, whi) in (("x", self.x, WORKSPACE_X), ("y", self.y, WORKSPACE_Y)):
            if not lo < hi:
                raise InvalidValueError(f"region {axis} range must have low < high, got {(lo, hi)}")
            if lo < wlo - 1e-9 or hi > whi + 1e-9:
                raise InvalidValueError(
                    f"region {axis} range {(lo, hi)} leaves the workspace {(wlo, whi)}"
                )
        return self


#: A given place on a host is at most this far (metres) from the host's centre.
MAX_OFFSET = 1.0
Offset = Annotated[float, Field(ge=-MAX_OFFSET, le=MAX_OFFSET, allow_inf_nan=False)]


class _OnHost(BaseModel):
    """Where on its host an object starts: a free spot (default), or the place
    given by ``offset`` (x, y in metres, in the host's frame) and ``yaw_deg``
    (relative to the host) — e.g. a disk on a given peg of a stand. A given place
    is a fact: an object there that overlaps something else is an error, never
    moved."""

    model_config = ConfigDict(extra="forbid")
    offset: tuple[Offset, Offset] | None = None
    yaw_deg: Annotated[float, Field(ge=-360, le=360, allow_inf_nan=False)] = 0.0


class StartOn(_OnHost):
    """Start resting on top of another variable (e.g. disks stacked on a stand)."""

    type: Literal["on"] = "on"
    support: Name

    #: The field naming the variable this start depends on (renaming rewrites it).
    reference_field: ClassVar[str] = "support"


class StartInside(_OnHost):
    """Start inside a receptacle variable (a container or bowl)."""

    type: Literal["inside"] = "inside"
    container: Name

    reference_field: ClassVar[str] = "container"


class InCabinet(BaseModel):
    """Start as drawer ``level`` (0: the bottom one) of the cabinet variable
    ``cabinet``, pulled out by ``opening`` (a fraction of its travel: 0 closed, 1 all
    the way out); its cabinet has one bay per drawer in it. A door starts so on the
    microwave variable ``cabinet`` (level 0, ``opening`` a fraction of its swing),
    and a shelf level as level ``level`` of the shelf variable ``cabinet`` (it never
    opens: ``opening`` 0). Only drawers, doors and shelf levels start so: each is a
    part of a piece of furniture, its place in it a fact."""

    model_config = ConfigDict(extra="forbid")
    type: Literal["in_cabinet"] = "in_cabinet"
    cabinet: Name
    level: int = Field(0, ge=0, le=MAX_DRAWERS - 1)
    opening: Annotated[float, Field(ge=0, le=1, allow_inf_nan=False)] = 0.0

    reference_field: ClassVar[str] = "cabinet"


class MountedOn(BaseModel):
    """Start as the switch of the switchable fixture variable ``host`` (a stove, a
    lamp: :data:`~factask.vocabulary.kinds.SWITCH_HOSTS`), on (pressed down) or off
    (up). Only a switch starts so; a host has one switch."""

    model_config = ConfigDict(extra="forbid")
    type: Literal["mounted_on"] = "mounted_on"
    host: Name
    on: bool = False

    reference_field: ClassVar[str] = "host"


#: Every start placement's field that names another variable (renaming rewrites them).
START_REFERENCE_FIELDS: tuple[str, ...] = tuple(
    c.reference_field for c in (StartOn, StartInside, InCabinet, MountedOn))


class AtFixedPose(BaseModel):
    """Start at a given x, y (metres) and yaw (degrees), resting on the table."""

    model_config = ConfigDict(extra="forbid")
    type: Literal["pose"] = "pose"
    x: Annotated[float, Field(ge=WORKSPACE_X[0], le=WORKSPACE_X[1], allow_inf_nan=False)]
    y: Annotated[float, Field(ge=WORKSPACE_Y[0], le=WORKSPACE_Y[1], allow_inf_nan=False)]
    yaw_deg: Annotated[float, Field(allow_inf_nan=False)] = 0.0


Placement = Annotated[
    OnTable | InRegion | StartOn | StartInside | AtFixedPose | InCabinet | MountedOn,
    Field(discriminator="type"),
]


class StateVariable(BaseModel):
    """A named thing (or group of identical things) in the scene.

    Attributes:
        name: snake_case identifier, unique in the graph.
        description: What the variable means in the task.
        kind: Asset kind (see :data:`factask.vocabulary.kinds.ASSET_KINDS`).
        size: Full extents (x, y, z) in metres (the one size convention, see
            :mod:`factask.vocabulary.kinds`); defaults to the kind's size.
        color: Palette colour name (see :data:`factask.vocabulary.palette.COLORS`).
        count: Number of identical objects the variable stands for.
        mass: Mass of one object in kg; defaults from the kind's density.
        fixed: Fixed to the table; defaults to the kind's default.
        symmetry_deg: Yaw symmetry override in degrees (0: yaw never matters);
            defaults from the kind and footprint.
        initial: Where the object(s) start; default a free table spot.
    """

    model_config = ConfigDict(extra="forbid")

    name: Name
    description: Text = ""
    kind: AssetKind
    size: tuple[PositiveLength, PositiveLength, PositiveLength] | None = None
    color: str = "gray"
    count: int = Field(1, ge=1, le=MAX_COUNT)
    mass: Annotated[float, Field(gt=0, le=50, allow_inf_nan=False)] | None = None
    fixed: bool | None = None
    symmetry_deg: Annotated[float, Field(ge=0, le=360, allow_inf_nan=False)] | None = None
    initial: Placement = Field(default_factory=OnTable)

    @field_validator("color")
    @classmethod
    def _known_color(cls, value: str) -> str:
        return normalize_color(value)

    @model_validator(mode="after")
    def _fill_defaults(self) -> StateVariable:
        spec = kind_spec(self.kind)
        if self.size is None:
            self.size = spec.default_size
        if self.fixed is None:
            self.fixed = not spec.movable
        return self

    @property
    def extents(self) -> tuple[float, float, float]:
        """Full extents (never None after validation).

        Raises:
            InvalidValueError: ``size`` was set to None after the variable was made.
        """
        if self.size is None:
            raise InvalidValueError(f"variable {self.name!r}: size is None (set after it was "
                                    "made); give a size, or make the variable again for "
                                    "its kind's default")
        return self.size

    def unset_defaults(self) -> list[str]:
        """Fields filled with the kind's default when the variable was made that were set
        back to None afterwards (``v.size = None``): None means "the default" only at
        construction, so such a variable is refused, not silently changed (a fixed bowl
        read as movable)."""
        return [f for f in ("size", "fixed") if getattr(self, f) is None]

    @property
    def is_fixed(self) -> bool:
        """True if the variable's objects are fixed to the table."""
        return bool(self.fixed)

    @property
    def symmetry(self) -> float:
        """Yaw symmetry in degrees (0: any yaw is equivalent)."""
        if self.symmetry_deg is not None:
            return self.symmetry_deg
        return yaw_symmetry_deg(self.kind, self.extents)

    @property
    def object_mass(self) -> float:
        """Mass of one object, kg."""
        return self.mass if self.mass is not None else default_mass(self.kind, self.extents)

    @property
    def instances(self) -> list[str]:
        """Names of the objects this variable stands for."""
        return instance_names(self.name, self.count)

    def references(self) -> list[str]:
        """Other variables this variable's initial placement depends on."""
        field = getattr(self.initial, "reference_field", None)
        return [getattr(self.initial, field)] if field else []


class VariableSet(Protocol):
    """What the layers below the task graph read of one: its variables, and one by name.

    :class:`factask.graph.TaskGraph` is one. The scene geometry and the relations'
    solvers sit below the graph (the graph imports the relations), so they name this
    protocol, not the class.
    """

    @property
    def variables(self) -> Sequence[StateVariable]: ...

    def variable(self, name: str) -> StateVariable: ...


def _one_object(v: StateVariable) -> list[Problem]:
    """A piece of furniture or one of its parts stands for one object (its place in
    its host, or its parts' places in it, are facts about that one object)."""
    if v.count == 1:
        return []
    return [Problem(v.name, "count", f"a {v.kind} variable stands for one object, "
                    f"got count {v.count}", "give each its own variable")]


def drawers_of(variables: Sequence[StateVariable], cabinet: str) -> list[StateVariable]:
    """The drawer variables that start in ``cabinet`` (:class:`InCabinet`), by level:
    their number is the cabinet's number of bays.

    Args:
        variables: A graph's variables.
        cabinet: The cabinet variable's name.
    """
    found = [v for v in variables
             if isinstance(v.initial, InCabinet) and v.initial.cabinet == cabinet]
    return sorted(found, key=lambda v: v.initial.level)  # type: ignore[union-attr]


#: The kind of furniture each articulated kind starts in (:class:`InCabinet`).
FURNITURE_OF = {"drawer": "cabinet", "door": "microwave"}


def gates_of(variables: Sequence[StateVariable]) -> dict[str, list[str]]:
    """Receptacle variable -> the articulated variables that must be open before
    anything goes into it: a drawer is its own gate, a microwave's door gates the
    microwave. The graph's order reads it (:mod:`factask.graph.order`).

    Args:
        variables: A graph's variables.

    Returns:
        The gates of each articulated receptacle (absent: none).
    """
    out: dict[str, list[str]] = {}
    for v in variables:
        if v.kind == "drawer":
            out.setdefault(v.name, []).append(v.name)
        elif v.kind == "door" and isinstance(v.initial, InCabinet):
            out.setdefault(v.initial.cabinet, []).append(v.name)
    return out


def cabinet_problems(variables: Sequence[StateVariable]) -> list[Problem]:
    """What is wrong with the graph's cabinets and drawers: a drawer starts
    ``in_cabinet`` of a cabinet variable (and nothing else does), both stand for one
    object, a cabinet's drawers take its bays 0..n-1 once each, and a drawer's size
    is the one its cabinet gives it (:func:`~factask.vocabulary.kinds.drawer_size`).

    Args:
        variables: A graph's variables.
    """
    out: list[Problem] = _door_problems(variables) + shelf_problems(variables)
    by_name = {v.name: v for v in variables}
    for v in variables:
        placed = isinstance(v.initial, InCabinet)
        if v.kind in ("door", "microwave", "shelf", "shelf_level"):  # their own checks
            continue
        if v.kind == "drawer" and not placed:
            out.append(Problem(v.name, "initial", "a drawer starts in a cabinet",
                               'give initial {"type": "in_cabinet", "cabinet": <a cabinet '
                               'variable>, "level": 0}'))
        if placed and v.kind != "drawer":
            out.append(Problem(v.name, "initial", "only a drawer or a door starts "
                               f"in_cabinet, not a {v.kind}", "start it on the table or "
                               "on/inside another variable"))
        if v.kind in ("drawer", "cabinet"):
            out.extend(_one_object(v))
        if v.kind == "drawer" and not v.is_fixed:
            out.append(Problem(v.name, "fixed", "a drawer slides in its cabinet; it cannot be "
                               "free", "leave fixed out"))
        if placed and v.kind == "drawer":
            host = by_name.get(v.initial.cabinet)  # type: ignore[union-attr]
            if host is not None and host.kind != "cabinet":
                out.append(Problem(v.name, "initial.cabinet", f"{host.name!r} is a "
                                   f"{host.kind}, not a cabinet", "name a cabinet variable"))
    for cab in (v for v in variables if v.kind == "cabinet"):
        drawers = drawers_of(variables, cab.name)
        if not drawers:
            out.append(Problem(cab.name, "kind", "a cabinet holds at least one drawer",
                               'add a drawer variable with initial {"type": "in_cabinet", '
                               f'"cabinet": "{cab.name}", "level": 0}}'))
            continue
        levels = [d.initial.level for d in drawers]  # type: ignore[union-attr]
        if levels != list(range(len(drawers))):
            out.append(Problem(drawers[-1].name, "initial.level", f"the drawers of "
                               f"{cab.name!r} take levels {levels}",
                               f"give its {len(drawers)} drawers levels 0..{len(drawers) - 1}"
                               ", one each"))
            continue
        want = drawer_size(cab.extents, len(drawers))
        for d in drawers:
            if any(abs(a - b) > 1e-6 for a, b in zip(d.extents, want, strict=True)):
                out.append(Problem(d.name, "size", f"a drawer of {cab.name!r} (its "
                                   f"{len(drawers)} drawer(s)) has size "
                                   f"{tuple(round(w, 6) for w in want)}, got {d.extents}",
                                   f"give size {[round(w, 6) for w in want]}"))
    return out


def switches_of(variables: Sequence[StateVariable], host: str) -> list[StateVariable]:
    """The switch variables mounted on ``host`` (:class:`MountedOn`).

    Args:
        variables: A graph's variables.
        host: The switchable fixture variable's name.

    Returns:
        Those switches, in graph order (a valid graph has one).
    """
    return [v for v in variables if isinstance(v.initial, MountedOn) and v.initial.host == host]


def switch_problems(variables: Sequence[StateVariable]) -> list[Problem]:
    """What is wrong with the graph's switches and switchable fixtures: a switch
    starts ``mounted_on`` a switchable fixture (and nothing else does), both stand for
    one object, a host has exactly one switch, and a switch's size is the one its
    host's mount gives it (:func:`~factask.vocabulary.kinds.switch_size`).

    Args:
        variables: A graph's variables.

    Returns:
        The problems, each naming the field and its fix.
    """
    out: list[Problem] = []
    by_name = {v.name: v for v in variables}
    hosts = " or ".join(SWITCH_HOSTS)
    for v in variables:
        mounted = isinstance(v.initial, MountedOn)
        if v.kind == "switch" and not mounted:
            out.append(Problem(v.name, "initial", "a switch is mounted on a switchable fixture",
                               'give initial {"type": "mounted_on", "host": <a ' + hosts
                               + ' variable>}'))
        if mounted and v.kind != "switch":
            out.append(Problem(v.name, "initial", f"only a switch starts mounted_on, not a "
                               f"{v.kind}", "start it on the table or on/inside another "
                               "variable, or make it kind switch"))
        if v.kind == "switch" or v.kind in SWITCH_HOSTS:
            out.extend(_one_object(v))
        if v.kind == "switch" and not v.is_fixed:
            out.append(Problem(v.name, "fixed", "a switch moves only along its button's "
                               "slide; it cannot be free", "leave fixed out"))
        if not (mounted and v.kind == "switch"):
            continue
        host = by_name.get(v.initial.host)  # type: ignore[union-attr]
        if host is None:
            continue  # an unknown variable: the graph's reference check says so
        if host.kind not in SWITCH_HOSTS:
            out.append(Problem(v.name, "initial.host", f"{host.name!r} is a {host.kind}, "
                               "which has no switch", f"name a {hosts} variable"))
            continue
        want = switch_size(host.kind)
        if any(abs(a - b) > 1e-6 for a, b in zip(v.extents, want, strict=True)):
            out.append(Problem(v.name, "size", f"the switch of a {host.kind} has size "
                               f"{want}, got {v.extents}",
                               f"give size {list(want)}"))
    for host in (v for v in variables if v.kind in SWITCH_HOSTS):
        mine = switches_of(variables, host.name)
        if len(mine) != 1:
            out.append(Problem(host.name, "kind", f"a {host.kind} has one switch, got "
                               f"{len(mine)}", 'give it one switch variable with initial '
                               f'{{"type": "mounted_on", "host": "{host.name}"}}'))
    return out


def _door_problems(variables: Sequence[StateVariable]) -> list[Problem]:
    """What is wrong with the graph's microwaves and doors: a door starts
    ``in_cabinet`` of a microwave variable at level 0, a microwave has exactly one
    door, both stand for one object, fixed, and a door's size is the one its
    microwave gives it (:func:`~factask.vocabulary.kinds.door_size`)."""
    out: list[Problem] = []
    by_name = {v.name: v for v in variables}
    for v in variables:
        if v.kind not in ("door", "microwave"):
            continue
        out.extend(_one_object(v))
        if v.kind == "microwave":
            doors = [d for d in variables if d.kind == "door" and isinstance(d.initial, InCabinet)
                     and d.initial.cabinet == v.name]
            if len(doors) != 1:
                out.append(Problem(v.name, "kind", f"a microwave has exactly one door, got "
                                   f"{len(doors)}", 'give it one door variable with initial '
                                   f'{{"type": "in_cabinet", "cabinet": "{v.name}"}}'))
            continue
        if not v.is_fixed:
            out.append(Problem(v.name, "fixed", "a door swings on its microwave's hinge; it "
                               "cannot be free", "leave fixed out"))
        if not isinstance(v.initial, InCabinet):
            out.append(Problem(v.name, "initial", "a door starts on a microwave",
                               'give initial {"type": "in_cabinet", "cabinet": <a microwave '
                               'variable>}'))
            continue
        host = by_name.get(v.initial.cabinet)
        if v.initial.level != 0:
            out.append(Problem(v.name, "initial.level", f"a door has no level, got "
                               f"{v.initial.level}", "leave level out (0)"))
        if host is not None and host.kind != "microwave":
            out.append(Problem(v.name, "initial.cabinet", f"{host.name!r} is a {host.kind}, "
                               "not a microwave", "name a microwave variable"))
        elif host is not None:
            want = door_size(host.extents)
            if any(abs(a - b) > 1e-6 for a, b in zip(v.extents, want, strict=True)):
                out.append(Problem(v.name, "size", f"the door of {host.name!r} has size "
                                   f"{tuple(round(w, 6) for w in want)}, got {v.extents}",
                                   f"give size {[round(w, 6) for w in want]}"))
    return out


def shelf_problems(variables: Sequence[StateVariable]) -> list[Problem]:
    """What is wrong with the graph's shelves and their levels: a level starts
    ``in_cabinet`` of a shelf variable, not opened, both stand for one fixed object,
    a shelf's levels take levels 0..n-1 once each (at most
    :data:`~factask.vocabulary.kinds.MAX_SHELF_LEVELS`), and a level's size is the
    one its shelf gives it (:func:`~factask.vocabulary.kinds.shelf_level_size`).

    Args:
        variables: A graph's variables.

    Returns:
        The problems, each naming the field and its fix.
    """
    out: list[Problem] = []
    by_name = {v.name: v for v in variables}
    for v in variables:
        if v.kind not in ("shelf", "shelf_level"):
            continue
        out.extend(_one_object(v))
        if not v.is_fixed:
            out.append(Problem(v.name, "fixed", f"a {v.kind} stands fixed on the table; it "
                               "cannot be free", "leave fixed out"))
        if v.kind == "shelf":
            continue
        if not isinstance(v.initial, InCabinet):
            out.append(Problem(v.name, "initial", "a shelf level starts in a shelf",
                               'give initial {"type": "in_cabinet", "cabinet": <a shelf '
                               'variable>, "level": 0}'))
            continue
        if v.initial.opening != 0:
            out.append(Problem(v.name, "initial.opening", "a shelf level does not open, got "
                               f"opening {v.initial.opening}", "leave opening out (0)"))
        host = by_name.get(v.initial.cabinet)
        if host is not None and host.kind != "shelf":
            out.append(Problem(v.name, "initial.cabinet", f"{host.name!r} is a {host.kind}, "
                               "not a shelf", "name a shelf variable"))
    for shelf in (v for v in variables if v.kind == "shelf"):
        levels = [lv for lv in drawers_of(variables, shelf.name) if lv.kind == "shelf_level"]
        if not levels:
            out.append(Problem(shelf.name, "kind", "a shelf has at least one level",
                               'add a shelf_level variable with initial {"type": '
                               f'"in_cabinet", "cabinet": "{shelf.name}", "level": 0}}'))
            continue
        taken = [lv.initial.level for lv in levels]  # type: ignore[union-attr]
        if taken != list(range(len(levels))):
            out.append(Problem(levels[-1].name, "initial.level", f"the levels of "
                               f"{shelf.name!r} take levels {taken}",
                               f"give its {len(levels)} levels levels 0.."
                               f"{len(levels) - 1}, one each (at most {MAX_SHELF_LEVELS})"))
            continue
        for lv in levels:
            want = shelf_level_size(shelf.extents, len(levels), lv.initial.level)  # type: ignore[union-attr]
            if any(abs(a - b) > 1e-6 for a, b in zip(lv.extents, want, strict=True)):
                out.append(Problem(lv.name, "size", f"level {lv.initial.level} of "  # type: ignore[union-attr]
                                   f"{shelf.name!r} (of {len(levels)}) has size "
                                   f"{tuple(round(w, 6) for w in want)}, got {lv.extents}",
                                   f"give size {[round(w, 6) for w in want]}"))
    return out
