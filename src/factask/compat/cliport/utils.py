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


def map_kit_scale(scale: Any) -> tuple[float, float, float]:
    """GenSim's kit-shape scale: the mesh's (x, y, z) scale divided by ten."""
    return (float(scale[0]) / 10, float(scale[1]) / 10, float(scale[2]) / 10)


#: CLIPort's image statistics per input distribution: (colour mean, colour std) of
#: pixels scaled to [0, 1], the same for r, g and b where one number is given.
IMAGE_STATS: dict[str, tuple[tuple[float, float, float], tuple[float, float, float]]] = {
    "transporter": ((0.18877631,) * 3, (0.07276466,) * 3),
    "franka": ((0.622291933, 0.628313992, 0.623031488), (0.168154213, 0.17626014, 0.184527364)),
    "clip": ((0.48145466, 0.4578275, 0.40821073), (0.26862954, 0.26130258, 0.27577711)),
    "mdetr": ((0.485, 0.456, 0.406), (0.229, 0.224, 0.225)),
}
#: (depth mean, depth std) per distribution (every one but franka uses transporter's).
DEPTH_STATS = {"transporter": (0.00509261, 0.00903967), "franka": (0.872146842, 0.195743116)}


def preprocess(img: Any, dist: str = "transporter") -> np.ndarray:
    """CLIPort's network input normalisation of an (H, W, 3 + k) colour-and-depth
    image, in place as CLIPort does: colour / 255 standardised by the
    distribution's statistics, depth standardised likewise (NumPy arrays only)."""
    if not isinstance(img, np.ndarray):
        raise Unsupported("utils.preprocess takes a NumPy (H, W, C) image here "
                          "(torch tensors are CLIPort's training code, not a task's)")
    color_mean, color_std = IMAGE_STATS.get(dist, IMAGE_STATS["transporter"])
    depth_mean, depth_std = DEPTH_STATS.get(dist, DEPTH_STATS["transporter"])
    img[:, :, :3] = (img[:, :, :3] / 255 - np.asarray(color_mean)) / np.asarray(color_std)
    img[:, :, 3:] = (img[:, :, 3:] - depth_mean) / depth_std
    return img


def deprocess(img: Any) -> np.ndarray:
    """The inverse of :func:`preprocess` (transporter statistics) back to 0-255, in
    place, as CLIPort writes it."""
    (color_mean, *_), (color_std, *_) = IMAGE_STATS["transporter"]
    depth_mean, depth_std = DEPTH_STATS["transporter"]
    img[:, :, :3] = np.uint8((img[:, :, :3] * color_std + color_mean) * 255)
    img[:, :, 3:] = np.uint8((img[:, :, 3:] * depth_std + depth_mean) * 255)
    return img


#: Names of CLIPort's ``utils`` module factask refuses, with why (docs/compat.md
#: lists them too; a task file that calls one gets this reason).
REFUSED: dict[str, str] = {
    **dict.fromkeys(("get_heightmap", "get_pointcloud", "transform_pointcloud",
                     "reconstruct_heightmaps", "unproject_vectorized",
                     "unproject_depth_vectorized", "get_fused_heightmap"),
                    "camera geometry for CLIPort's networks: factask renders its own "
                    "observations (factask.sim), a task file needs none"),
    **dict.fromkeys(("get_image_transform", "check_transform",
                     "get_se3_from_image_transform", "get_random_image_transform_params",
                     "perturb", "apply_perturbation", "apply_transform", "ImageRotator"),
                    "data augmentation for training CLIPort's networks (OpenCV / torch), "
                    "not part of a task"),
    **dict.fromkeys(("plot", "create_visualizer", "make_frame", "meshcat_visualize"),
                    "plots and meshcat windows: factask's viewer is `factask show` / "
                    "`factask render`"),
    **dict.fromkeys(("load_cfg", "load_hydra_config"),
                    "reads CLIPort's configuration files, which task files are not "
                    "lent"),
}


def set_seed(seed: int, torch: bool = False) -> None:
    """Seed ``random`` and ``np.random`` (torch is not used here)."""
    random.seed(seed)
    np.random.seed(seed)


def __getattr__(name: str) -> Any:
    if name.startswith("__"):
        raise AttributeError(name)
    why = REFUSED.get(name, "not part of CLIPort's utils that factask knows")
    raise Unsupported(f"cliport.utils.utils.{name} is not provided by factask's CLIPort "
                      f"layer: {why}")
