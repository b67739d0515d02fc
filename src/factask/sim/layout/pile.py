"""Piles: where the K small blocks of a ``pile`` variable start (a cluster).

A pile variable (kind ``pile``, see :mod:`factask.vocabulary.kinds`) stands for
``count`` small blocks that are pushed, never picked one by one. They start as
one cluster, as Ravens' sweeping tasks spawn them: a jittered grid of blocks
around one random centre, the whole cluster free of every other object. The
blocks of one cluster keep a small gap between them (:data:`PILE_GAP`), less
than the layout clearance between objects (a pile is one thing), so a pile of
50 blocks of 1 cm covers about 14 x 14 cm.

Pure numpy, like the rest of the layout (:mod:`factask.sim.layout.sampling` calls
:func:`place_pile`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from factask.geometry import Pose
from factask.relations.pile_in_zone import PILE_KIND
from factask.scene.collision import WORKSPACE_CENTER, WORKSPACE_HALF, Occupancy, in_workspace
from factask.scene.objects import SceneObject, resting_pose
from factask.vocabulary.variables import AtFixedPose, InRegion, StateVariable
from factask.vocabulary.world import TABLE_Z

#: Gap (m) between neighbouring blocks of a cluster, beyond a block's diagonal
#: (any yaw fits its cell).
PILE_GAP = 0.003
#: Random jitter of a block inside its cell, as a fraction of the cell's slack.
PILE_JITTER = 0.8


def is_pile(var: StateVariable) -> bool:
    """True when ``var`` is a pile of small blocks."""
    return var.kind == PILE_KIND


def pile_pitch(block: tuple[float, float, float]) -> float:
    """Centre-to-centre distance (m) of neighbouring blocks in a starting cluster."""
    return math.hypot(block[0], block[1]) + PILE_GAP


def pile_half_extent(var: StateVariable) -> float:
    """Half side (m) of the square a pile's starting cluster covers."""
    cols = math.ceil(math.sqrt(var.count))
    return cols * pile_pitch(var.extents) / 2


def layout_area(var: StateVariable) -> float:
    """Table area (m^2) a variable's objects take at the start, for the placement
    order (the larger first): a pile's whole cluster, else one object's footprint."""
    if is_pile(var):
        return (2 * pile_half_extent(var)) ** 2
    if var.kind == "rope":  # laid out straight: its whole length
        return var.count * var.extents[0] * var.extents[1]
    ex = var.extents
    return ex[0] * ex[1]


def cluster_offsets(count: int, pitch: float, rng: np.random.Generator,
                    slack: float) -> np.ndarray:
    """(count, 2) block centres of a cluster around (0, 0): the first ``count`` cells
    of a square grid, in random cell order, each jittered by up to ``slack`` / 2.

    Args:
        count: Number of blocks.
        pitch: Cell size (m).
        rng: Random generator.
        slack: Room (m) a block has in its cell.
    """
    cols = math.ceil(math.sqrt(count))
    cells = rng.permutation(cols * cols)[:count]
    ij = np.stack([cells // cols, cells % cols], axis=1).astype(float)
    centre = (cols - 1) / 2
    xy = (ij - centre) * pitch
    return xy + rng.uniform(-0.5, 0.5, size=(count, 2)) * slack * PILE_JITTER


def place_pile(var: StateVariable, objs: Mapping[str, SceneObject], occ: Occupancy,
               rng: np.random.Generator, tries: int) -> dict[str, Pose] | None:
    """Start poses of every block of pile ``var``: one cluster free of ``occ``.

    Args:
        var: The pile variable.
        objs: Scene objects by instance name.
        occ: What is already placed (the blocks are added to it when placed).
        rng: Random generator.
        tries: Cluster centres to try.

    Returns:
        Instance -> pose, or None when no centre in ``tries`` gave a free cluster.
    """
    insts = var.instances
    first = objs[insts[0]]
    pitch = pile_pitch(first.size)
    half = pile_half_extent(var)
    if isinstance(var.initial, AtFixedPose):  # the cluster's centre is given
        lo = hi = np.array([var.initial.x, var.initial.y])
    elif isinstance(var.initial, InRegion):
        lo = np.array([var.initial.x[0], var.initial.y[0]]) + half
        hi = np.array([var.initial.x[1], var.initial.y[1]]) - half
    else:
        lo = WORKSPACE_CENTER - WORKSPACE_HALF + half
        hi = WORKSPACE_CENTER + WORKSPACE_HALF - half
    if np.any(lo > hi):  # the region is smaller than the cluster: centre it there
        lo = hi = (lo + hi) / 2
    slack = pitch - math.hypot(first.size[0], first.size[1])
    for _ in range(tries):
        centre = rng.uniform(lo, hi)
        xy = centre + cluster_offsets(len(insts), pitch, rng, slack)
        yaws = rng.uniform(-math.pi, math.pi, size=len(insts))
        poses = [resting_pose(objs[i], float(p[0]), float(p[1]), TABLE_Z, float(a))
                 for i, p, a in zip(insts, xy, yaws, strict=True)]
        if not all(in_workspace(objs[i], p) for i, p in zip(insts, poses, strict=True)):
            continue
        if not occ.free_mask(first, poses).all():
            continue
        for inst, pose in zip(insts, poses, strict=True):
            occ.put(inst, objs[inst], pose)
        return dict(zip(insts, poses, strict=True))
    return None
