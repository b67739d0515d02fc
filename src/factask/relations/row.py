"""``row``: objects side by side in a straight line (free, along a line, or on a row)."""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Annotated, Any, ClassVar, Literal

import numpy as np
from pydantic import Field

from factask.geometry import Pose, wrap_angle
from factask.relations.base import RelationBase
from factask.relations.solving import (
    Infeasible,
    Plan,
    SolveContext,
    SolvedFactor,
    make_plan,
    same_variable,
)
from factask.relations.status import CheckScene, Verdict, check_slots
from factask.scene.collision import CLEARANCE, TABLE
from factask.scene.objects import (
    GEOMETRY_EPS,
    Area,
    SceneObject,
    corner_arm_width,
    corner_vertex,
    group_area,
    placement_area,
    principal_yaw,
    rest_surface_z,
    resting_pose,
    yaw_rotation_2d,
)
from factask.vocabulary.errors import Problem
from factask.vocabulary.names import Name
from factask.vocabulary.world import TABLE_Z, WORKSPACE_DIAGONAL

if TYPE_CHECKING:  # the graph model sits above the relations (it imports their schemas)
    from factask.vocabulary.variables import StateVariable

#: Extra gap in a row with no explicit spacing: widest object + this (metres).
ROW_GAP = 0.01
#: The marker kind a row may run along the arm of.
CORNER_KIND = "corner"

#: Builds a row's plan: (centre, yaw, surface, hosts) -> the plan.
LineBuilder = Callable[[np.ndarray, float, float, list[str]], Plan]


class Row(RelationBase):
    """Place the objects side by side in a straight row, centre-to-centre
    ``spacing`` metres apart (default: widest object + 1 cm). ``along``: lie on
    that line/zone variable; or, a corner marker: along its longer arm, first
    object at the corner's vertex; or, a list of two variables: on the table in
    the gap between them, first object nearest the first. ``on``: rest on top of
    the row below, made of the instances of variable ``on`` or of a list of
    variables (a layer of mixed colours): same count: one on each; one fewer:
    each bridging two neighbours, as in a pyramid; fewer still: centred on it."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {
        "along": ("region",), "on": ("support",)}
    anchor_kinds: ClassVar[Mapping[str, tuple[str, ...]]] = {"along": (CORNER_KIND,)}

    type: Literal["row"] = "row"
    spacing: Annotated[float, Field(gt=0, le=0.5, allow_inf_nan=False)] | None = None
    along: Name | Annotated[list[Name], Field(min_length=1, max_length=2)] | None = None
    on: Name | Annotated[list[Name], Field(min_length=1, max_length=16)] | None = None
    ordered: bool = True

    def problems(self, factor: str, variables: Mapping[str, StateVariable]) -> list[Problem]:
        """Beyond the anchors' kinds: no name twice in ``on`` or ``along``, and no
        corner among two variables a row runs between."""
        out = super().problems(factor, variables)
        for fname in ("on", "along"):
            names = self.anchor_names(fname)
            for name in dict.fromkeys(n for n in names if names.count(n) > 1):
                out.append(Problem(factor, f"goal.{fname}", f"{name!r} listed twice",
                                   "list it once"))
        pair = self.anchor_names("along")
        for name in pair if len(pair) == 2 else []:
            v = variables.get(name)
            if v is not None and v.kind == CORNER_KIND:
                out.append(Problem(factor, "goal.along", f"{name!r} is a corner: a row runs "
                                   "between two regions, or along one corner",
                                   "give the corner alone"))
        return out

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], Row]:
        return ([{"name": "blocks", "kind": "block", "count": 3, "color": "yellow"}],
                cls(objects=["blocks"]))

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        """A row runs along its yaw, first object at the -x end."""
        n = len(movers)
        matches = same_variable(movers) if self.ordered else np.ones((n, n), dtype=bool)
        spacing = self.spacing or (max(o.size[0] for o in movers) + ROW_GAP)

        def line(centre: np.ndarray, yaw: float, surface: float, hosts: list[str]) -> Plan:
            d = yaw_rotation_2d(yaw) @ np.array([1.0, 0.0])
            slots = [resting_pose(o, *(centre + (k - (n - 1) / 2) * spacing * d), surface, yaw)
                     for k, o in enumerate(movers)]
            return make_plan(slots, [surface] * n, [hosts[0] if hosts else TABLE] * n,
                             [set(hosts)] * n, matches)

        if self.on:
            below = [i for v in self.anchor_names("on") for i in ctx.inst(v)]
            bobjs = [ctx.objs[b] for b in below]
            bposes = [ctx.current[b] for b in below]
            centres = np.array([p.pos[:2] for p in bposes])
            yaw = principal_yaw(centres) if len(below) > 1 else bposes[0].yaw
            d = yaw_rotation_2d(yaw) @ np.array([1.0, 0.0])
            order = list(np.argsort(centres @ d, kind="stable"))
            tops = [rest_surface_z(bobjs[i], bposes[i]) for i in order]
            names = [below[i] for i in order]
            pts = [centres[i] for i in order]
            if len(below) == n:
                spots = list(zip(pts, tops, [[b] for b in names], strict=True))
            elif len(below) == n + 1:
                spots = [((pts[k] + pts[k + 1]) / 2, max(tops[k], tops[k + 1]),
                          [names[k], names[k + 1]]) for k in range(n)]
            else:
                plan = line(centres.mean(axis=0), yaw, max(tops), names)
                areas = {b: placement_area(ctx.objs[b], ctx.current[b]) for b in names}
                for j, (o, slot) in enumerate(zip(movers, plan.slots, strict=True)):
                    under = [b for b, a in areas.items() if bool(a.contains(slot.pos[:2]).all())]
                    if not under:
                        raise Infeasible(f"a row of {n} on the {len(below)} object(s) of "
                                         f"{self.on!r} leaves {o.name} unsupported (use as "
                                         "many objects as below, or fewer)", retry=False)
                    plan.supports[j] = under[0]
                return plan
            slots = [resting_pose(o, *c, s, yaw) for o, (c, s, _) in zip(movers, spots,
                                                                          strict=True)]
            return make_plan(slots, [s for _, s, _ in spots], [h[0] for _, _, h in spots],
                             [set(h) for _, _, h in spots], matches)
        narrowest = min(o.size[0] for o in movers)
        if n > 1 and spacing + GEOMETRY_EPS < narrowest:  # neighbours would overlap
            raise Infeasible(f"a row spaced {spacing:.3f} m is narrower than its objects "
                             f"({narrowest:.3f} m along the row): neighbours would overlap "
                             "(use a spacing of at least the objects' width)", retry=False)
        guide = self.anchor_names("along")
        if len(guide) == 2:
            return _between(ctx, movers, line, guide, spacing)
        if guide:
            host = ctx.inst(guide[0])[0]
            hobj, hpose = ctx.objs[host], ctx.current[host]
            if hobj.kind == CORNER_KIND:
                return _along_corner(movers, line, host, hobj, hpose, spacing)
            yaw = hpose.yaw if hobj.size[0] >= hobj.size[1] else hpose.yaw + math.pi / 2
            # A line looks the same turned half a turn: take the direction pointing to
            # +x (as principal_yaw does), so "first object" means the same end always.
            yaw = wrap_angle(yaw)
            if yaw > math.pi / 2 + GEOMETRY_EPS:
                yaw -= math.pi
            elif yaw <= -math.pi / 2 + GEOMETRY_EPS:
                yaw += math.pi
            plan = line(hpose.pos[:2], yaw, rest_surface_z(hobj, hpose), [host])
            area = placement_area(hobj, hpose)
            for slot in plan.slots:
                if not bool(area.contains(slot.pos[:2]).all()):
                    raise Infeasible(f"a row of {n} spaced {spacing:.3f} m is longer than "
                                     f"{self.along!r}", retry=False)
            return plan
        length = (n - 1) * spacing + max(max(o.size[:2]) for o in movers)
        if length > WORKSPACE_DIAGONAL:  # necessary: a free row fits the workspace
            raise Infeasible(f"a row of {n} spaced {spacing:.3f} m is {length:.2f} m long; "
                             f"the longest line in the workspace is {WORKSPACE_DIAGONAL:.2f} m",
                             retry=False)
        return ctx.search(movers, lambda xy, yaw: line(xy, yaw, TABLE_Z, []),
                          f"a row of {n}")

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        return check_slots(solved, scene, self.tolerances)


def _reach(area: Area, direction: np.ndarray) -> float:
    """How far ``area`` reaches from its centre along the unit vector ``direction``."""
    if area.round:
        return float(area.half[0])
    axes = yaw_rotation_2d(area.yaw)
    return float(abs(direction @ axes[:, 0]) * area.half[0] +
                 abs(direction @ axes[:, 1]) * area.half[1])


def _footprint(ctx: SolveContext, var: str) -> Area:
    """The outer footprint of an anchor variable (the rectangle covering its instances)."""
    hosts = ctx.inst(var)
    objs, poses = [ctx.objs[h] for h in hosts], [ctx.current[h] for h in hosts]
    if len(hosts) == 1:
        return Area(poses[0].pos[:2].copy(), poses[0].yaw, objs[0].half_xy, objs[0].is_round)
    return group_area(objs, poses)


def _between(ctx: SolveContext, movers: list[SceneObject], line: LineBuilder,
             pair: list[str], spacing: float) -> Plan:
    """A row on the table in the gap between two anchors, on the line joining their
    centres, centred in the gap, first object nearest ``pair[0]``.

    Raises:
        Infeasible: the anchors overlap, or the row is longer than the gap.
    """
    first, second = (_footprint(ctx, v) for v in pair)
    u = second.center - first.center
    dist = float(np.linalg.norm(u))
    if dist < GEOMETRY_EPS:
        raise Infeasible(f"{pair[0]!r} and {pair[1]!r} have the same centre: no gap between "
                         "them", retry=False)
    u = u / dist
    lo, hi = _reach(first, u), dist - _reach(second, u)
    n = len(movers)
    length = (n - 1) * spacing + 2 * max(float(o.half_xy[0]) for o in movers) + 2 * CLEARANCE
    if hi - lo < length - GEOMETRY_EPS:
        raise Infeasible(f"a row of {n} spaced {spacing:.3f} m needs {length:.3f} m between "
                         f"{pair[0]!r} and {pair[1]!r}; the gap is {max(hi - lo, 0.0):.3f} m",
                         retry=False)
    return line(first.center + u * (lo + hi) / 2, math.atan2(u[1], u[0]), TABLE_Z, [])


def _along_corner(movers: list[SceneObject], line: LineBuilder, host: str,
                  hobj: SceneObject, hpose: Pose, spacing: float) -> Plan:
    """A row inside a corner marker along its longer arm, touching the arm, first
    object's end at the inner vertex.

    Raises:
        Infeasible: the row is longer than the arm.
    """
    rot = yaw_rotation_2d(hpose.yaw)
    along_x = hobj.size[0] >= hobj.size[1]
    d = rot @ (np.array([1.0, 0.0]) if along_x else np.array([0.0, 1.0]))
    inward = rot @ (np.array([0.0, 1.0]) if along_x else np.array([1.0, 0.0]))
    w = corner_arm_width(hobj.size)
    arm = float(hobj.size[0] if along_x else hobj.size[1]) - w
    n = len(movers)
    head = float(movers[0].half_xy[0])
    length = head + (n - 1) * spacing + float(movers[-1].half_xy[0])
    if length > arm + GEOMETRY_EPS:
        raise Infeasible(f"a row of {n} spaced {spacing:.3f} m is {length:.3f} m long; the "
                         f"arm of {host!r} is {arm:.3f} m", retry=False)
    side = max(float(o.half_xy[1]) for o in movers)
    centre = (corner_vertex(hobj, hpose) + d * (head + (n - 1) / 2 * spacing) +
              inward * side)
    yaw = hpose.yaw + (0.0 if along_x else math.pi / 2)
    return line(centre, yaw, rest_surface_z(hobj, hpose), [host])
