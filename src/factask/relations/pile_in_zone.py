"""``pile_in_zone``: the small blocks of piles pushed into a region (Ravens' zone metric).

A pile (kind ``pile``) is ``count`` small blocks that are pushed, not picked.
The goal's progress is the share of the blocks' footprint area inside the
region, averaged over the blocks and divided by the goal's ``fraction`` (capped
at 1): each block counts as a square of its
footprint's area, aligned with the region, so its share changes linearly while
it crosses the region's edge (:func:`block_inside`). Progress is therefore a
continuous (Lipschitz) function of the blocks' positions, and a per-factor
reward stays informative while a push moves half the pile. The goal is
satisfied once the share reaches the ``fraction`` the relation carries (progress
1 then: the reward and the success agree).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Annotated, Any, ClassVar, Literal

import numpy as np
from pydantic import Field

from factask.relations.base import RelationBase
from factask.relations.solving import Plan, SolveContext, SolvedFactor, make_plan
from factask.relations.status import (
    MAX_DETAIL_ITEMS,
    CheckScene,
    FactorStatus,
    Verdict,
    factor_status,
)
from factask.scene.objects import (
    GEOMETRY_EPS,
    Area,
    SceneObject,
    placement_area,
    points_in_rect,
    rest_surface_z,
    resting_pose,
    yaw_rotation_2d,
)
from factask.vocabulary.names import Name

#: The kind whose variables this relation moves.
PILE_KIND = "pile"
#: Default fraction of the piles' blocks that must be inside (Ravens' sweeping
#: episodes end above 0.9 of the zone metric far more often than at 1.0).
DEFAULT_PILE_FRACTION = 0.9


def block_inside(area: Area, xy: np.ndarray, side: float) -> np.ndarray:
    """Fraction (k,) of each block's footprint inside ``area``, continuous in ``xy``.

    A block is taken as a square of side ``side`` aligned with the area (its own
    yaw ignored: what matters is where it is, and the measure stays continuous);
    for a round area, a segment of length ``side`` along the radius.

    Args:
        area: The region's area.
        xy: (k, 2) block centres.
        side: Side of the square standing for a block (m).

    Returns:
        Values in [0, 1]; 1 when the whole square is inside.
    """
    pts = np.asarray(xy, dtype=float).reshape(-1, 2)
    if area.round:
        d = np.linalg.norm(pts - area.center, axis=1)
        return np.clip((area.half[0] + side / 2 + GEOMETRY_EPS - d) / side, 0.0, 1.0)
    local = np.abs((pts - area.center) @ yaw_rotation_2d(area.yaw))
    # GEOMETRY_EPS: a block exactly on its slot at the area's edge counts whole, as
    # Area.contains counts boundary points in.
    per_axis = np.clip((area.half[None, :] + side / 2 + GEOMETRY_EPS - local) / side, 0.0, 1.0)
    return per_axis.prod(axis=1)


def _bodies_in(ctx: SolveContext, area: Area, movers: list[SceneObject]) -> list[Area]:
    """Footprints of the other objects with a body standing in ``area`` now (a
    fixture in the zone): a pile's blocks come to rest beside them, not on them."""
    skip = {o.name for o in movers}
    out = []
    for name, obj in ctx.objs.items():
        pose = ctx.current.get(name)
        if name in skip or pose is None or not obj.collides or obj.kind == PILE_KIND:
            continue
        if area.contains(pose.pos[None, :2])[0]:
            out.append(Area(pose.pos[:2].copy(), pose.yaw, obj.half_xy))
    return out


def _slot_cells(area: Area, block: SceneObject, n: int, bodies: list[Area]) -> list[np.ndarray]:
    """``n`` slot centres on a square grid over ``area`` (a whole block side from its
    edge, so any yaw stays inside), clear of ``bodies``: the grid is made finer until
    enough of its cells are clear; with none in the zone, the plain ceil(sqrt(n))
    grid."""
    half = area.packing_half()
    reach = 2 * float(block.half_xy.max())
    inset = np.maximum(half - reach, 0.0)
    rot = yaw_rotation_2d(area.yaw)
    cols = math.ceil(math.sqrt(n))
    plain: list[np.ndarray] = []
    for _ in range(4):
        step = 2 * inset / max(cols - 1, 1)
        cells = []
        for r in range(cols):
            for c in range(cols):
                local = np.zeros(2) if cols == 1 else -inset + step * np.array([c, r], float)
                cells.append(area.center + rot @ local)
        plain = plain or cells
        free = [p for p in cells if not any(
            points_in_rect(p[None], b.center, b.yaw, b.half + reach)[0] for b in bodies)]
        if len(free) >= n:
            return free[:n]
        cols += 1
    return plain[:n]  # no clear grid: the plain one (the reset reports the overlap)


def block_side(obj: SceneObject) -> float:
    """Side (m) of the square of a block's footprint area."""
    return math.sqrt(obj.footprint_area)


class PileInZone(RelationBase):
    """Push the small blocks of the piles ``objects`` (kind pile) into the region
    variable ``zone``. Progress is the share of the blocks inside (continuous) over
    ``fraction``; satisfied, with progress 1, once at least ``fraction`` of them are."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {"zone": ("region",)}
    moves_kinds: ClassVar[frozenset[str] | None] = frozenset([PILE_KIND])
    other_kinds_fix: ClassVar[str] = "use in_zone for other kinds, or make it a pile"

    type: Literal["pile_in_zone"] = "pile_in_zone"
    zone: Name
    fraction: Annotated[float, Field(gt=0, le=1, allow_inf_nan=False)] = DEFAULT_PILE_FRACTION

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], PileInZone]:
        return ([{"name": "red_pile", "kind": "pile", "count": 20, "color": "red"},
                 {"name": "green_zone", "kind": "zone", "color": "green"}],
                cls(objects=["red_pile"], zone="green_zone", fraction=1.0))

    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        """Nominal slots on a grid over the region (markers, obstacles for later
        goals), clear of any object with a body standing in it (a fixture: the
        blocks come to rest beside it); blocks are pushed, so the slots may overlap
        one another and the blocks' starts."""
        hosts = ctx.inst(self.zone)
        n = len(movers)
        slots = []
        surfaces = []
        for k, host in enumerate(hosts):
            mine = [i for i in range(n) if i % len(hosts) == k]
            if not mine:
                continue
            hobj, hpose = ctx.objs[host], ctx.current[host]
            area = placement_area(hobj, hpose)
            obj = movers[mine[0]]
            surface = rest_surface_z(hobj, hpose)
            cells = _slot_cells(area, obj, len(mine), _bodies_in(ctx, area, movers))
            for (x, y), i in zip(cells, mine, strict=True):
                slots.append((i, resting_pose(movers[i], float(x), float(y), surface,
                                              area.yaw)))
                surfaces.append((i, surface))
        slots.sort(key=lambda t: t[0])
        surfaces.sort(key=lambda t: t[0])
        # The names SolveContext.accept gives the movers' starts and the plan's slots.
        own = {f"@slot{j}" for j in range(n)} | {f"@start:{o.name}" for o in movers}
        # Other piles' slots too: two piles may go into one zone.
        own |= {i for v in ctx.graph.variables if v.kind == PILE_KIND for i in v.instances}
        return make_plan([p for _, p in slots], [s for _, s in surfaces],
                         [hosts[i % len(hosts)] for i in range(n)],
                         [own | set(hosts)] * n, np.ones((n, n), dtype=bool),
                         region=list(hosts))

    def inside(self, solved: SolvedFactor, scene: CheckScene) -> dict[str, float]:
        """Each block's fraction inside the best of the region's instances (held: 0)."""
        objs = scene.objects
        areas = [placement_area(objs[r], scene.pose(r)) for r in solved.regions]
        out: dict[str, float] = {}
        for name in solved.objects:
            pose = scene.pose(name)
            if name in scene.held:
                out[name] = 0.0
                continue
            side = block_side(objs[name])
            out[name] = max(float(block_inside(a, pose.pos[:2], side)[0]) for a in areas)
        return out

    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        """A block is placed when its centre is inside (half its square or more)."""
        frac = self.inside(solved, scene)
        placed: dict[str, int | None] = {n: None for n, f in frac.items() if f >= 0.5}
        problems = [f"{n}: held by the robot" if n in scene.held else
                    f"{n}: {f:.0%} inside {'/'.join(solved.regions)}"
                    for n, f in frac.items() if f < 0.5]
        return Verdict(placed, problems)

    def status(self, solved: SolvedFactor, scene: CheckScene) -> FactorStatus:
        """Progress = the blocks' mean share inside over ``fraction`` (at most 1);
        satisfied once the share reaches ``fraction``."""
        frac = self.inside(solved, scene)
        share = float(np.mean(list(frac.values()))) if frac else 1.0
        verdict = self.check(solved, scene)
        base = factor_status(solved, scene, verdict)
        ok = share + 1e-12 >= self.fraction
        # Over the threshold, so a satisfied goal has full progress: the reward and
        # the success agree (an episode succeeds at reward >= 0.99).
        progress = 1.0 if ok else share / self.fraction
        detail = (f"{share:.0%} of {len(frac)} block(s) inside "
                  f"{'/'.join(solved.regions)} (needs {self.fraction:.0%})")
        shown = verdict.problems[:MAX_DETAIL_ITEMS]
        if shown:
            more = len(verdict.problems) - len(shown)
            detail += "; " + "; ".join(shown) + (f"; +{more} more" if more > 0 else "")
        return replace(base, progress=progress, satisfied=ok, detail=detail)
