"""Small helpers shared by several test modules."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from factask.geometry import Pose, quat_from_axis_angle, quat_mul
from factask.graph import TaskGraph
from factask.scene.objects import footprint_corners, obb_overlaps
from factask.sim.env import FactaskEnv

#: The benchmark task list shipped inside the package.
GENSIM_TASKS = (Path(__file__).resolve().parents[1] / "src" / "factask" / "data"
                / "gensim_tasks.json")
#: The CLIPort original task files, shipped inside the package.
CLIPORT_ORIGINALS = (Path(__file__).resolve().parents[1] / "src" / "factask" / "data"
                     / "cliport_tasks")


def make_graph(variables: list[dict[str, Any]], factors: list[dict[str, Any]],
               name: str = "t") -> TaskGraph:
    """A validated graph; factor weights default to equal shares."""
    for f in factors:
        f.setdefault("weight", 1.0 / len(factors))
    return TaskGraph.model_validate(
        {"name": name, "variables": variables, "factors": factors}).ensure_valid()


def free_spot(env: FactaskEnv, half: float = 0.04, seed: int = 0,
              tries: int = 1000) -> np.ndarray:
    """An (x, y) in the workspace with no object (nor target) within ``half`` metres."""
    occupied = [footprint_corners(env.objects[n], p, 0.02) for n, p in env.object_poses().items()]
    for solved in env.solved.values():
        occupied += [footprint_corners(env.objects[n], p, 0.02)
                     for n, p in solved.targets(env.objects).items()]
    occ = np.array(occupied).reshape(-1, 4, 2)
    rng = np.random.default_rng(seed)
    for _ in range(tries):
        xy = rng.uniform([0.3, -0.45], [0.7, 0.45])
        square = np.array([[xy[0] - half, xy[1] - half], [xy[0] + half, xy[1] - half],
                           [xy[0] + half, xy[1] + half], [xy[0] - half, xy[1] + half]])
        if not obb_overlaps(square[None], occ).any():
            return xy
    raise AssertionError("no free spot found in the workspace")


def perturbed(pose: Pose, d: tuple[float, float, float, float, float]) -> Pose:
    """``pose`` moved by (dx, dy, dz) m, turned by dyaw and tilted by dtilt degrees."""
    dx, dy, dz, dyaw, dtilt = d
    q = quat_mul(quat_from_axis_angle((0.0, 0.0, 1.0), math.radians(dyaw)), pose.quat)
    q = quat_mul(quat_from_axis_angle((1.0, 0.0, 0.0), math.radians(dtilt)), q)
    return Pose(pose.pos + np.array([dx, dy, dz]), q)
