"""``aligned``: each object at a reference's position and yaw, or in its corner."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar, Literal

import numpy as np

from factask.model.errors import Problem
from factask.model.names import Name
from factask.model.variables import StateVariable
from factask.relations.base import RelationBase
from factask.relations.solving import Infeasible, Plan, SolveContext, SolvedFactor, make_plan
from factask.relations.status import CheckScene, Verdict, check_slots
from factask.scene.collision import TABLE
from factask.scene.objects import (
    SceneObject,
    corner_vertex,
    rest_surface_z,
    resting_pose,
    yaw_rotation_2d,
)


class Aligned(RelationBase):
    """Align each object with the ``reference`` variable: ``center`` puts it at the
    reference's position and yaw (an ell into its fixture, a block onto a marker);
    ``corner`` puts the object's corner into the reference corner marker."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {"reference": ()}

    type: Literal["aligned"] = "aligned"
    reference: Name
    mode: Literal["center", "corner"] = "center"

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], Aligned]:
        return ([{"name": "ell", "kind": "ell", "color": "purple"},
                 {"name": "fixture", "kind": "fixture"}],
                cls(objects=["ell"], reference="fixture"))

    def problems(self, factor: str, variables: Mapping[str, StateVariable]) -> list[Problem]:
        """Beyond the anchor's kind: an instance of the reference for every object
        (each object is aligned with one of its own), found before any reset."""
        out = super().problems(factor, variables)
        ref = variables.get(self.reference)
        n = sum(variables[o].count for o in dict.fromkeys(self.objects) if o in variables)
        if ref is not None and n > ref.count:
            out.append(Problem(factor, "goal.objects",
                               f"{n} object(s) to align but {self.reference!r} has "
                               f"{ref.count} instance(s): each object is aligned with an "
                               "instance of its own",
                               f"give {self.reference!r} count {n}, or use 'on' or "
                               "'in_zone' to put several objects on one"))
        return out

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        refs = ctx.inst(self.reference)
        n, m = len(movers), len(refs)
        if n > m:
            raise Infeasible(f"{n} object(s) but only {m} instance(s) of reference "
                             f"{self.reference!r}", retry=False)
        slots, surfaces, supports, ignore = [], [], [], []
        for j, ref in enumerate(refs):
            robj, rpose = ctx.objs[ref], ctx.current[ref]
            obj = movers[j if j < n else 0]
            surface = rest_surface_z(robj, rpose)
            if self.mode == "corner":
                v = corner_vertex(robj, rpose)
                c = v + yaw_rotation_2d(rpose.yaw) @ obj.half_xy
            else:
                c = rpose.pos[:2]
            slots.append(resting_pose(obj, float(c[0]), float(c[1]), surface, rpose.yaw))
            surfaces.append(surface)
            supports.append(ref if robj.collides else TABLE)
            ignore.append({ref})
        nominal = [movers[j if j < n else 0] for j in range(m)]
        matches = np.array([[np.allclose(o.size, nominal[j].size) for j in range(m)]
                            for o in movers], dtype=bool)
        return make_plan(slots, surfaces, supports, ignore, matches)

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        return check_slots(solved, scene, self.tolerances)
