"""How the oracle plans a push for a ``pile_in_zone`` goal.

Aimed at the remaining blocks, from outside the zone towards it: the block
outside the zone farthest from the zone's centre is the aim (the blade then
sweeps the blocks between it and the zone along); the blade comes down behind
it, on the line through the block and the zone's centre, at the first of a few
distances back where no block lies under the blade, and stops once the aimed
block is :data:`DEPTH` inside the zone's edge (never past the centre): pushing
further would shove the blocks already inside out of the far side.

A block counts as in when its footprint square is inside the zone shrunk by
:data:`AIM_MARGIN` (a turned block's corners reach that far beyond its square:
Ravens' zone metric looks at corners). Blocks the caller says to avoid (aimed at
by pushes that did not help) are aimed at last.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping
from dataclasses import dataclass

import numpy as np

from factask.geometry import Pose
from factask.model.world import TABLE_Z
from factask.relations.pile_in_zone import PileInZone, block_inside, block_side
from factask.relations.solving import SolvedFactor
from factask.scene.objects import Area, SceneObject, placement_area, yaw_rotation_2d
from factask.sim.push import BLADE_THICKNESS, BLADE_WIDTH

#: Distances (m) behind the aimed block, beyond its half side and the blade's half
#: thickness, tried for the blade's way down.
BEHIND = (0.012, 0.025, 0.04, 0.06)
#: How deep (m) inside the zone's edge a push leaves the aimed block.
DEPTH = 0.02
#: The zone shrunk by this (m) is where a block counts as in for the oracle.
AIM_MARGIN = 0.004
#: A block with at least this share inside (the shrunk zone) counts as in.
IN_SHARE = 0.999


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
    # Farthest first; blocks to avoid after every other.
    aim = max(out, key=lambda i: (names[i] not in avoid, float(np.linalg.norm(
        xy[i] - _zone_for(areas, xy[i]).center))))
    p = xy[aim]
    zone = _zone_for(areas, p)
    d = zone.center - p
    length = float(np.linalg.norm(d))
    u = d / length if length > 1e-9 else np.array([1.0, 0.0])
    yaw = math.atan2(u[1], u[0])
    base = side / 2 + BLADE_THICKNESS / 2
    margin = side / 2
    start = p - u * (base + BEHIND[-1])
    for back in BEHIND:
        cand = p - u * (base + back)
        if _blade_free(cand, yaw, xy, margin):
            start = cand
            break
    # The blade's face stops where the aimed block is DEPTH inside the edge.
    reach = entry_distance(zone, p, u, side / 2 + DEPTH)
    end = p + u * (reach - base)
    if float(np.dot(end - start, u)) < base + side:  # always push a little
        end = start + u * (base + side + BEHIND[0])
    return PushAction(np.array([*start, TABLE_Z, yaw]), np.array([*end, TABLE_Z, yaw]),
                      names[aim], factor, f"push {names[aim]} towards {solved.regions[0]}")
