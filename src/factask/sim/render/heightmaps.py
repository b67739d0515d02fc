"""CLIPort's top-down colour and height maps, fused from several cameras.

Each camera's depth image is back-projected to world points
(:func:`~factask.sim.render.cameras.points_from_depth`); the points inside the workspace
box fall into pixels of :data:`PIXEL_SIZE` metres (row = y, column = x, as
CLIPort's ``pix_to_xyz``: x = x0 + column * size, y = y0 + row * size), the
highest point of a pixel wins. Fusing takes the highest height over cameras and
the mean colour over the cameras that saw the pixel (Ravens' ``get_fused_heightmap``).
Pixels no camera saw are 0 in both maps.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from factask.sim.render.cameras import CameraSpec, points_from_depth
from factask.vocabulary.world import RAVENS_Z, WORKSPACE_X, WORKSPACE_Y

#: CLIPort's height-map resolution (m per pixel): 160 x 320 pixels over the workspace.
PIXEL_SIZE = 0.003125


@dataclass(frozen=True)
class HeightmapGrid:
    """The box a height map covers and its resolution.

    Attributes:
        x: (low, high) x range (m).
        y: (low, high) y range (m).
        z: (low, high) z range (m); heights are measured from ``z[0]``.
        pixel_size: Metres per pixel.
    """

    x: tuple[float, float] = WORKSPACE_X
    y: tuple[float, float] = WORKSPACE_Y
    z: tuple[float, float] = RAVENS_Z  # CLIPort's maps: clipped at 0.3 m, as there
    pixel_size: float = PIXEL_SIZE

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, columns) = (y pixels, x pixels)."""
        return (round((self.y[1] - self.y[0]) / self.pixel_size),
                round((self.x[1] - self.x[0]) / self.pixel_size))

    def pixel_to_xy(self, row: int, col: int) -> tuple[float, float]:
        """World (x, y) of a pixel's corner (CLIPort's ``pix_to_xyz`` without z)."""
        return self.x[0] + col * self.pixel_size, self.y[0] + row * self.pixel_size


def camera_heightmap(points: np.ndarray, colors: np.ndarray, grid: HeightmapGrid
                     ) -> tuple[np.ndarray, np.ndarray]:
    """One camera's (height, colour) maps from its world points and colours.

    Args:
        points: (h, w, 3) world points.
        colors: (h, w, 3) uint8 colours.
        grid: The box and resolution.

    Returns:
        (height (rows, cols) float32, colour (rows, cols, 3) uint8).
    """
    rows, cols = grid.shape
    height = np.zeros((rows, cols), dtype=np.float32)
    color = np.zeros((rows, cols, 3), dtype=np.uint8)
    pts, cls = points.reshape(-1, 3), colors.reshape(-1, 3)
    keep = ((pts[:, 0] >= grid.x[0]) & (pts[:, 0] < grid.x[1]) & (pts[:, 1] >= grid.y[0])
            & (pts[:, 1] < grid.y[1]) & (pts[:, 2] >= grid.z[0] - 1e-4)
            & (pts[:, 2] < grid.z[1]))
    pts, cls = pts[keep], cls[keep]
    # Ascending z: later (higher) points overwrite lower ones in the same pixel.
    order = np.argsort(pts[:, 2], kind="stable")
    pts, cls = pts[order], cls[order]
    col = np.clip(np.floor((pts[:, 0] - grid.x[0]) / grid.pixel_size).astype(int), 0, cols - 1)
    row = np.clip(np.floor((pts[:, 1] - grid.y[0]) / grid.pixel_size).astype(int), 0, rows - 1)
    height[row, col] = np.maximum(pts[:, 2] - grid.z[0], 0.0)
    color[row, col] = cls
    return height, color


def fuse_heightmaps(views: Sequence[tuple[CameraSpec, np.ndarray, np.ndarray]],
                    grid: HeightmapGrid) -> tuple[np.ndarray, np.ndarray]:
    """Fused (colour, height) maps from (camera, rgb, depth) views.

    Returns:
        (colour (rows, cols, 3) uint8, height (rows, cols) float32).
    """
    heights, colors = [], []
    for cam, rgb, depth in views:
        h, c = camera_heightmap(points_from_depth(depth, cam), rgb, grid)
        heights.append(h)
        colors.append(c.astype(np.float32))
    cstack = np.stack(colors)
    valid = cstack.sum(axis=3) > 0
    repeat = np.maximum(valid.sum(axis=0), 1)
    color = np.round(cstack.sum(axis=0) / repeat[..., None]).astype(np.uint8)
    return color, np.max(np.stack(heights), axis=0).astype(np.float32)
