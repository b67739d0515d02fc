"""What ``in_zone`` and ``inside`` share: packing into a region, the region check.

An object is in a region when at least ``region_fraction`` of its footprint's
sample points lie in the region's area (of any instance, if the region variable
has several); ``inside`` also wants its bottom between the floor and the rim.
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from factask.relations.base import RelationBase
from factask.relations.packing import pack_plan
from factask.relations.solving import Plan, SolveContext, SolvedFactor, make_plan
from factask.relations.status import CheckScene, Verdict
from factask.scene.objects import (
    SceneObject,
    bottom_z,
    floor_top_z,
    footprint_points,
    placement_area,
    top_z,
)

_CM = 100.0


class RegionRelation(RelationBase):
    """Base of the relations that put objects into a region variable's area."""

    #: The anchor field naming the region variable.
    region_field: ClassVar[str]
    #: Also check the bottom between the receptacle's floor and rim.
    between_floor_and_rim: ClassVar[bool] = False

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        hosts = ctx.inst(getattr(self, self.region_field))
        n = len(movers)
        groups = [(h, [i for i in range(n) if i % len(hosts) == k])
                  for k, h in enumerate(hosts)]
        groups = [(h, m) for h, m in groups if m]
        # Alternate: a grid (tight, reliable) on even attempts, random spots (which
        # work around objects already resting in the region) on odd ones.
        slots, surfaces, supports = pack_plan(ctx, movers, groups, ctx.attempt % 2 == 1)
        ignore = [{s} for s in supports]
        return make_plan(slots, surfaces, supports, ignore, np.ones((n, n), dtype=bool),
                         region=list(hosts), random=True)

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        tol = self.tolerances
        objs = scene.objects
        problems = []
        placed: dict[str, int | None] = {}
        for name in solved.objects:
            obj, pose = objs[name], scene.pose(name)
            if name in scene.held:
                problems.append(f"{name}: held by the robot")
                continue
            pts = footprint_points(obj, pose)
            best, why = 0.0, ""
            for region in solved.regions:
                robj, rpose = objs[region], scene.pose(region)
                frac = float(placement_area(robj, rpose).contains(pts).mean())
                if frac + 1e-12 < tol.region_fraction:
                    best = max(best, frac)
                    why = why or (f"{name}: {frac:.0%} inside {region} "
                                  f"(needs {tol.region_fraction:.0%})")
                    continue
                if self.between_floor_and_rim:
                    b = bottom_z(obj, pose)
                    floor, rim = floor_top_z(robj, rpose), top_z(robj, rpose)
                    if b < floor - tol.z or b >= rim:
                        why = (f"{name}: bottom at {b * _CM:.1f} cm, not between {region}'s "
                               f"floor ({floor * _CM:.1f} cm) and rim ({rim * _CM:.1f} cm)")
                        continue
                best = 1.0
                break
            if best >= 1.0:
                placed[name] = None
            else:
                problems.append(why or f"{name}: not in {'/'.join(solved.regions)}")
        return Verdict(placed, problems)
