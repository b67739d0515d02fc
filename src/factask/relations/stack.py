"""``stack``: one column of objects, first at the bottom, on a base or the table."""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np

from factask.relations.base import RelationBase
from factask.relations.solving import (
    Plan,
    SolveContext,
    SolvedFactor,
    make_plan,
    same_size,
    same_variable,
)
from factask.relations.status import CheckScene, Verdict, check_slots
from factask.scene.collision import MAX_TRIES_PER_OBJECT, TABLE
from factask.scene.objects import GEOMETRY_EPS, SceneObject, resting_pose, yaw_rotation_2d
from factask.vocabulary.errors import Problem
from factask.vocabulary.names import Name
from factask.vocabulary.world import TABLE_Z

if TYPE_CHECKING:  # the graph model sits above the relations (it imports their schemas)
    from factask.vocabulary.variables import StateVariable

#: A base marker a column may stand in, and the piece that carries only its like.
CORNER_KIND, ELL_KIND = "corner", "ell"


class Stack(RelationBase):
    """Stack the objects into one column, first object at the bottom. The column
    stands on ``base`` if given (a corner marker: in it, the column at its
    centre and yaw), else on a free spot of the table. An ell carries only an ell
    no larger than itself (centred on it, its bars on the lower bars). With
    ``ordered`` false any order counts."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {"base": ("support", "region")}
    anchor_kinds: ClassVar[Mapping[str, tuple[str, ...]]] = {"base": (CORNER_KIND, ELL_KIND)}

    type: Literal["stack"] = "stack"
    base: Name | None = None
    ordered: bool = True

    def problems(self, factor: str, variables: Mapping[str, StateVariable]) -> list[Problem]:
        """Beyond the anchors: whatever rests on an ell (the base or a layer) is an ell
        no larger than it, since an L carries nothing else flat (a centred smaller
        ell of the library's proportions has most of its bars on the lower bars)."""
        out = super().problems(factor, variables)
        column = ([self.base] if self.base else []) + list(self.objects)
        for below, above in itertools.pairwise(column):
            lo, hi = variables.get(below), variables.get(above)
            if lo is None or hi is None or lo.kind != ELL_KIND:
                continue
            if hi.kind != ELL_KIND or hi.extents[0] > lo.extents[0] + GEOMETRY_EPS or \
                    hi.extents[1] > lo.extents[1] + GEOMETRY_EPS:
                out.append(Problem(factor, "goal.objects",
                                   f"{above!r} ({hi.kind}) would rest on the ell {below!r}: an "
                                   "ell carries only an ell no larger than itself",
                                   "put it on a block, box or pallet, or use a smaller ell"))
        return out

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], Stack]:
        return ([{"name": "bottom", "kind": "block", "color": "red"},
                 {"name": "middle", "kind": "block", "color": "green"},
                 {"name": "top", "kind": "block", "color": "blue"}],
                cls(objects=["bottom", "middle", "top"]))

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        n = len(movers)
        matches = same_variable(movers) if self.ordered else same_size(movers)

        def build(xy: np.ndarray, yaw: float, surface: float = TABLE_Z,
                  hosts: list[str] | None = None) -> Plan:
            slots, surfaces, supports = [], [], []
            z = surface
            for k, o in enumerate(movers):
                slots.append(resting_pose(o, float(xy[0]), float(xy[1]), z, yaw))
                surfaces.append(z)
                supports.append(movers[k - 1].name if k else (hosts[0] if hosts else TABLE))
                z += o.height
            return make_plan(slots, list(surfaces), supports, [set(hosts or [])] * n, matches,
                             chain=True, support_group=list(hosts or []))

        if self.base:
            area, surface, hosts = ctx.anchor(self.base)
            fits = bool(np.all(movers[0].half_xy <= area.packing_half() + GEOMETRY_EPS))
            if len(hosts) > 1 or not fits:
                return build(area.center, area.yaw, surface, hosts)
            # Centred on the base if free there, else another spot of its top face.
            room = np.maximum(area.packing_half() - movers[0].half_xy, 0.0)
            local = ctx.rng.uniform(-room, room, size=(MAX_TRIES_PER_OBJECT, 2))
            local[0] = 0.0
            spots = [(area.center + yaw_rotation_2d(area.yaw) @ p, area.yaw) for p in local]
            return ctx.search(movers, lambda xy, yaw: build(xy, yaw, surface, hosts),
                              f"a stack of {n} on {self.base!r}", spots)
        return ctx.search(movers, build, f"a stack of {n}")

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        return check_slots(solved, scene, self.tolerances)
