"""How the oracle plans a push for a ``pile_in_zone`` goal.

Aimed at the remaining blocks, from outside the zone towards it: the block
outside the zone farthest from the zone's centre is the aim (the blade then
sweeps the blocks between it and the zone along); the blade comes down behind
it, on the line through the block and the zone's centre, at the first of a few
distances back where no block lies under the blade, and stops once the aimed
block is :data:`DEPTH` inside the zone's edge (never past the centre): pushing
further would shove the blocks already inside out of the far side.

A push sweeps everything in its corridor along (the blade's width, from where it
comes down to where the blocks it drives stop), so it must not cross what other
goals have placed: the **obstacle regions** (:func:`obstacle_regions`) are the
blocks of other piles (outside this goal's zone; a marked region holding some is
an obstacle as a whole) and every other object with a body (a fixture, an ell,
a box) outside this goal's zone (one standing in it is not: the push stops
:data:`DEPTH` inside the zone's edge and the blocks it drives rest against it).
Each region grown by the blade's half width and :data:`CLEARANCE` is what the
aimed block's line must keep out of. When the straight line into the
zone crosses one, the block is routed in legs (:func:`plan_route`): around the
grown regions' corners (a visibility graph), one push per leg, the blocks left
at a corner pushed on by the next call. Blocks whose route has fewer legs are
aimed at first, the farthest among them (a block already clear of every region
goes straight in); when no block has a clear route, the straight push is the
fallback.

A block counts as in when its footprint square is inside the zone shrunk by
:data:`AIM_MARGIN` (a turned block's corners reach that far beyond its square:
Ravens' zone metric looks at corners). Blocks the caller says to avoid (aimed at
by pushes that did not help) are aimed at last.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from factask.geometry import Pose
from factask.relations.pile_in_zone import (
    PILE_KIND,
    PileInZone,
    block_inside,
    block_side,
)
from factask.relations.solving import SolvedFactor
from factask.scene.collision import WORKSPACE_AREA
from factask.scene.objects import Area, SceneObject, placement_area, yaw_rotation_2d
from factask.scene.routes import Route, RouteMap, crosses, grown, inside, ring_points
from factask.sim.robots.spatula import BLADE_THICKNESS, BLADE_WIDTH
from factask.vocabulary.world import TABLE_Z

#: Distances (m) behind the aimed block, beyond its half side and the blade's half
#: thickness, tried for the blade's way down.
BEHIND = (0.012, 0.025, 0.04, 0.06)
#: How deep (m) inside the zone's edge a push leaves the aimed block.
DEPTH = 0.02
#: The zone shrunk by this (m) is where a block counts as in for the oracle.
AIM_MARGIN = 0.004
#: A block with at least this share inside (the shrunk zone) counts as in.
IN_SHARE = 0.999
#: Room (m) between a push's corridor (the blade's width) and an obstacle region:
#: driven blocks spread a little beyond the blade's ends.
CLEARANCE = 0.015
#: How far (m) beyond a waypoint the blocks driven ahead of the aimed block reach:
#: a leg's corridor is checked that much further.
LEAD = 0.04
#: A waypoint lies this much (m) further out than a grown region's corner.
CORNER_OUT = 0.01
#: Added (m) to a route's length per extra leg: of two nearly as long, fewer pushes.
LEG_COST = 0.05
#: A waypoint closer than this (m) to the aimed block is not a leg of its own.
MIN_LEG = 0.02
#: Other piles' blocks closer than this (m) form one obstacle region (the blade
#: cannot pass between them).
LINK = BLADE_WIDTH


@dataclass(frozen=True)
class PushAction:
    """One planned push and why it was chosen.

    Attributes:
        start: (x, y, z, yaw) where the blade comes down.
        end: (x, y, z, yaw) where it stops.
        obj: The block aimed at.
        factor: The factor it works on.
        purpose: In words.
    """

    start: np.ndarray
    end: np.ndarray
    obj: str
    factor: str
    purpose: str

    def as_env_action(self) -> dict[str, np.ndarray]:
        """The env's push action: ``{"start": ..., "end": ...}``."""
        return {"start": self.start, "end": self.end}


def _blade_free(xy: np.ndarray, yaw: float, blocks: np.ndarray, margin: float) -> bool:
    """No block centre within ``margin`` of the blade's footprint at ``xy``."""
    if len(blocks) == 0:
        return True
    local = np.abs((blocks - xy) @ yaw_rotation_2d(yaw))
    half = np.array([BLADE_THICKNESS / 2, BLADE_WIDTH / 2]) + margin
    return not bool(np.any(np.all(local <= half, axis=1)))


def _zone_for(areas: list[Area], xy: np.ndarray) -> Area:
    """The region instance nearest to ``xy``."""
    return min(areas, key=lambda a: float(np.linalg.norm(a.center - xy)))


def _shrunk(area: Area, by: float) -> Area:
    """``area`` with every side moved in by ``by`` (at least a point)."""
    return Area(area.center, area.yaw, np.maximum(area.half - by, 0.0), area.round)


def entry_distance(area: Area, p: np.ndarray, u: np.ndarray, inset: float) -> float:
    """How far from ``p`` along unit ``u`` a point is ``inset`` inside ``area``'s
    edge, at most the distance to its centre (the ray aims at the centre)."""
    to_centre = float(np.linalg.norm(area.center - p))
    if area.round:
        return max(0.0, min(to_centre, to_centre - (area.half[0] - inset)))
    rot = yaw_rotation_2d(area.yaw)
    q, v = (p - area.center) @ rot, u @ rot
    half = np.maximum(area.half - inset, 0.0)
    t_in = 0.0
    for i in range(2):
        if abs(v[i]) < 1e-9:
            continue  # moving along this slab: the other axis decides
        t1, t2 = (-half[i] - q[i]) / v[i], (half[i] - q[i]) / v[i]
        t_in = max(t_in, min(t1, t2))
    return float(min(max(t_in, 0.0), to_centre))


def _clusters(xy: np.ndarray, side: float) -> list[Area]:
    """Axis-aligned boxes around groups of blocks closer than :data:`LINK` to each other."""
    n = len(xy)
    parent = list(range(n))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i in range(n):
        close = np.nonzero(np.linalg.norm(xy[i + 1:] - xy[i], axis=1) < LINK)[0]
        for j in close:
            parent[root(i)] = root(i + 1 + int(j))
    groups: dict[int, list[int]] = {}
    for i in range(n):
        groups.setdefault(root(i), []).append(i)
    out = []
    for members in groups.values():
        pts = xy[members]
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        # A turned block reaches half its diagonal beyond its centre.
        out.append(Area((lo + hi) / 2, 0.0, (hi - lo) / 2 + side * math.sqrt(0.5)))
    return out


def obstacle_regions(solved: SolvedFactor, objects: Mapping[str, SceneObject],
                     poses: Mapping[str, Pose], held: Collection[str]) -> list[Area]:
    """What a push for the factor ``solved`` must not sweep through (ungrown).

    The blocks of other piles, except those inside this factor's own regions (two
    piles may share a zone), as boxes around groups of them; a marked region (a
    zone) holding any such block, as a whole; every other object with a body
    (fixtures, ells, boxes) outside this factor's zones, its footprint. Held
    objects are off the table.

    Args:
        solved: The factor's solved targets (its blocks and regions).
        objects: Scene objects by instance name.
        poses: Current poses of every instance.
        held: Instances held now.

    Returns:
        The regions, as rectangles.
    """
    own_blocks, own_regions = set(solved.objects), set(solved.regions)
    zones = [placement_area(objects[r], poses[r]) for r in solved.regions]
    others = [n for n, o in objects.items()
              if o.kind == PILE_KIND and n not in own_blocks and n not in held]
    xy = np.array([poses[n].pos[:2] for n in others]).reshape(-1, 2)
    if len(xy) and zones:
        xy = xy[~np.any([z.contains(xy) for z in zones], axis=0)]
    out: list[Area] = []
    for name, obj in objects.items():
        if name in own_blocks or name in own_regions or name in held or obj.kind == PILE_KIND:
            continue
        pose = poses[name]
        if obj.collides:
            # A body standing in this goal's zone (a fixture) is no obstacle: the push
            # stops DEPTH inside the zone's edge, the blocks it drives rest against it.
            if not any(z.contains(pose.pos[None, :2])[0] for z in zones):
                out.append(Area(pose.pos[:2].copy(), pose.yaw, obj.half_xy))
        elif obj.spec.region and len(xy):
            area = placement_area(obj, pose)
            if area.contains(xy).any():
                out.append(area)
    if len(xy):
        out += _clusters(xy, block_side(objects[others[0]]))
    return out


def plan_route(blocks: np.ndarray, zones: Sequence[Area], regions: Sequence[Area],
               back: float) -> list[Route | None]:
    """Each block's route into the nearest reachable of ``zones`` clear of ``regions``.

    A leg from ``q`` to ``w`` is clear when its corridor, from ``back`` behind
    ``q`` (where the blade comes down) to :data:`LEAD` beyond ``w``, keeps out of
    every region grown by the blade's half width and :data:`CLEARANCE`; a last leg
    goes towards a zone's centre and is checked until it enters the zone (inside,
    the push stops short of the centre). From a block inside a grown region, that
    region counts ungrown (a block beside a zone may be pushed away from it), and
    not at all when the block is inside it.

    Args:
        blocks: (k, 2) block centres.
        zones: The goal's regions.
        regions: Obstacle regions (:func:`obstacle_regions`).
        back: How far behind a leg's start the blade comes down (m).

    Returns:
        Per block its :class:`Route`, or None when none is clear.
    """
    grown_regions = [grown(r, BLADE_WIDTH / 2 + CLEARANCE) for r in regions]

    def goal_leg(rects: Sequence[Area]) -> Callable[[np.ndarray], tuple[float, int]]:
        def leg(q: np.ndarray) -> tuple[float, int]:
            best = (math.inf, 0)
            for k, zone in enumerate(zones):
                d = zone.center - q
                length = float(np.linalg.norm(d))
                if length < 1e-9:
                    return (0.0, k)
                u = d / length
                enter = q + u * entry_distance(zone, q, u, 0.0)
                if not any(crosses(q - u * back, enter, r) for r in rects):
                    best = min(best, (length, k))
            return best
        return leg

    def clear(rects: Sequence[Area]) -> Callable[[np.ndarray, np.ndarray], bool]:
        def leg(q: np.ndarray, w: np.ndarray) -> bool:
            d = w - q
            u = d / max(float(np.linalg.norm(d)), 1e-9)
            return not any(crosses(q - u * back, w + u * LEAD, r) for r in rects)
        return leg

    # Waypoints: the grown regions' corners, CORNER_OUT further out, in the room and
    # outside every grown region.
    room = _shrunk(WORKSPACE_AREA, BLADE_WIDTH / 2)
    nodes = [p for p in ring_points(grown_regions, CORNER_OUT, edges=False)
             if room.contains(p[None])[0] and not any(inside(g, p) for g in grown_regions)]
    routes = RouteMap(nodes, goal_leg(grown_regions), clear(grown_regions), LEG_COST)
    out: list[Route | None] = []
    for p in np.asarray(blocks, dtype=float).reshape(-1, 2):
        # From inside a grown region: that region ungrown, or none if inside that too.
        rects = [g if not inside(g, p) else r
                 for g, r in zip(grown_regions, regions, strict=True) if not inside(r, p)]
        out.append(routes.route_from(p, goal_leg(rects), clear(rects), MIN_LEG))
    return out


def plan_push(factor: str, goal: PileInZone, solved: SolvedFactor,
              objects: Mapping[str, SceneObject], poses: Mapping[str, Pose],
              held: set[str], avoid: Collection[str] = ()) -> PushAction | None:
    """The next push for a ``pile_in_zone`` factor, or None when no block is outside.

    Args:
        factor: The factor's name.
        goal: Its relation.
        solved: Its solved targets (the regions).
        objects: Scene objects by instance name.
        poses: Current poses of every instance.
        held: Instances held now (never aimed at).
        avoid: Blocks to aim at only when no other is outside.
    """
    del goal  # the relation's threshold decides when to stop, not where to push
    areas = [placement_area(objects[r], poses[r]) for r in solved.regions]
    names = [n for n in solved.objects if n not in held]
    xy = np.array([poses[n].pos[:2] for n in names])
    side = block_side(objects[names[0]]) if names else 0.0
    inner = [_shrunk(a, AIM_MARGIN) for a in areas]
    share = np.max([block_inside(a, xy, side) for a in inner], axis=0) if names else []
    out = [i for i, s in enumerate(share) if s < IN_SHARE]
    if not out:
        return None
    base = side / 2 + BLADE_THICKNESS / 2
    regions = obstacle_regions(solved, objects, poses, held)
    if regions:
        routes = plan_route(xy[out], areas, regions, base + BEHIND[0])
    else:  # nothing in the way: every block straight into its nearest zone
        routes = [min((Route(1, float(np.linalg.norm(xy[i] - a.center)), None, k)
                       for k, a in enumerate(areas)), key=lambda r: r.length) for i in out]
    by_block = dict(zip(out, routes, strict=True))

    def rank(i: int) -> tuple[bool, int, float]:
        route = by_block[i]
        if route is None:  # no clear route: straight in, after every routed block
            return (names[i] not in avoid, -10**6,
                    float(np.linalg.norm(xy[i] - _zone_for(areas, xy[i]).center)))
        # Fewest legs first, farthest among them; blocks to avoid after every other.
        return (names[i] not in avoid, -route.legs, route.length)

    aim = max(out, key=rank)
    p = xy[aim]
    route = by_block[aim]
    via = route.via if route is not None else None
    zone = areas[route.goal] if route is not None else _zone_for(areas, p)
    d = (via if via is not None else zone.center) - p
    length = float(np.linalg.norm(d))
    u = d / length if length > 1e-9 else np.array([1.0, 0.0])
    yaw = math.atan2(u[1], u[0])
    margin = side / 2
    start = p - u * (base + BEHIND[-1])
    for back in BEHIND:
        cand = p - u * (base + back)
        if _blade_free(cand, yaw, xy, margin):
            start = cand
            break
    if via is not None:  # the blade stops with the aimed block on the waypoint
        end = via - u * base
        purpose = (f"push {names[aim]} towards {solved.regions[0]}, leg 1 of "
                   f"{route.legs if route else 1} around other goals' regions")
    else:
        # The blade's face stops where the aimed block is DEPTH inside the edge.
        reach = entry_distance(zone, p, u, side / 2 + DEPTH)
        end = p + u * (reach - base)
        purpose = f"push {names[aim]} towards {solved.regions[0]}"
    if float(np.dot(end - start, u)) < base + side:  # always push a little
        end = start + u * (base + side + BEHIND[0])
    return PushAction(np.array([*start, TABLE_Z, yaw]), np.array([*end, TABLE_Z, yaw]),
                      names[aim], factor, purpose)
