"""Stand-in for ``cliport.utils.utils``: colours and pose helpers task code uses.

Colours are factask's palette (:mod:`factask.vocabulary.palette`), which starts with
the Ravens/Tableau values, as RGB lists (task code writes ``COLORS[name] + [1]``).
Unlike GenSim, an unknown colour name is an error listing the valid names, not
silently red. Names this module does not provide raise
:class:`~factask.compat.cliport.errors.Unsupported` naming them.
"""

from __future__ import annotations

import random
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from factask.compat.cliport import transforms
from factask.compat.cliport.errors import UnknownColorNameError, Unsupported
from factask.geometry import quat_mul
from factask.vocabulary.palette import COLORS as PALETTE

#: The names GenSim's ``utils.COLORS`` holds, in its order: what task code iterating
#: over the palette (``for c in utils.COLORS``, ``utils.COLORS_NAMES[:n]``) sees.
#: factask's palette has more colours; they are looked up, never iterated.
GENSIM_COLOR_NAMES = ("blue", "red", "green", "orange", "yellow", "purple", "pink", "cyan",
                      "brown", "white", "gray", "indigo", "violet", "black", "silver", "gold")


class _Colors(dict):  # type: ignore[type-arg]
    """Name -> RGB list; a copy on every lookup (callers append alpha in place).
    Iterates GenSim's names; any name of factask's palette is looked up."""

    def __getitem__(self, key: Any) -> list[float]:
        if key in self:
            return list(dict.__getitem__(self, key))
        if isinstance(key, str) and key in PALETTE:
            return list(PALETTE[key])
        raise UnknownColorNameError(f"unknown colour {key!r}; valid colours: {', '.join(self)}")

    def get(self, key: Any, default: Any = None) -> Any:
        try:
            return self[key]
        except KeyError:
            return default


#: Colour name -> [r, g, b] in [0, 1].
COLORS: dict[str, list[float]] = _Colors({n: list(PALETTE[n]) for n in GENSIM_COLOR_NAMES})
COLORS_NAMES = list(GENSIM_COLOR_NAMES)
#: Ravens' colour splits.
TRAIN_COLORS = ["blue", "red", "green", "yellow", "brown", "gray", "cyan"]
EVAL_COLORS = ["blue", "red", "green", "orange", "purple", "pink", "white"]


def get_colors_names(mode: str = "train") -> list[str]:
    """Colour names of a split, as CLIPort/GenSim give them: ``train`` the train
    colours, ``full`` train then eval (three names twice, as there), any other
    mode the eval colours."""
    if mode == "train":
        return list(TRAIN_COLORS)
    if mode == "full":
        return TRAIN_COLORS + EVAL_COLORS
    return list(EVAL_COLORS)


def get_colors(mode: str = "train", n_colors: int = -1, **kwargs: Any
               ) -> tuple[list[list[float]], list[str]]:
    """``n_colors`` colours of the mode's split, drawn without replacement (all of
    them if -1): (RGB lists, names)."""
    names = get_colors_names(mode)
    if n_colors != -1:
        names = random.sample(names, n_colors)
    return [COLORS[n] for n in names], names


def get_random_color() -> tuple[list[list[float]], list[str]]:
    """One random train colour, as GenSim returns it."""
    return get_colors(mode="train", n_colors=1)


def invert(pose: Any) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Inverse of a (position, quaternion xyzw) pose."""
    return transforms.invert(pose)


def multiply(pose0: Any, pose1: Any) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Product ``pose0 * pose1`` of two poses."""
    return transforms.multiply(pose0, pose1)


def apply(pose: Any, position: Any) -> tuple[Any, ...]:
    """Move point(s) ``position`` ((3,) or (3, N)) into the frame of ``pose``."""
    pts = np.float32(position)
    shape = pts.shape
    pts = pts.reshape(3, -1)
    pos, quat = transforms.split_pose(pose)
    rot = np.float32(Rotation.from_quat(quat).as_matrix())
    out = rot @ pts + np.float32(pos).reshape(3, 1)
    return tuple(out.reshape(shape))


def eulerXYZ_to_quatXYZW(rotation: Any) -> tuple[float, ...]:
    """Quaternion xyzw of Euler angles (x, y, z) in CLIPort's convention (static z-x-y)."""
    rx, ry, rz = (float(c) for c in rotation)
    return tuple(float(c) for c in Rotation.from_euler("zxy", [rz, rx, ry]).as_quat())


def quatXYZW_to_eulerXYZ(quaternion_xyzw: Any) -> tuple[float, ...]:
    """Euler angles (x, y, z) of a quaternion xyzw, inverse of :func:`eulerXYZ_to_quatXYZW`."""
    rz, rx, ry = Rotation.from_quat(transforms.as_quat_xyzw(quaternion_xyzw)).as_euler("zxy")
    return float(rx), float(ry), float(rz)


def q_mult(q1: Any, q2: Any) -> tuple[float, ...]:
    """Product of two (w, x, y, z) quaternions (CLIPort's ``q_mult`` order)."""
    product = quat_mul(np.asarray(q1, dtype=float), np.asarray(q2, dtype=float))
    return tuple(float(c) for c in product)


def sample_distribution(prob: Any, n_samples: int = 1) -> np.ndarray:
    """Sample pixel coordinates in proportion to ``prob`` (uses ``np.random``)."""
    prob = np.asarray(prob, dtype=float)
    flat = prob.flatten() / np.sum(prob)
    idx = np.random.choice(np.arange(len(flat)), n_samples, p=flat, replace=False)
    return np.int32(np.array(np.unravel_index(idx, prob.shape)).T.squeeze())


def xyz_to_pix(position: Any, bounds: Any, pixel_size: float) -> tuple[int, int]:
    """Pixel (row, column) of a world position in CLIPort's top-down heightmap."""
    bounds = np.asarray(bounds)
    u = int(np.round((position[1] - bounds[1, 0]) / pixel_size))
    v = int(np.round((position[0] - bounds[0, 0]) / pixel_size))
    return u, v


def pix_to_xyz(pixel: Any, height: Any, bounds: Any, pixel_size: float,
               skip_height: bool = False) -> tuple[float, float, float]:
    """World position of a heightmap pixel (height from ``height`` unless skipped)."""
    bounds = np.asarray(bounds)
    u, v = int(pixel[0]), int(pixel[1])
    x = bounds[0, 0] + v * pixel_size
    y = bounds[1, 0] + u * pixel_size
    z = 0.0 if skip_height else bounds[2, 0] + float(np.asarray(height)[u, v])
    return float(x), float(y), float(z)


def solve_hanoi_all(n_disks: int) -> list[list[int]]:
    """Moves [disk, from rod, to rod] solving Towers of Hanoi from rod 0 to rod 2."""
    steps: list[list[int]] = []

    def solve(n: int, t0: int, t1: int, t2: int) -> None:
        if n == 0:
            steps.append([n, t0, t1])
            return
        solve(n - 1, t0, t2, t1)
        steps.append([n, t0, t1])
        solve(n - 1, t2, t1, t0)

    solve(n_disks - 1, 0, 2, 1)
    return steps


class TreeNode:
    """A node of GenSim's box-splitting tree: ``bbox`` is (min x, min y, min z,
    max x, max y, max z)."""

    def __init__(self, parent: TreeNode | None, children: list[TreeNode], bbox: Any) -> None:
        self.parent = parent
        self.children = children
        self.bbox = np.asarray(bbox, dtype=float)


#: Leaves one box split may produce at most (a guard against absurd arguments).
MAX_KD_LEAVES = 10_000


def KDTree(node: TreeNode, min_object_dim: float, margin: float,
           bboxes: list[Any]) -> None:
    """Split ``node``'s box into boxes no side of which is over twice ``min_object_dim``,
    ``margin`` apart, appending the leaves to ``bboxes`` (GenSim's ``utils.KDTree``).

    The axis to cut is drawn among those still long enough, the cut position
    uniformly between ``min_object_dim`` from either end; both draws use
    ``np.random``, depth first, first child first (so a seed gives GenSim's boxes).

    Raises:
        Unsupported: the split would make more than :data:`MAX_KD_LEAVES` boxes
            (``min_object_dim`` far too small for the box).
    """
    if not min_object_dim > 0 or not np.all(np.isfinite(node.bbox)):
        raise Unsupported(f"utils.KDTree: min_object_dim must be > 0 and the box finite, "
                          f"got {min_object_dim!r} and {node.bbox.tolist()}")
    stack = [node]
    leaves = 0
    while stack:
        current = stack.pop()
        size = current.bbox[3:] - current.bbox[:3]
        long_enough = size > 2 * min_object_dim
        if not long_enough.any():
            bboxes.append(current.bbox)
            leaves += 1
            if leaves > MAX_KD_LEAVES:
                raise Unsupported(f"utils.KDTree: more than {MAX_KD_LEAVES} boxes; "
                                  "min_object_dim is too small for the box")
            continue
        weights = long_enough.astype(float) / long_enough.sum()
        axis = int(np.random.choice(range(len(weights)), 1, p=weights)[0])
        cut = (np.random.rand() * (size[axis] - 2 * min_object_dim)
               + current.bbox[axis] + min_object_dim)
        low, high = current.bbox.copy(), current.bbox.copy()
        low[3 + axis] = cut - margin / 2
        high[axis] = cut + margin / 2
        current.children = [TreeNode(current, [], low), TreeNode(current, [], high)]
        stack.extend(reversed(current.children))  # the first child is split first


def set_seed(seed: int, torch: bool = False) -> None:
    """Seed ``random`` and ``np.random`` (torch is not used here)."""
    random.seed(seed)
    np.random.seed(seed)


def __getattr__(name: str) -> Any:
    if name.startswith("__"):
        raise AttributeError(name)
    raise Unsupported(f"cliport.utils.utils.{name} is not provided by factask's CLIPort layer")
