"""``circle``: objects evenly on a ring, around an anchor or a free spot."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Annotated, Any, ClassVar, Literal

import numpy as np
from pydantic import Field

from factask.relations.base import RelationBase
from factask.relations.packing import clear_radius
from factask.relations.solving import Infeasible, Plan, SolveContext, SolvedFactor, make_plan
from factask.relations.status import CheckScene, Verdict, check_slots
from factask.scene.collision import CLEARANCE, TABLE
from factask.scene.objects import SceneObject, footprint_corners, rest_surface_z, resting_pose
from factask.vocabulary.names import Name
from factask.vocabulary.world import TABLE_Z, WORKSPACE_DEPTH

#: Extra chord (m) between neighbours on a ring, over the clearance.
RING_SLACK = 0.001


class Circle(RelationBase):
    """Arrange the objects evenly on a circle of ``radius`` metres (default: just
    wide enough), around variable ``center`` if given, else around a free spot."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {
        "center": ("region", "support", "receptacle")}

    type: Literal["circle"] = "circle"
    radius: Annotated[float, Field(gt=0, le=0.4, allow_inf_nan=False)] | None = None
    center: Name | None = None

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], Circle]:
        return ([{"name": "blocks", "kind": "block", "count": 4, "color": "orange"}],
                cls(objects=["blocks"]))

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        n = len(movers)
        diag = 2 * max(clear_radius(o) for o in movers)
        # RING_SLACK: neighbours exactly at the clearance fail the collision test by
        # rounding, for some phases only (a slow, random search otherwise).
        radius = (diag + RING_SLACK) / (2 * math.sin(math.pi / n)) if n > 1 else 0.0
        ones = np.ones((n, n), dtype=bool)
        phase = float(ctx.rng.uniform(0, 2 * math.pi / max(n, 1)))

        def ring(centre: np.ndarray, r: float, surface: float, hosts: list[str]) -> Plan:
            slots = []
            for k, o in enumerate(movers):
                a = phase + 2 * math.pi * k / n
                xy = centre + r * np.array([math.cos(a), math.sin(a)])
                slots.append(resting_pose(o, *xy, surface, a + math.pi))
            return make_plan(slots, [surface] * n, [hosts[0] if hosts else TABLE] * n,
                             [set(hosts)] * n, ones)

        if self.center:
            hosts = ctx.inst(self.center)
            hobjs = [ctx.objs[h] for h in hosts]
            area, _, _ = ctx.anchor(self.center)
            first = hobjs[0]
            if first.is_receptacle or not first.collides:
                surface = TABLE_Z
                if first.is_receptacle:  # around it on the table: clear its footprint
                    outer = float(np.linalg.norm(area.half)) + diag / 2
                    radius = max(radius, outer)
            else:
                surface = max(rest_surface_z(o, ctx.current[h])
                              for o, h in zip(hobjs, hosts, strict=True))
            r = self.radius or radius
            plan = ring(area.center, r, surface, [] if first.is_receptacle else hosts)
            plan.random = True  # the phase is random
            if first.collides and not first.is_receptacle:
                fits_on_top = all(bool(area.contains(footprint_corners(o, slot)).all())
                                  for o, slot in zip(movers, plan.slots, strict=True))
                if not fits_on_top:
                    # Too small to carry the ring (a block among others): the ring goes
                    # *around* it on the table, clear of its footprint.
                    outer = float(np.linalg.norm(area.half)) + diag / 2 + CLEARANCE
                    r = max(self.radius or 0.0, radius, outer)
                    plan = ring(area.center, r, TABLE_Z, [])
                    plan.random = True
            return plan
        r = self.radius or radius
        across = 2 * r + diag
        if across > WORKSPACE_DEPTH:  # necessary: a free circle fits the workspace's depth
            raise Infeasible(f"a circle of {n} is {across:.3f} m across; the workspace is "
                             f"{WORKSPACE_DEPTH:.2f} m deep", retry=False)
        return ctx.search(movers, lambda xy, _yaw: ring(xy, r, TABLE_Z, []),
                          f"a circle of {n}")

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        return check_slots(solved, scene, self.tolerances)
