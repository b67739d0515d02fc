"""Where the cup takes a receptacle, in every world at once: the batched twin of
:func:`factask.sim.oracle.pick_points.grasp_offset`.

A receptacle is taken on its rim: of the candidate points in the middle of its walls
(:func:`~factask.sim.oracle.pick_points.rim_points`), one whose cup disk keeps
:data:`~factask.sim.oracle.pick_points.CUP_GAP` clear of everything that stands as high
as the rim, the one nearest the robot's base; where none is clear, the clearest.
Here the candidates of one receptacle are scored against every object in every world
as arrays (points x objects x worlds).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from factask.batch.geometry import rotate_2d, to_local_2d, yaws
from factask.scene.objects import SceneObject
from factask.sim.oracle.pick_points import CUP_GAP, LEVEL_MARGIN, rim_points
from factask.sim.robots.suction import CUP_RADIUS
from factask.vocabulary.world import ROBOT_BASE


def rim_offsets(column: int, objects: Sequence[SceneObject], pos: np.ndarray,
                quat: np.ndarray, tops: np.ndarray) -> np.ndarray:
    """World XY offset (s, 2) from receptacle ``column``'s centre to where the cup
    takes it, in each of ``s`` worlds.

    Args:
        column: The receptacle's column in the scene.
        objects: Every scene object, in column order.
        pos: Every object's position per world (s, N, 3).
        quat: Every object's orientation per world (s, N, 4).
        tops: Every object's highest point per world (s, N).

    Returns:
        The offsets (s, 2).
    """
    me = objects[column]
    centre = pos[:, column, :2]  # (s, 2)
    offsets = rotate_2d(rim_points(me)[None], yaws(quat[:, column])[:, None])  # (s, K, 2)
    points = centre[:, None] + offsets
    rim = tops[:, column]
    gaps = np.full(points.shape[:2], np.inf)
    for c, other in enumerate(objects):
        if c == column or not other.collides:
            continue
        level = tops[:, c] > rim - LEVEL_MARGIN  # (s,)
        local = to_local_2d(points - pos[:, c, None, :2], yaws(quat[:, c])[:, None])
        if other.spec.round:
            dist = np.maximum(np.linalg.norm(local, axis=-1) - other.half_xy[0], 0.0)
        else:
            dist = np.linalg.norm(np.maximum(np.abs(local) - other.half_xy, 0.0), axis=-1)
        gaps = np.where(level[:, None], np.minimum(gaps, dist), gaps)
    gaps -= CUP_RADIUS
    reach = np.linalg.norm(points - np.asarray(ROBOT_BASE[:2], dtype=float), axis=-1)
    clear = gaps >= CUP_GAP
    best = np.where(clear.any(axis=1), np.where(clear, reach, np.inf).argmin(axis=1),
                    gaps.argmax(axis=1))
    return offsets[np.arange(len(best)), best]


__all__ = ["rim_offsets"]
