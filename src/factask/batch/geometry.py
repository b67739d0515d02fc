"""Pose arithmetic over many worlds at once (NumPy), the batched twin of
:mod:`factask.geometry` and the parts of :mod:`factask.scene.objects` the checks use.

Poses of a batch are arrays: positions ``(..., 3)``, quaternions ``(..., 4)``
(MuJoCo's w, x, y, z). Every function here gives, element by element, the number
its scalar twin gives for the same pose (up to floating-point rounding); the test
``tests/test_batch_checks.py`` holds them to it through the checks.
"""

from __future__ import annotations

import math

import numpy as np

from factask.scene.objects import GEOMETRY_EPS, ROUND_SAMPLES, SPHERE_KINDS, SceneObject


def normalize_quat(quat: np.ndarray) -> np.ndarray:
    """Unit quaternions (..., 4), as :class:`~factask.geometry.Pose` stores them: a
    zero quaternion becomes the identity; a non-finite one stays non-finite.

    Args:
        quat: Quaternions (w, x, y, z), any leading shape.

    Returns:
        Normalised quaternions of the same shape.
    """
    q = np.asarray(quat, dtype=float)
    n = np.linalg.norm(q, axis=-1, keepdims=True)
    ok = np.isfinite(n) & (n > 0)
    out = np.where(ok, q / np.where(ok, n, 1.0), q)
    ident = np.zeros_like(q)
    ident[..., 0] = 1.0
    return np.where(n == 0, ident, out)


def rotation_matrices(quat: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 3, 3) of unit quaternions (..., 4).

    Args:
        quat: Unit quaternions (w, x, y, z).

    Returns:
        The matrices, laid out as :func:`factask.geometry.rotation_matrix`.
    """
    w, x, y, z = np.moveaxis(np.asarray(quat, dtype=float), -1, 0)
    rows = [
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def yaws(quat: np.ndarray) -> np.ndarray:
    """Yaw (radians, in (-pi, pi]) of quaternions (..., 4) (see
    :func:`~factask.geometry.yaw_of`)."""
    w, x, y, z = np.moveaxis(np.asarray(quat, dtype=float), -1, 0)
    return np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def tilts_deg(quat: np.ndarray) -> np.ndarray:
    """Angle (degrees) between each body's z axis and world z (see
    :func:`~factask.geometry.tilt_deg`)."""
    w, x, y, z = np.moveaxis(np.asarray(quat, dtype=float), -1, 0)
    zz = w * w - x * x - y * y + z * z  # z of the rotated z axis
    return np.degrees(np.arccos(np.clip(zz, -1.0, 1.0)))


def upright_tilts_deg(obj: SceneObject, quat: np.ndarray) -> np.ndarray:
    """Tilt from upright in degrees; 0 for spheres, a log's axis's slope (see
    :func:`~factask.relations.status.upright_tilt_deg`)."""
    q = np.asarray(quat, dtype=float)
    if obj.kind in SPHERE_KINDS:
        return np.zeros(q.shape[:-1])
    if obj.kind == "log":  # the slope of the x axis: its rolls about x do not count
        w, x, y, z = np.moveaxis(q, -1, 0)
        return np.degrees(np.arcsin(np.clip(np.abs(2 * (x * z - w * y)), 0.0, 1.0)))
    return tilts_deg(q)


def yaw_errors_deg(yaw_a: np.ndarray, yaw_b: np.ndarray, symmetry_deg: float) -> np.ndarray:
    """Smallest yaw difference in degrees modulo ``symmetry_deg`` (0: any yaw; see
    :func:`~factask.geometry.yaw_error_deg`)."""
    a = np.asarray(yaw_a, dtype=float)
    b = np.asarray(yaw_b, dtype=float)
    if symmetry_deg <= 0:
        return np.zeros(np.broadcast_shapes(a.shape, b.shape))
    d = np.mod(np.degrees(a - b), symmetry_deg)
    return np.minimum(d, symmetry_deg - d)


def rotate_2d(xy: np.ndarray, yaw: np.ndarray) -> np.ndarray:
    """Points (..., 2) turned by ``yaw`` (...,) about the origin."""
    c, s = np.cos(yaw), np.sin(yaw)
    x, y = xy[..., 0], xy[..., 1]
    return np.stack([c * x - s * y, s * x + c * y], axis=-1)


def to_local_2d(xy: np.ndarray, yaw: np.ndarray) -> np.ndarray:
    """Points (..., 2) in a frame turned by ``yaw`` (...,): the inverse of :func:`rotate_2d`."""
    c, s = np.cos(yaw), np.sin(yaw)
    x, y = xy[..., 0], xy[..., 1]
    return np.stack([c * x + s * y, -s * x + c * y], axis=-1)


def _box_signs() -> np.ndarray:
    return np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)],
                    dtype=float)


def box_z_range(obj: SceneObject, pos: np.ndarray, quat: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray]:
    """Lowest and highest points (...,) of the object's box at the poses (tilt
    included; a ball's whatever its rotation): :func:`~factask.scene.objects.bottom_z`
    and :func:`~factask.scene.objects.top_z` at once.

    Args:
        obj: The object.
        pos: Positions (..., 3).
        quat: Unit quaternions (..., 4).

    Returns:
        (bottom z, top z).
    """
    pos = np.asarray(pos, dtype=float)
    if obj.kind in SPHERE_KINDS:
        return pos[..., 2] - obj.half[2], pos[..., 2] + obj.half[2]
    local = _box_signs() * obj.half  # (8, 3)
    rot_z = rotation_matrices(quat)[..., 2, :]  # (..., 3): the rows giving world z
    z = pos[..., 2, None] + np.einsum("...d,cd->...c", rot_z, local)
    return z.min(axis=-1), z.max(axis=-1)


def footprint_grid(obj: SceneObject, per_axis: int = 3) -> np.ndarray:
    """The object-frame sample points (k, 3) behind
    :func:`~factask.scene.objects.footprint_points` (a box's grid on its top and
    bottom faces; a round kind's centre and rim, top and bottom)."""
    if obj.is_round:
        ang = np.linspace(0.0, 2 * math.pi, ROUND_SAMPLES, endpoint=False)
        disk = np.concatenate([[[0.0, 0.0]], np.stack([np.cos(ang), np.sin(ang)], 1)])
        grid = np.array([[x, y, c] for x, y in disk for c in (-1.0, 1.0)])
    else:
        t = np.linspace(-1.0, 1.0, per_axis)
        grid = np.array([[a, b, c] for a in t for b in t for c in (-1.0, 1.0)])
    return grid * obj.half


def footprint_points_batch(obj: SceneObject, pos: np.ndarray, quat: np.ndarray) -> np.ndarray:
    """XY sample points (..., k, 2) of the object's shape at the poses, projected
    onto the table (a ball sampled upright)."""
    local = footprint_grid(obj)
    pos = np.asarray(pos, dtype=float)
    if obj.kind in SPHERE_KINDS:
        pts = pos[..., None, :] + local
    else:
        rot = rotation_matrices(quat)  # (..., 3, 3)
        pts = pos[..., None, :] + np.einsum("...ij,kj->...ki", rot, local)
    return pts[..., :2]


def in_rect(points: np.ndarray, center: np.ndarray, yaw: np.ndarray,
            half: np.ndarray) -> np.ndarray:
    """Which points (..., k, 2) lie in rectangles (centre (..., 2), yaw (...,),
    half extents (..., 2)), boundary included."""
    local = to_local_2d(points - center[..., None, :], yaw[..., None])
    return np.all(np.abs(local) <= half[..., None, :] + GEOMETRY_EPS, axis=-1)


def in_disk(points: np.ndarray, center: np.ndarray, radius: np.ndarray) -> np.ndarray:
    """Which points (..., k, 2) lie in disks (centre (..., 2), radius (...,))."""
    d = np.linalg.norm(points - center[..., None, :], axis=-1)
    return d <= radius[..., None] + GEOMETRY_EPS


def footprint_rects(half_xy: np.ndarray, xy: np.ndarray, yaw: np.ndarray) -> np.ndarray:
    """Footprint corners (..., 4, 2), counter-clockwise, of rectangles of half extents
    ``half_xy`` (..., 2) at centres ``xy`` (..., 2) turned by ``yaw`` (...,) (see
    :func:`~factask.scene.objects.footprint_corners`)."""
    signs = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], dtype=float)
    local = signs * np.asarray(half_xy, dtype=float)[..., None, :]
    return rotate_2d(local, np.asarray(yaw)[..., None]) + np.asarray(xy)[..., None, :]


def _edge_normals(corners: np.ndarray) -> np.ndarray:
    e = np.stack([corners[..., 1, :] - corners[..., 0, :],
                  corners[..., 3, :] - corners[..., 0, :]], axis=-2)
    norm = np.linalg.norm(e, axis=-1, keepdims=True)
    return e / np.where(norm > 0, norm, 1.0)


def rects_overlap(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Separating-axis overlap of rectangles paired element by element: corners
    (..., 4, 2) each, broadcast together (see :func:`~factask.scene.objects.obb_overlaps`:
    touching edges do not count)."""
    a, b = np.broadcast_arrays(np.asarray(a, dtype=float), np.asarray(b, dtype=float))
    axes = np.concatenate([_edge_normals(a), _edge_normals(b)], axis=-2)  # (..., 4, 2)
    pa = np.einsum("...ad,...cd->...ac", axes, a)
    pb = np.einsum("...ad,...cd->...ac", axes, b)
    separated = (pa.max(-1) <= pb.min(-1) + GEOMETRY_EPS) | (pb.max(-1) <= pa.min(-1)
                                                              + GEOMETRY_EPS)
    return ~separated.any(-1)


__all__ = [
    "box_z_range",
    "footprint_grid",
    "footprint_points_batch",
    "footprint_rects",
    "in_disk",
    "in_rect",
    "normalize_quat",
    "rects_overlap",
    "rotate_2d",
    "rotation_matrices",
    "tilts_deg",
    "to_local_2d",
    "upright_tilts_deg",
    "yaw_errors_deg",
    "yaws",
]
