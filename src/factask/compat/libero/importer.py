"""A LIBERO BDDL problem → a factask task graph: :func:`import_libero`.

What is taken in (everything else is a :class:`LiberoUnsupported` naming the
predicate or object and why):

* Every object becomes one state variable (its LIBERO name made snake_case), its
  kind, size and colour from :data:`~factask.compat.libero.kinds.LIBERO_KINDS`.
  Fixtures with a stand-in (stove, cabinet, wine rack) become fixed variables;
  the table and the floor are factask's table.
* ``:init``: ``(On obj <table>_<region>)`` → an :class:`InRegion` start around the
  region's centre (see the coordinate map below); a fixture's own ``On`` → its
  fixed pose (:class:`AtFixedPose`, yaw the middle of its ``yaw_rotation``);
  ``(On obj other)`` → :class:`StartOn` (:class:`StartInside` when ``other`` is a
  receptacle the object fits in); ``(On obj <fixture>_<top region>)`` → on the
  fixture's stand-in; ``(In obj <receptacle>_<region>)`` → :class:`StartInside`.
* ``:goal``: ``(On a b)`` → ``on`` when ``b`` is a support, ``inside`` when it is a
  receptacle; ``(In a <receptacle>_<region>)`` → ``inside``; ``(On a <fixture>_<top
  region>)`` → ``on`` the fixture, ``(In a <fixture>_<inside region>)`` →
  ``inside`` it (the region's role: :func:`~factask.compat.libero.kinds.region_role`;
  a region behind a door or a side face is refused);
  ``(On a <shelf>_<level region>)`` → ``on`` that level of the stepped shelf
  (:mod:`factask.compat.libero.articulated`), in ``:init`` a start on it;
  ``(On a <table>_<region>)`` → ``in_zone`` of a goal zone made for the region
  (:meth:`_Importer.goal_zone`). A stand-in fixed by default that a goal moves
  becomes movable; a goal that moves a fixture is refused.
* Articulated fixtures (:mod:`factask.compat.libero.articulated`): a cabinet's
  drawers, a microwave's hinged door and a stove's switch are variables of their
  own; ``Open`` / ``Close`` / ``Turnon`` / ``Turnoff`` are ``open`` / ``closed`` /
  ``switched_on`` / ``switched_off`` of them; ``In`` a drawer region or a
  microwave's ``heating_region`` is ``inside`` it, after an ``open`` milestone where
  it starts shut. Other moving parts are refused.
* The language line is the description; the task's name is the file's name.

Coordinate map (one for every file). LIBERO's table frame has x forward away from
the robot, y to the left, the origin at the table's centre and the robot's base at
about x = -0.66 m; factask's robot base is the origin and the workspace is x 0.25
to 0.75, y -0.5 to 0.5. The shipped files' region centres span x -0.42 to 0.21
(0.63 m, more than the workspace's 0.5 m depth), so the map scales uniformly:
``x' = OFFSET_X + SCALE * x``, ``y' = SCALE * y`` with ``SCALE = 0.75`` and
``OFFSET_X = 0.58`` (x -0.42 → 0.265, 0.21 → 0.7375); the living room's and the
coffee table's 0.70 m deep tables, whose centre is nearer LIBERO's robot, use
``OFFSET_X = 0.50`` (:data:`LOW_TABLE_OFFSET_X`). Objects keep their real
sizes, so the scene is more crowded than LIBERO's: LIBERO's 2 cm (5 cm on the
floor) start regions are widened to :data:`MIN_REGION` square around their centre
(:data:`START_SLACK` more than the object's larger side where that is larger),
clipped to the workspace, which gives the layout sampler room. A fixture's centre
is moved in so that its whole footprint is on the workspace.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from factask.compat.libero.articulated import WHAT_FACTASK_MODELS, ArticulatedParts
from factask.compat.libero.bddl import load_bddl
from factask.compat.libero.kinds import (
    LiberoKind,
    LiberoUnsupported,
    UnknownLiberoRegion,
    libero_kind,
    region_role,
    scene_of,
)
from factask.compat.libero.model import BddlProblem, Predicate, Region
from factask.graph import TaskGraph, parse_graph
from factask.vocabulary.kinds import WALL_THICKNESS, kind_spec
from factask.vocabulary.names import slugify, unique_name
from factask.vocabulary.world import WORKSPACE_X, WORKSPACE_Y

#: Uniform scale of LIBERO's table frame into factask's (see the module's docstring).
SCALE = 0.75
#: factask x of LIBERO's table centre (metres).
OFFSET_X = 0.58
#: factask x of the centre of the living room's and the coffee table scene's
#: 0.70 m deep tables: LIBERO's robot stands 0.51 m behind their centre (0.66 m
#: behind the 1.0 m deep tables'), and their whole depth maps to x 0.24 to 0.76.
LOW_TABLE_OFFSET_X = 0.50
#: Scenes whose table centre is :data:`LOW_TABLE_OFFSET_X`.
LOW_TABLE_SCENES = frozenset({"living_room_table", "coffee_table"})
#: factask y of LIBERO's table centre (metres).
OFFSET_Y = 0.0
#: Side (metres) of the square start region an object's LIBERO region is widened to.
MIN_REGION = 0.20
#: ... or to the object's larger side plus this (metres), if that is larger: a 16 cm
#: plate in a 20 cm square has 4 cm to move in, too little beside a fixture.
START_SLACK = 0.10
#: A goal zone (a goal on a bare table region) is at least the object's larger side
#: plus this (metres): factask's region check wants the whole footprint inside, LIBERO's
#: the object's centre, so a 6 cm region gets a zone a 16 cm plate fits in.
ZONE_MARGIN = 0.03
#: Room (m) an object's footprint circle keeps inside a round receptacle's inner
#: circle for it to count as fitting (the layout keeps objects off the walls).
ROUND_FIT_MARGIN = 0.005
#: Colour of the goal zones made from table regions.
ZONE_COLOR = "gray"
#: Why a region of each refused role is refused.
_WHY_ROLE = {"door": "behind a door factask does not model",
             "side": "a side face of it: no factask relation puts things against a side",
             "open_top": "the top of factask's microwave, which is open at the top (no "
                         "roof, so that top-down cups put things in): nothing stands on "
                         "it"}


@dataclass(frozen=True)
class LiberoImport:
    """What :func:`import_libero` made.

    Attributes:
        graph: The validated task graph.
        warnings: What was approximated, one line each.
        names: LIBERO name → factask variable, for every object and fixture that
            became a variable.
        problem: The BDDL problem it came from.
    """

    graph: TaskGraph
    warnings: list[str] = field(default_factory=list)
    names: dict[str, str] = field(default_factory=dict)
    problem: BddlProblem | None = None


def to_factask_xy(x: float, y: float, offset_x: float = OFFSET_X) -> tuple[float, float]:
    """A point of LIBERO's table frame in factask's frame (metres).

    Args:
        x: LIBERO x (away from the robot), metres from the table's centre.
        y: LIBERO y (to the robot's left).
        offset_x: factask x of the table's centre (the scene's: :data:`OFFSET_X`, or
            :data:`LOW_TABLE_OFFSET_X` for the living room's and coffee table's).

    Returns:
        The point (x, y) in factask's frame.
    """
    return offset_x + SCALE * x, OFFSET_Y + SCALE * y


def _clip(lo: float, hi: float, bounds: tuple[float, float]) -> tuple[float, float]:
    lo, hi = max(lo, bounds[0]), min(hi, bounds[1])
    return lo, hi


class _Importer(ArticulatedParts):
    def __init__(self, problem: BddlProblem, name: str) -> None:
        self.p, self.task = problem, name
        self.types: dict[str, str] = {**problem.fixtures, **problem.objects}
        self.specs: dict[str, LiberoKind] = {n: libero_kind(t, n) for n, t in self.types.items()}
        self.warnings: list[str] = []
        self.plain_where_unused()
        taken: set[str] = set()
        self.names = {n: unique_name(slugify(n, "_", 64, "obj"), taken)
                      for n, s in self.specs.items() if s.kind is not None}
        self.initial: dict[str, dict[str, Any]] = {}
        #: Goal zones made from table regions (variables of their own).
        self.zones: list[dict[str, Any]] = []
        self.taken_names = set(self.names.values())
        #: Objects whose stand-in is fixed but that a goal moves: made movable.
        self.moved: set[str] = set()
        self.setup_parts()
        scene = scene_of(problem.name)
        if scene is None:
            self.warnings.append(f"problem {problem.name!r} is no LIBERO scene factask "
                                 "knows; read as a tabletop scene")
        #: factask x of the scene's table centre.
        self.offset_x = (LOW_TABLE_OFFSET_X if scene is not None
                         and scene.table in LOW_TABLE_SCENES else OFFSET_X)

    def is_fixture(self, name: str) -> bool:
        """A fixture: declared under ``:fixtures`` or of a fixture type."""
        return name in self.p.fixtures or (name in self.specs and self.specs[name].fixture)

    def region_host(self, pred: Predicate, region: Region) -> tuple[str, str] | None:
        """What a fixture's or object's own region means, by its role
        (:func:`~factask.compat.libero.kinds.region_role`): ``("on", variable)`` for
        its top, ``("inside", variable)`` for its inside; None for an object's region
        no rule types (the object itself is then the host).

        Raises:
            LiberoUnsupported: the region is behind a door, a
                side, or a fixture's region no rule types (:class:`UnknownLiberoRegion`).
        """
        target = region.target
        if target not in self.specs:
            raise self.refuse(pred, f"{region.full_name}: its target {target!r} is no "
                              "declared object or fixture")
        spec, type_name = self.specs[target], self.types[target]
        role = region_role(spec, region.name)
        if role == "top":
            return "on", self.names[target]
        if role == "inside":
            if not kind_spec(spec.kind or "").receptacle:
                raise self.refuse(pred, f"{region.full_name} is inside the {type_name}, "
                                  f"whose stand-in (a {spec.kind}) holds nothing")
            if region.name != "contain_region" and spec.kind != "microwave":
                self.warnings.append(f"{region.full_name}: a compartment of the {type_name}; "
                                     f"factask's stand-in has one inside: inside {target}")
            return "inside", self.names[target]
        if role is not None:
            raise self._refuse_role(pred, region, role, type_name, spec)
        if not self.is_fixture(target):
            return None
        known = ([r for r, _ in spec.regions] + list(spec.drawers)
                 + [r for r, _ in spec.levels])
        raise UnknownLiberoRegion(
            f"{self.where}: {pred}: region {region.name!r} of the {type_name} "
            f"({region.full_name}) is no region factask knows for this type (known: "
            f"{', '.join(known) or 'none'})")

    def _refuse_role(self, pred: Predicate, region: Region, role: str, type_name: str,
                     spec: LiberoKind) -> LiberoUnsupported:
        why = _WHY_ROLE[role]
        if role == "door" and spec.articulation:
            why = (f"behind the {type_name}'s {spec.articulation}, not modelled; "
                   f"{WHAT_FACTASK_MODELS}")
        return self.refuse(pred, f"{region.full_name} is {why}")

    # ---- what a name is -------------------------------------------------------------
    def is_table(self, name: str) -> bool:
        return name in self.specs and self.specs[name].kind is None

    def variable(self, name: str, pred: Predicate) -> str:
        if name not in self.names:
            raise self.refuse(pred, f"{name!r} is no object factask models")
        return self.names[name]

    def host_kind(self, name: str) -> str | None:
        spec = self.specs.get(name)
        return spec.kind if spec else None

    def fits_inside(self, obj: str, host: str) -> bool:
        """``obj``'s footprint fits inside ``host``'s walls (a round host: the
        footprint's circumscribed circle inside its inner circle)."""
        o, h = self.specs[obj].size, self.specs[host].size
        assert o is not None and h is not None
        inner = sorted((h[0] - 2 * WALL_THICKNESS, h[1] - 2 * WALL_THICKNESS))
        if kind_spec(self.host_kind(host) or "").round:
            own = o[0] / 2 if kind_spec(self.specs[obj].kind or "").round else math.hypot(
                o[0] / 2, o[1] / 2)
            return own + ROUND_FIT_MARGIN <= inner[0] / 2
        return all(a <= b for a, b in zip(sorted(o[:2]), inner, strict=True))

    # ---- init -----------------------------------------------------------------------
    def read_init(self) -> None:
        for pred in self.p.init:
            if self.read_part_init(pred):
                continue
            if pred.name not in ("on", "in") or len(pred.args) != 2:
                raise self.refuse(pred, "no factask start placement for this predicate")
            obj, host = (str(a) for a in pred.args)
            if self.is_table(obj):
                continue
            var = self.variable(obj, pred)
            self.initial[var] = self.start_of(pred, obj, host)
        for libero, var in self.names.items():
            if var not in self.initial:
                self.warnings.append(f"{libero}: no start in :init; starts anywhere on "
                                     "the table")

    def start_of(self, pred: Predicate, obj: str, host: str) -> dict[str, Any]:
        fixture = self.is_fixture(obj)
        if self.is_table(host):
            return {"type": "table"}
        if host in self.drawers:
            return {"type": "inside", "container": self.drawers[host][0]}
        if host in self.levels:
            return {"type": "on", "support": self.levels[host][0]}
        region = self.p.regions_by_full_name.get(host)
        if region is not None:
            if self.is_table(region.target):
                return self.table_start(pred, region, obj, fixture)
            hosted = self.region_host(pred, region)
            if hosted is not None:
                relation, var = hosted
                if relation == "on":
                    return {"type": "on", "support": var}
                if self.fits_inside(obj, region.target):
                    return {"type": "inside", "container": var}
                raise self.refuse(pred, f"{obj} does not fit inside {region.target}")
            host = region.target
        if host not in self.names:
            raise self.refuse(pred, f"{host!r} is no object or region factask models")
        spec = kind_spec(self.host_kind(host) or "")
        if spec.receptacle and self.fits_inside(obj, host):
            return {"type": "inside", "container": self.names[host]}
        if spec.support and pred.name == "on":
            return {"type": "on", "support": self.names[host]}
        raise self.refuse(pred, f"{obj} cannot start {pred.name} {host} (a "
                          f"{self.host_kind(host)} stand-in): an object resting on a "
                          "receptacle it does not fit in is not modelled")

    def table_start(self, pred: Predicate, region: Region, obj: str,
                    fixture: bool) -> dict[str, Any]:
        if not region.ranges:
            raise self.refuse(pred, f"table region {region.full_name} has no ranges")
        x0, y0, x1, y1 = region.ranges[0]
        cx, cy = to_factask_xy((x0 + x1) / 2, (y0 + y1) / 2, self.offset_x)
        size = self.specs[obj].size
        assert size is not None
        if fixture:
            yaw = (math.degrees(sum(region.yaw_rotation[0]) / 2)
                   if region.yaw_rotation else 0.0)
            if self.faces_robot(obj):
                # factask's cabinet, microwave and stove have their moving part on
                # their -x side: turned to face the robot whatever LIBERO's yaw (its
                # cabinet model's front is its own +x).
                yaw = 0.0
            turned = round(abs(math.sin(math.radians(yaw)))) == 1  # a quarter turn
            half_x, half_y = (size[1], size[0]) if turned else (size[0], size[1])
            x = min(max(cx, WORKSPACE_X[0] + half_x / 2), WORKSPACE_X[1] - half_x / 2)
            x = self.room_in_front(obj, size, x)
            if self.specs[obj].levels and abs(x - cx) > 1e-3:
                self.warnings.append(f"{obj}: the stepped shelf ({size[0] * 100:.0f} cm "
                                     f"deep) moved from x {cx:.3f} to {x:.3f} m so that "
                                     "its whole footprint is on the workspace")
            y = min(max(cy, WORKSPACE_Y[0] + half_y / 2), WORKSPACE_Y[1] - half_y / 2)
            return {"type": "pose", "x": round(x, 4), "y": round(y, 4),
                    "yaw_deg": round(yaw, 3)}
        least = max(MIN_REGION, max(size[0], size[1]) + START_SLACK)
        half_x = max(SCALE * abs(x1 - x0), least) / 2
        half_y = max(SCALE * abs(y1 - y0), least) / 2
        return {"type": "region",
                "x": [round(v, 4) for v in _clip(cx - half_x, cx + half_x, WORKSPACE_X)],
                "y": [round(v, 4) for v in _clip(cy - half_y, cy + half_y, WORKSPACE_Y)]}

    # ---- goal -----------------------------------------------------------------------
    def read_goal(self) -> list[dict[str, Any]]:
        factors: list[dict[str, Any]] = []
        taken: set[str] = set()
        for pred in self.p.goal:
            part = self.part_goal(pred, taken)
            if part is not None:
                factors.append(part)
                continue
            if pred.name not in ("on", "in") or len(pred.args) != 2:
                raise self.refuse(pred, "no factask relation for this goal predicate")
            obj, host = (str(a) for a in pred.args)
            var = self.variable(obj, pred)
            goal = self.goal_of(pred, var, host)
            self.check_fits(pred, obj, goal)
            if self.is_fixture(obj):
                raise self.refuse(pred, f"{obj} is a fixture (a {self.specs[obj].kind} "
                                  "stand-in fixed to the table); no goal may move it")
            if self.specs[obj].fixed:
                self.moved.add(var)
                self.warnings.append(f"{obj}: its stand-in is fixed by default; a goal moves "
                                     "it, so it is movable here")
            word = "in" if goal["type"] in ("inside", "in_zone") else "on"
            target = goal.get("container", goal.get("support", goal.get("zone")))
            name = unique_name(slugify(f"put {var} {word} {target}", "_", 64, "goal"), taken)
            factors.append({"name": name, "description": f"LIBERO goal {pred}", "goal": goal})
        self.open_before_putting_inside(factors, taken)
        for f in factors:
            f["weight"] = 1.0 / len(factors)
        return factors

    def check_fits(self, pred: Predicate, obj: str, goal: dict[str, Any]) -> None:
        """Refuse a goal that puts ``obj`` inside a stand-in it does not fit in (a
        butter pack in a bowl, a bowl stacked on a bowl of its size): factask's
        ``inside`` needs the whole footprint inside the walls (drawers are sized for
        what LIBERO puts in them and not checked here)."""
        if goal["type"] != "inside":
            return
        host = next((n for n, v in self.names.items() if v == goal["container"]), None)
        if host is None or self.fits_inside(obj, host):
            return
        raise self.refuse(pred, f"{obj} does not fit inside {host} (a "
                          f"{self.host_kind(host)} stand-in) and cannot rest on it: an "
                          "object resting on a receptacle it does not fit in is not "
                          "modelled")

    def goal_of(self, pred: Predicate, var: str, host: str) -> dict[str, Any]:
        if host in self.drawers:  # In / On a cabinet's drawer region: inside the drawer
            return {"type": "inside", "objects": [var], "container": self.drawers[host][0]}
        if host in self.levels:  # On / In a shelf's level region: on the level
            return {"type": "on", "objects": [var], "support": self.levels[host][0]}
        region = self.p.regions_by_full_name.get(host)
        if region is not None:
            if self.is_table(region.target):
                if pred.name != "on":
                    raise self.refuse(pred, f"{host} is a place on the table: nothing is "
                                      "in it, an object is on it")
                return {"type": "in_zone", "objects": [var],
                        "zone": self.goal_zone(pred, region, pred.args[0])}
            hosted = self.region_host(pred, region)
            if hosted is not None:
                relation, target = hosted
                if relation == "on":
                    return {"type": "on", "objects": [var], "support": target}
                return {"type": "inside", "objects": [var], "container": target}
            host = region.target
        if self.is_table(host) or host not in self.names:
            raise self.refuse(pred, f"{host!r} is no object factask models")
        spec = kind_spec(self.host_kind(host) or "")
        if spec.receptacle:
            return {"type": "inside", "objects": [var], "container": self.names[host]}
        if spec.support and pred.name == "on":
            return {"type": "on", "objects": [var], "support": self.names[host]}
        raise self.refuse(pred, f"{host} (a {self.host_kind(host)} stand-in) is neither a "
                          "support nor a receptacle")

    def goal_zone(self, pred: Predicate, region: Region, obj: str) -> str:
        """A zone variable marking table region ``region`` (made once per region): at
        the region's mapped centre, as large as the mapped region or as the object's
        larger side plus :data:`ZONE_MARGIN`, whichever is larger."""
        name = slugify(region.name, "_", 64, "zone")
        for zone in self.zones:
            if zone["libero"] == region.full_name:
                return str(zone["name"])
        if not region.ranges:
            raise self.refuse(pred, f"table region {region.full_name} has no ranges")
        x0, y0, x1, y1 = region.ranges[0]
        cx, cy = to_factask_xy((x0 + x1) / 2, (y0 + y1) / 2, self.offset_x)
        size = self.specs[str(obj)].size
        assert size is not None
        least = max(size[0], size[1]) + ZONE_MARGIN
        sx, sy = max(SCALE * abs(x1 - x0), least), max(SCALE * abs(y1 - y0), least)
        if sx > SCALE * abs(x1 - x0) + 1e-9 or sy > SCALE * abs(y1 - y0) + 1e-9:
            self.warnings.append(
                f"{region.full_name}: the goal zone is {sx * 100:.0f} x {sy * 100:.0f} cm "
                f"(the region maps to {SCALE * abs(x1 - x0) * 100:.0f} x "
                f"{SCALE * abs(y1 - y0) * 100:.0f} cm) so that {obj} fits in it whole")
        var = unique_name(name, self.taken_names)
        self.zones.append({
            "libero": region.full_name, "name": var, "kind": "zone",
            "size": [round(sx, 4), round(sy, 4), 0.001], "color": ZONE_COLOR,
            "initial": {"type": "pose",
                        "x": round(min(max(cx, WORKSPACE_X[0]), WORKSPACE_X[1]), 4),
                        "y": round(min(max(cy, WORKSPACE_Y[0]), WORKSPACE_Y[1]), 4),
                        "yaw_deg": 0.0},
            "description": f"goal zone: LIBERO table region {region.full_name}"})
        return var

    # ---- the graph ------------------------------------------------------------------
    def variables(self) -> list[dict[str, Any]]:
        out = []
        for libero, var in self.names.items():
            spec = self.specs[libero]
            data: dict[str, Any] = {
                "name": var, "kind": spec.kind, "size": list(spec.size or ()),
                "color": spec.color, "initial": self.initial.get(var, {"type": "table"}),
                "description": f"{spec.note} (LIBERO {libero} of type {self.types[libero]})"}
            if var in self.moved:
                data["fixed"] = False
            elif libero in self.p.fixtures:
                data["fixed"] = True
            elif spec.fixed is not None:
                data["fixed"] = spec.fixed
            out.append(data)
        out.extend(self.part_variables())
        out.extend({k: v for k, v in zone.items() if k != "libero"} for zone in self.zones)
        return out

    def build(self) -> LiberoImport:
        self.read_init()
        factors = self.read_goal()
        description = self.p.language or f"LIBERO task {self.task}"
        graph = parse_graph({"name": self.task, "description": description,
                             "variables": self.variables(), "factors": factors})
        return LiberoImport(graph.ensure_valid(), self.warnings, dict(self.names), self.p)


def import_libero(source: str | Path | BddlProblem, name: str | None = None) -> LiberoImport:
    """Import a LIBERO BDDL task as a factask task graph.

    Args:
        source: A ``.bddl`` file, or a problem already read.
        name: The task's name (default: the file's name, kebab-case).

    Returns:
        The graph, the warnings and the LIBERO → factask name map.

    Raises:
        BddlError: the file cannot be read as BDDL.
        LiberoUnsupported: the task uses what factask does not model (an articulated
            fixture, a fixture's region in the goal, an unknown type).
        GraphValidationError: the graph made is not valid (a bug of the mapping).
    """
    problem = source if isinstance(source, BddlProblem) else load_bddl(source)
    stem = Path(problem.source).stem if problem.source != "<string>" else problem.name
    task = name or slugify(stem, "-", 100, "libero-task", letter_first=False)
    return _Importer(problem, task).build()
