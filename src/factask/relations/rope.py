"""``rope_along``: a rope laid straight along a line (Ravens' rope tasks).

A rope (kind ``rope``) is ``count`` segments in a chain. Its target is a
straight run of slots, :data:`SLOT_PITCH` of a segment length apart, centred on the ``along``
variable (a line, zone or any region: along its longer side) or, with ``start``
and ``end`` given, from the centre of ``start`` towards the centre of ``end``
(the rope's ends at two targets, Ravens' corners of a square). Either end of
the rope may take either end of the run: the check takes the better direction.

Progress is continuous: each segment scores 1 within ``tolerances.xy`` of its
slot, 0 beyond twice that, linearly between; progress is the mean score in the
better direction (a maximum of continuous functions). The goal is satisfied
when every segment is within ``tolerances.xy`` in one direction.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np

from factask.model.errors import Problem
from factask.model.names import Name
from factask.model.world import TABLE_Z
from factask.relations.base import RelationBase
from factask.relations.solving import Infeasible, Plan, SolveContext, SolvedFactor, make_plan
from factask.relations.status import MAX_DETAIL_ITEMS, CheckScene, FactorStatus, Verdict
from factask.scene.collision import TABLE
from factask.scene.objects import SceneObject, resting_pose

if TYPE_CHECKING:
    from factask.model.variables import StateVariable

#: The kind whose variables this relation moves.
ROPE_KIND = "rope"
#: Slots are this fraction of a segment length apart: a little slack, so laying one
#: segment does not pull the ones laid before it off their slots.
SLOT_PITCH = 0.92
_CM = 100.0


def segment_scores(dist: np.ndarray, tol: float) -> np.ndarray:
    """Each segment's score from its distance to its slot: 1 within ``tol``, 0 beyond
    ``2 tol``, linear between (continuous)."""
    return np.clip((2 * tol - np.asarray(dist, dtype=float)) / tol, 0.0, 1.0)


class RopeAlong(RelationBase):
    """Lay the rope ``objects`` (kind rope) straight: along the region variable
    ``along`` (centred on it, along its longer side), or from the centre of
    ``start`` towards the centre of ``end``. Either rope end may go first."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {
        "along": ("region",), "start": (), "end": ()}

    type: Literal["rope_along"] = "rope_along"
    along: Name | None = None
    start: Name | None = None
    end: Name | None = None

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], RopeAlong]:
        return ([{"name": "red_rope", "kind": "rope", "count": 10, "color": "red"},
                 {"name": "green_line", "kind": "line", "color": "green"}],
                cls(objects=["red_rope"], along="green_line"))

    def problems(self, factor: str, variables: Mapping[str, StateVariable]) -> list[Problem]:
        out = super().problems(factor, variables)
        if (self.along is None) == (self.start is None or self.end is None):
            out.append(Problem(factor, "goal", "rope_along needs `along`, or `start` and "
                               "`end` (not both)", "give a line, or the two end anchors"))
        if len(self.objects) != 1:
            out.append(Problem(factor, "goal.objects", "rope_along lays out one rope",
                               "one factor per rope"))
        for name in self.objects:
            v = variables.get(name)
            if v is not None and v.kind != ROPE_KIND:
                out.append(Problem(factor, "goal.objects",
                                   f"{name!r} is a {v.kind}; rope_along moves ropes",
                                   "use row or at_pose for other kinds"))
        return out

    def _run(self, ctx: SolveContext, seg: float, n: int) -> tuple[np.ndarray, float]:
        """Centre (2,) and yaw of the run of ``n`` slots."""
        if self.along is not None:
            host = ctx.inst(self.along)[0]
            hobj, hpose = ctx.objs[host], ctx.current[host]
            yaw = hpose.yaw if hobj.size[0] >= hobj.size[1] else hpose.yaw + math.pi / 2
            return hpose.pos[:2].copy(), yaw
        assert self.start is not None and self.end is not None
        a = ctx.current[ctx.inst(self.start)[0]].pos[:2]
        b = ctx.current[ctx.inst(self.end)[0]].pos[:2]
        d = b - a
        if float(np.linalg.norm(d)) < 1e-9:
            raise Infeasible(f"{self.start!r} and {self.end!r} are at one spot", retry=False)
        u = d / np.linalg.norm(d)
        # The first segment's centre half a segment in from start (Ravens' beads).
        return a + u * (n * seg / 2), math.atan2(u[1], u[0])

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        n = len(movers)
        seg = movers[0].size[0] * SLOT_PITCH
        centre, yaw = self._run(ctx, seg, n)
        d = np.array([math.cos(yaw), math.sin(yaw)])
        slots = [resting_pose(o, *(centre + (k - (n - 1) / 2) * seg * d), TABLE_Z, yaw)
                 for k, o in enumerate(movers)]
        matches = np.zeros((n, n), dtype=bool)
        for k in range(n):
            matches[k, k] = matches[k, n - 1 - k] = True
        # Neighbouring segments touch: the slots may, and the rope's own start.
        own = {f"@slot{j}" for j in range(n)} | {f"@start:{o.name}" for o in movers}
        hosts = set(self.anchors())
        hosts = {i for h in hosts for i in ctx.inst(h)}
        return make_plan(slots, [TABLE_Z] * n, [TABLE] * n, [own | hosts] * n, matches)

    def _distances(self, solved: SolvedFactor, scene: CheckScene) -> tuple[np.ndarray, bool]:
        """Distances (n,) of the segments to their slots in the better direction, and
        whether that direction is reversed."""
        objs = scene.objects
        names = solved.objects
        xy = np.array([scene.pose(n).pos[:2] for n in names])
        fwd = np.array([solved.target_pose(objs[n], k).pos[:2] for k, n in enumerate(names)])
        held = np.array([n in scene.held for n in names])
        dist = np.linalg.norm(xy - fwd, axis=1)
        back = np.linalg.norm(xy - fwd[::-1], axis=1)
        tol = self.tolerances.xy
        dist[held] = back[held] = np.inf
        # The better direction: more score, then (a rope far away) the nearer ends.
        def key(d: np.ndarray) -> tuple[float, float]:
            finite = np.where(np.isfinite(d), d, 0.0)
            return float(segment_scores(d, tol).sum()), -float(finite.sum())

        rev = key(back) > key(dist)
        return (back if rev else dist), rev

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        dist, rev = self._distances(solved, scene)
        n = len(solved.objects)
        tol = self.tolerances.xy
        placed: dict[str, int | None] = {}
        problems = []
        for k, name in enumerate(solved.objects):
            slot = n - 1 - k if rev else k
            if dist[k] <= tol:
                placed[name] = slot
            elif name in scene.held:
                problems.append(f"{name}: held by the robot")
            else:
                problems.append(f"{name}: {dist[k] * _CM:.1f} cm from its place on the rope's "
                                f"line (tolerance {tol * _CM:.1f} cm)")
        return Verdict(placed, problems)

    def status(self, solved: SolvedFactor, scene: CheckScene) -> FactorStatus:
        """Progress = mean segment score in the better direction; every unplaced
        segment's target is its slot in that direction."""
        dist, rev = self._distances(solved, scene)
        n = len(solved.objects)
        verdict = self.check(solved, scene)
        progress = float(segment_scores(dist, self.tolerances.xy).mean()) if n else 1.0
        ok = len(verdict.placed) == n
        placed = {k: int(v) for k, v in verdict.placed.items() if v is not None}
        todo = {name: (n - 1 - k if rev else k) for k, name in enumerate(solved.objects)
                if name not in verdict.placed}
        free = tuple(sorted(todo.values()))
        shown = verdict.problems[:MAX_DETAIL_ITEMS]
        more = len(verdict.problems) - len(shown)
        detail = (f"all {n} segment(s) on the line" if ok else
                  f"{len(placed)}/{n} segment(s) on the line; " + "; ".join(shown)
                  + (f"; +{more} more" if more > 0 else ""))
        return FactorStatus(1.0 if ok else progress, ok, detail, placed, free, todo)


def rope_slot_order(targets: Mapping[str, int], n: int,
                    distance: Mapping[str, float], far_end: float = 0.5) -> str:
    """The segment to place next: the one for the run's first slot, then the one for
    its last (pulling the rope out straight behind it), then the one farthest from
    its slot (each move then is short and local); an end only while it is at least
    ``far_end`` times as far off as the farthest segment.

    Args:
        targets: Unplaced segment -> its slot.
        n: Number of slots (segments).
        distance: Unplaced segment -> its distance to its slot (m).
        far_end: See above.
    """
    by_slot = {slot: name for name, slot in targets.items()}
    far = max(targets, key=lambda name: distance[name])
    for end in (0, n - 1):
        # An end far off first; one a little off waits (moving it drags the rope).
        if end in by_slot and distance[by_slot[end]] >= far_end * distance[far]:
            return by_slot[end]
    return far


__all__ = ["RopeAlong", "rope_slot_order", "segment_scores"]
