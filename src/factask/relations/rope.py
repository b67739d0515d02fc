"""``rope_along``: a rope laid straight along a line (Ravens' rope tasks).

A rope (kind ``rope``) is ``count`` segments in a chain. Its target is a
straight run of slots, :data:`SLOT_PITCH` of a segment length apart, centred on the ``along``
variable (a line, zone or any region: along its longer side) or, with ``start``
and ``end`` given, from the centre of ``start`` towards the centre of ``end``
(the rope's ends at two targets, Ravens' corners of a square); or, with
``points``, one given point per segment in chain order (any curve: Ravens' bead
targets). Either end of the rope may take either end of the run (unless
``either_end`` is false): the check takes the better direction. Each slot's yaw
is the run's direction there (from the slot before towards the slot after).

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
from pydantic import Field

from factask.relations.at_pose import TargetPose
from factask.relations.base import RelationBase
from factask.relations.solving import Infeasible, Plan, SolveContext, SolvedFactor, make_plan
from factask.relations.status import MAX_DETAIL_ITEMS, CheckScene, FactorStatus, Verdict
from factask.scene.collision import TABLE
from factask.scene.objects import SceneObject, resting_pose
from factask.vocabulary.errors import Problem
from factask.vocabulary.kinds import kind_spec
from factask.vocabulary.names import Name
from factask.vocabulary.world import TABLE_Z

if TYPE_CHECKING:
    from factask.vocabulary.variables import StateVariable

#: The kind whose variables this relation moves.
ROPE_KIND = "rope"
#: Where on an ``along`` region the run lies.
RunSide = Literal["middle", "+x", "-x", "+y", "-y", "diagonal"]
#: Gap (m) left between a solid end anchor (a block) and the rope's end segment.
ANCHOR_GAP = 0.015
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
    ``start`` towards the centre of ``end``; or on ``points`` (one x, y per
    segment, in chain order). Either rope end may go first unless ``either_end``
    is false."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {
        "along": ("region",), "start": (), "end": ()}
    moves_kinds: ClassVar[frozenset[str] | None] = frozenset([ROPE_KIND])
    other_kinds_fix: ClassVar[str] = "use row or at_pose for other kinds"

    type: Literal["rope_along"] = "rope_along"
    along: Name | None = None
    side: RunSide = Field(
        default="middle",
        description="With `along`: the run through the region's middle along its longer "
                    "side, along one edge ('+x', '-x', '+y', '-y' in its frame), or across "
                    "its diagonal (from its -x -y corner to its +x +y corner).")
    start: Name | None = None
    end: Name | None = None
    points: list[TargetPose] | None = Field(
        default=None, min_length=2,
        description="One target (x, y) per segment, in chain order (yaw and z ignored).")
    either_end: bool = True

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], RopeAlong]:
        return ([{"name": "red_rope", "kind": "rope", "count": 10, "color": "red"},
                 {"name": "green_line", "kind": "line", "color": "green"}],
                cls(objects=["red_rope"], along="green_line"))

    def problems(self, factor: str, variables: Mapping[str, StateVariable]) -> list[Problem]:
        out = super().problems(factor, variables)
        given = [self.along is not None, self.start is not None or self.end is not None,
                 self.points is not None]
        if sum(given) != 1 or (given[1] and (self.start is None or self.end is None)):
            out.append(Problem(factor, "goal", "rope_along needs `along`, or `start` and "
                               "`end`, or `points` (one of them)",
                               "give a line, the two end anchors, or a point per segment"))
        if self.side != "middle" and self.along is None:
            out.append(Problem(factor, "goal.side", "`side` places the run on the `along` "
                               "region", "give `along`, or leave `side` out"))
        if len(self.objects) != 1:
            out.append(Problem(factor, "goal.objects", "rope_along lays out one rope",
                               "one factor per rope"))
        for name in self.objects:
            v = variables.get(name)
            if (v is not None and v.kind == ROPE_KIND and self.points is not None
                    and len(self.points) != v.count):
                out.append(Problem(factor, "goal.points",
                                   f"{name!r} has {v.count} segment(s) but "
                                   f"{len(self.points)} point(s) are given",
                                   "give one point per segment"))
        return out

    def _run(self, ctx: SolveContext, seg: float, n: int) -> tuple[np.ndarray, float]:
        """Centre (2,) and yaw of the run of ``n`` slots."""
        if self.along is not None:
            host = ctx.inst(self.along)[0]
            hobj, hpose = ctx.objs[host], ctx.current[host]
            return _side_run(hpose.pos[:2], hpose.yaw, hobj.size, self.side)
        if self.start is None or self.end is None:  # validation names it; solving alone too
            raise Infeasible("a rope_along goal needs 'along', or both 'start' and 'end'",
                             retry=False)
        first = ctx.inst(self.start)[0]
        a = ctx.current[first].pos[:2]
        b = ctx.current[ctx.inst(self.end)[0]].pos[:2]
        d = b - a
        if float(np.linalg.norm(d)) < 1e-9:
            raise Infeasible(f"{self.start!r} and {self.end!r} are at one spot", retry=False)
        u = d / np.linalg.norm(d)
        # The first segment's centre half a segment in from start (Ravens' beads); from
        # a solid start (a block), half a segment beyond its edge.
        return a + u * (_edge(ctx.objs[first], ctx.current[first].yaw, u)
                        + n * seg / 2), math.atan2(u[1], u[0])

    def slot_points(self, ctx: SolveContext, movers: list[SceneObject]) -> np.ndarray:
        """The slots' centres (n, 2), in chain order."""
        n = len(movers)
        if self.points is not None:
            if len(self.points) != n:
                raise Infeasible(f"{n} segment(s) but {len(self.points)} point(s)",
                                 retry=False)
            return np.array([[p.x, p.y] for p in self.points], dtype=float)
        seg = movers[0].size[0] * SLOT_PITCH
        centre, yaw = self._run(ctx, seg, n)
        d = np.array([math.cos(yaw), math.sin(yaw)])
        return np.array([centre + (k - (n - 1) / 2) * seg * d for k in range(n)])

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        n = len(movers)
        pts = self.slot_points(ctx, movers)
        slots = [resting_pose(o, *pts[k], TABLE_Z, run_yaw(pts, k))
                 for k, o in enumerate(movers)]
        matches = np.eye(n, dtype=bool)
        if self.either_end:
            matches |= np.eye(n, dtype=bool)[::-1]
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
        if not self.either_end:
            return dist, False
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


def _side_run(centre: np.ndarray, yaw: float, size: Any, side: str
              ) -> tuple[np.ndarray, float]:
    """Centre (2,) and yaw of a run on a region (centre, yaw, full size) at ``side``."""
    c, s = math.cos(yaw), math.sin(yaw)
    ex, ey = np.array([c, s]), np.array([-s, c])
    hx, hy = size[0] / 2, size[1] / 2
    if side == "middle":
        return centre.copy(), yaw if size[0] >= size[1] else yaw + math.pi / 2
    if side == "diagonal":
        return centre.copy(), yaw + math.atan2(size[1], size[0])
    if side in ("+x", "-x"):
        sign = 1.0 if side == "+x" else -1.0
        return centre + sign * hx * ex, yaw + math.pi / 2
    sign = 1.0 if side == "+y" else -1.0
    return centre + sign * hy * ey, yaw


def _edge(obj: SceneObject, yaw: float, u: np.ndarray) -> float:
    """How far (m) from its centre along ``u`` a solid anchor's footprint reaches (plus
    :data:`ANCHOR_GAP`); 0 for a marker (zone, line, corner: the rope may lie on it)."""
    spec = kind_spec(obj.kind)
    if spec.region or not spec.collides:
        return 0.0
    c, s = math.cos(yaw), math.sin(yaw)
    reach = (abs(u @ np.array([c, s])) * obj.size[0] / 2
             + abs(u @ np.array([-s, c])) * obj.size[1] / 2)
    return float(reach) + ANCHOR_GAP


def run_yaw(points: np.ndarray, k: int) -> float:
    """Direction (rad) of a run of points at point ``k``: from the point before it
    towards the point after it (at an end, towards or from its one neighbour)."""
    a = points[max(k - 1, 0)]
    b = points[min(k + 1, len(points) - 1)]
    d = b - a
    return math.atan2(float(d[1]), float(d[0]))


def rope_slot_order(targets: Mapping[str, int], n: int,
                    distance: Mapping[str, float], far_end: float = 0.5,
                    bend: Mapping[str, float] | None = None,
                    kink_deg: float = 90.0, near: float = 0.04, first_end: int = 0) -> str:
    """The segment to place next.

    1. The one for the run's ``first_end`` slot (its first, 0, or its last), then
       the one for the other end (pulling the rope out straight behind it), each
       while it is at least ``far_end`` times as far off as the farthest segment
       (one a little off waits: moving an end drags the rope).
    2. The segment turned farthest from the run's direction, by more than
       ``kink_deg``, among those within ``near`` of their slots: a fold, which holds
       rope the ends lack (placing the ends again would only drag it along).
    3. The one farthest from its slot (each move then is short and local).

    Args:
        targets: Unplaced segment -> its slot.
        n: Number of slots (segments).
        distance: Segment -> its distance to its slot (m); every unplaced one, and
            placed ones where ``bend`` is given.
        far_end: See above.
        bend: Segment -> how far (degrees, 0-180) it is turned from the run's
            direction at its slot; placed segments too (a fold within tolerance still
            holds rope). None: no folds are looked for.
        kink_deg: See above.
        near: See above (m).
        first_end: The slot (0 or ``n - 1``) whose end goes first.
    """
    by_slot = {slot: name for name, slot in targets.items()}
    far = max(targets, key=lambda name: distance[name])
    for end in ((0, n - 1) if first_end == 0 else (n - 1, 0)):
        name = by_slot.get(end)
        if name is not None and distance[name] >= far_end * distance[far]:
            return name
    folds = {name: b for name, b in (bend or {}).items()
             if b > kink_deg and distance[name] <= near}
    if folds:
        return max(folds, key=lambda name: folds[name])
    return far


__all__ = ["RopeAlong", "rope_slot_order", "run_yaw", "segment_scores"]
