"""``aligned``: each object at a reference's position and yaw, in its corner, or lined
up with its hole."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar, Literal

import numpy as np

from factask.relations.base import RelationBase, Reserve
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
from factask.vocabulary.errors import Problem
from factask.vocabulary.kinds import side_hole
from factask.vocabulary.names import Name
from factask.vocabulary.variables import StateVariable
from factask.vocabulary.world import TABLE_Z

#: Mode ``hole``: the gap (m) between the box's holed face and the object's end.
HOLE_GAP = 0.005


#: Kinds whose objects are put in place by alignment, not inside or on them: an ell
#: into its fixture, a block into a corner marker, a shape into its kit, a log by a
#: holed box.
ALIGNING_KINDS = frozenset({"fixture", "corner", "kit", "holed_box"})


def modes_for(reference_kind: str) -> tuple[str, ...]:
    """The modes an ``aligned`` goal may take with a reference of this kind, the one
    its kind asks first: a ``holed_box`` is lined up with (``hole``) and nothing else
    is; into a corner marker an object goes corner to corner."""
    if reference_kind == "holed_box":
        return ("hole",)
    return ("corner", "center") if reference_kind == "corner" else ("center", "corner")


class Aligned(RelationBase):
    """Align each object with the ``reference`` variable: ``center`` puts it at the
    reference's position and yaw (an ell into its fixture, a block onto a marker);
    ``corner`` puts the object's corner into the reference corner marker; ``hole``
    lays the object on the table in front of a ``holed_box``'s hole, its x axis (a
    log's axis) through the hole and its end just short of the box."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {"reference": ()}

    type: Literal["aligned"] = "aligned"
    reference: Name
    mode: Literal["center", "corner", "hole"] = "center"

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
        if ref is not None and self.mode not in modes_for(ref.kind):
            fix = " or ".join(repr(m) for m in modes_for(ref.kind))
            out.append(Problem(factor, "goal.mode",
                               f"mode {self.mode!r} does not fit {self.reference!r}, a "
                               f"{ref.kind} (a holed_box is lined up with its hole: mode "
                               "'hole'; anything else is aligned by centre or corner)",
                               f"use mode {fix}"))
        elif self.mode == "hole" and ref is not None:
            out += self._hole_problems(factor, ref, variables)
        return out

    def layout_reserves(self, variables: Mapping[str, StateVariable]) -> list[Reserve]:
        """Mode ``hole``: the table in front of the hole, where the object will lie
        (the longest and widest of the objects)."""
        ref = variables.get(self.reference)
        movers = [variables[o] for o in dict.fromkeys(self.objects) if o in variables]
        if self.mode != "hole" or ref is None or not movers:
            return []
        length = max(v.extents[0] for v in movers)
        width = max(v.extents[1] for v in movers)
        return [Reserve(self.reference, ref.extents[0] / 2 + HOLE_GAP + length / 2, 0.0,
                        (length, width))]

    def _hole_problems(self, factor: str, ref: StateVariable,
                       variables: Mapping[str, StateVariable]) -> list[Problem]:
        """Mode ``hole``: the reference has a hole, and each object's axis (at half its
        height, resting on the table) passes through it."""
        side, centre = side_hole(ref.extents)
        out = []
        for name in dict.fromkeys(self.objects):
            var = variables.get(name)
            if var is not None and abs(var.extents[2] / 2 - centre) > side / 2:
                out.append(Problem(
                    factor, "goal.objects",
                    f"{name!r}'s axis {var.extents[2] / 2:.3f} m above the table misses "
                    f"{self.reference!r}'s hole ({side:.3f} m square, centre "
                    f"{centre:.3f} m up)",
                    f"give {self.reference!r} a height near {var.extents[2]:.3f} m (the hole "
                    "is in the middle of its side)"))
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
            support = ref if robj.collides else TABLE
            if self.mode == "corner":
                v = corner_vertex(robj, rpose)
                c = v + yaw_rotation_2d(rpose.yaw) @ obj.half_xy
            elif self.mode == "hole":  # on the table, in front of the +x face
                ahead = robj.size[0] / 2 + HOLE_GAP + obj.size[0] / 2
                c = rpose.pos[:2] + yaw_rotation_2d(rpose.yaw) @ np.array([ahead, 0.0])
                surface, support = TABLE_Z, TABLE
            else:
                c = rpose.pos[:2]
            slots.append(resting_pose(obj, float(c[0]), float(c[1]), surface, rpose.yaw))
            surfaces.append(surface)
            supports.append(support)
            ignore.append({ref})
        nominal = [movers[j if j < n else 0] for j in range(m)]
        matches = np.array([[np.allclose(o.size, nominal[j].size) for j in range(m)]
                            for o in movers], dtype=bool)
        return make_plan(slots, surfaces, supports, ignore, matches)

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        return check_slots(solved, scene, self.tolerances)
