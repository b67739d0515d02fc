"""Packing objects into an area: a grid, a ring in a round area, or random free spots.

Shared by the relations that put objects *into* something (``in_zone``,
``inside``, ``on``): even attempts pack a grid (tight, reliable), odd ones random
free spots (which work around objects already resting there).
"""

from __future__ import annotations

import math

import numpy as np

from factask.geometry import Pose
from factask.relations.solving import Infeasible, SolveContext
from factask.scene.collision import (
    CLEARANCE,
    MAX_TRIES_PER_OBJECT,
    TABLE,
    area_candidates,
    first_free,
)
from factask.scene.objects import (
    GEOMETRY_EPS,
    Area,
    SceneObject,
    footprint_radius,
    placement_area,
    rest_surface_z,
    resting_pose,
    yaw_rotation_2d,
)

#: Distance (m) a packed grid keeps from the edge of its area when it can.
EDGE_MARGIN = 0.004


def grid(movers: list[SceneObject], area: Area, rng: np.random.Generator,
         what: str) -> tuple[list[np.ndarray], float]:
    """Centres (and yaw) of a grid of the objects inside ``area`` with a random offset.

    Raises:
        Infeasible: the grid does not fit (not retryable).
    """
    n = len(movers)
    if area.round:
        ring = ring_in_disk(movers, area, rng)
        if ring is not None:
            return ring, area.yaw
    half = area.packing_half()
    size = np.array([[o.size[0], o.size[1]] for o in movers]).max(axis=0)
    best = None
    # Keep the outer objects EDGE_MARGIN off the area's edge (a wall, a zone's
    # border) so physics jitter cannot push them partly outside; only a grid that
    # fits no other way touches the edge.
    for margin in (EDGE_MARGIN, 0.0):
        length = 2 * half - 2 * margin
        for turn in (0.0, math.pi / 2):
            cell = (size if turn == 0.0 else size[::-1]) + CLEARANCE
            cap = np.floor((length + CLEARANCE) / cell + GEOMETRY_EPS).astype(int)
            if cap[0] * cap[1] >= n and cap.min() >= 1:
                best = (turn, cell, cap)
                break
        if best is not None:
            break
    if best is None:
        raise Infeasible(f"{n} object(s) of up to {size[0]:.3f} x {size[1]:.3f} m do not fit "
                         f"in {what} ({length[0]:.3f} x {length[1]:.3f} m usable)",
                         retry=False)
    turn, cell, cap = best
    cols = int(min(cap[0], n))
    rows = math.ceil(n / cols)
    used = np.array([cols * cell[0] - CLEARANCE, rows * cell[1] - CLEARANCE])
    slack = np.maximum(length - used, 0.0)
    offset = rng.uniform(-slack / 2, slack / 2)
    centres = []
    rot = yaw_rotation_2d(area.yaw)
    for k in range(n):
        r, c = divmod(k, cols)
        local = np.array([(c - (cols - 1) / 2) * cell[0], (r - (rows - 1) / 2) * cell[1]])
        centres.append(area.center + rot @ (local + offset))
    return centres, area.yaw + turn


def clear_radius(obj: SceneObject) -> float:
    """Half the centre distance at which two such objects keep the clearance whatever
    their yaw (a box's grown corner reaches clearance/2 * sqrt(2) further)."""
    grow = CLEARANCE / 2 * (1.0 if obj.is_round else math.sqrt(2.0))
    return footprint_radius(obj) + grow


def ring_in_disk(movers: list[SceneObject], area: Area,
                 rng: np.random.Generator) -> list[np.ndarray] | None:
    """Centres of the objects on a ring inside a disk area (None if they do not fit)."""
    n = len(movers)
    rad = max(footprint_radius(o) for o in movers)
    ring = max(clear_radius(o) for o in movers) / math.sin(math.pi / n) if n > 1 else 0.0
    if ring + rad > area.half[0] + GEOMETRY_EPS:
        return None
    phase = float(rng.uniform(0.0, 2 * math.pi))
    return [area.center + ring * np.array([math.cos(phase + 2 * math.pi * k / n),
                                           math.sin(phase + 2 * math.pi * k / n)])
            for k in range(n)]


def pack_plan(ctx: SolveContext, movers: list[SceneObject],
              groups: list[tuple[str, list[int]]],
              attempt_sampling: bool) -> tuple[list[Pose], list[float | None], list[str]]:
    """Slots for objects packed into the area of each host (grid, or random spots)."""
    n = len(movers)
    slots: list[Pose | None] = [None] * n
    surfaces: list[float | None] = [None] * n
    supports = [TABLE] * n
    for host, members in groups:
        hobj, hpose = ctx.objs[host], ctx.current[host]
        area = placement_area(hobj, hpose)
        surface = rest_surface_z(hobj, hpose)
        mobjs = [movers[i] for i in members]
        if attempt_sampling:
            trial = ctx.occ.copy()
            for i, obj in zip(members, mobjs, strict=True):
                yaws = area.yaw + (math.pi / 2) * ctx.rng.integers(0, 2, MAX_TRIES_PER_OBJECT)
                pose = first_free(trial, obj, area_candidates(
                    obj, area, surface, ctx.rng, MAX_TRIES_PER_OBJECT, yaws), [host], area)
                if pose is None:
                    raise Infeasible(f"no free spot for {obj.name} in {host!r}")
                trial.put(f"@{obj.name}", obj, pose)
                slots[i] = pose
        else:
            centres, yaw = grid(mobjs, area, ctx.rng, repr(host))
            for i, obj, c in zip(members, mobjs, centres, strict=True):
                slots[i] = resting_pose(obj, float(c[0]), float(c[1]), surface, yaw)
        for i in members:
            surfaces[i] = surface
            supports[i] = host
    return [s for s in slots if s is not None], surfaces, supports

