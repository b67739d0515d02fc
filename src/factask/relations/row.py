"""``row``: objects side by side in a straight line (free, along a line, or on a row)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Annotated, Any, ClassVar, Literal

import numpy as np
from pydantic import Field

from factask.geometry import wrap_angle
from factask.model.errors import Problem
from factask.model.names import Name
from factask.model.world import TABLE_Z, WORKSPACE_DIAGONAL
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
from factask.scene.collision import TABLE
from factask.scene.objects import (
    GEOMETRY_EPS,
    SceneObject,
    placement_area,
    principal_yaw,
    rest_surface_z,
    resting_pose,
    yaw_rotation_2d,
)

if TYPE_CHECKING:  # the graph model sits above the relations (it imports their schemas)
    from factask.model.variables import StateVariable

#: Extra gap in a row with no explicit spacing: widest object + this (metres).
ROW_GAP = 0.01


class Row(RelationBase):
    """Place the objects side by side in a straight row, centre-to-centre
    ``spacing`` metres apart (default: widest object + 1 cm). ``along``: lie on
    that line/zone variable. ``on``: rest on top of the row below, made of the
    instances of variable ``on`` or of a list of variables (a layer of mixed
    colours): same count: one on each; one fewer: each bridging two neighbours,
    as in a pyramid; fewer still: centred on the row below."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {
        "along": ("region",), "on": ("support",)}

    type: Literal["row"] = "row"
    spacing: Annotated[float, Field(gt=0, le=0.5, allow_inf_nan=False)] | None = None
    along: Name | None = None
    on: Name | Annotated[list[Name], Field(min_length=1, max_length=16)] | None = None
    ordered: bool = True

    def problems(self, factor: str, variables: Mapping[str, StateVariable]) -> list[Problem]:
        out = super().problems(factor, variables)
        below = self.anchor_names("on")
        for name in dict.fromkeys(n for n in below if below.count(n) > 1):
            out.append(Problem(factor, "goal.on", f"{name!r} listed twice", "list it once"))
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
        if self.along:
            host = ctx.inst(self.along)[0]
            hobj, hpose = ctx.objs[host], ctx.current[host]
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
