"""``in_zone``: objects inside the footprint of a region variable."""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np
from pydantic import Field

from factask.relations.at_pose import TargetPose, solve_given_poses
from factask.relations.region import RegionRelation
from factask.relations.solving import Infeasible, Plan, SolveContext
from factask.scene.objects import SceneObject
from factask.vocabulary.errors import Problem
from factask.vocabulary.names import Name

if TYPE_CHECKING:
    from factask.vocabulary.variables import StateVariable


class InZone(RegionRelation):
    """Put every object inside the footprint of the region variable ``zone``
    (a zone, pallet, kit, stand, line, bowl, container or fixture). ``poses``
    (optional, one per object instance in order) says where each goes, e.g. a
    packing plan; left out, the library packs them."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {"zone": ("region",)}
    met_by_starting_in: ClassVar[str | None] = "zone"
    region_field: ClassVar[str] = "zone"

    type: Literal["in_zone"] = "in_zone"
    zone: Name
    poses: list[TargetPose] | None = Field(default=None, min_length=1)

    def problems(self, factor: str, variables: Mapping[str, StateVariable]) -> list[Problem]:
        out = super().problems(factor, variables)
        if self.poses is not None and all(o in variables for o in self.objects):
            n = sum(variables[o].count for o in self.objects)
            if len(self.poses) != n:
                out.append(Problem(factor, "goal.poses", f"{n} object(s) but "
                                   f"{len(self.poses)} pose(s)",
                                   "give one pose per object instance, or leave poses out"))
        return out

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        if self.poses is None:
            return super().solve(ctx, movers)
        if len(self.poses) != len(movers):
            raise Infeasible(f"{len(movers)} object(s) but {len(self.poses)} pose(s); give "
                             "one pose per object instance", retry=False)
        plan = solve_given_poses(ctx, movers, self.poses, np.eye(len(movers), dtype=bool))
        plan.region = list(ctx.inst(self.zone))
        return plan

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], InZone]:
        return ([{"name": "blocks", "kind": "block", "count": 2},
                 {"name": "green_zone", "kind": "zone", "color": "green"}],
                cls(objects=["blocks"], zone="green_zone"))
