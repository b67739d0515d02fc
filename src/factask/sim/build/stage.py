"""The stage every scene stands on: the table, the floor, the lights and the fixed cameras.
Plain data, read by both emitters (:mod:`factask.sim.build.mjspec` and
:mod:`factask.sim.build.mjcf`) and by rendering, so the compiled and the exported
scenes light and frame the table alike.
"""

from __future__ import annotations

import functools

import numpy as np

from factask.sim.build.parts import fmt
from factask.vocabulary.world import TABLE_X, TABLE_Y, WORKSPACE_X, WORKSPACE_Y

#: Table top thickness (m); its extent is TABLE_X, TABLE_Y of factask.vocabulary.world.
TABLE_THICKNESS = 0.05
#: Height of the table top above the floor (m).
TABLE_HEIGHT = 0.70
TABLE_RGBA = (0.62, 0.60, 0.57, 1.0)
FLOOR_RGBA = (0.35, 0.37, 0.40, 1.0)
#: Names of the fixed cameras.
TOP_CAMERA = "top"
FRONT_CAMERA = "front"
#: Camera positions (m) and the point they look at (the workspace centre).
WORKSPACE_CENTER = (
    (WORKSPACE_X[0] + WORKSPACE_X[1]) / 2,
    (WORKSPACE_Y[0] + WORKSPACE_Y[1]) / 2,
    0.0,
)
TOP_CAMERA_HEIGHT = 1.0
FRONT_CAMERA_POS = (1.2, 0.0, 0.6)
CAMERA_FOVY = 45.0
#: Shadow map size: software rendering speed depends on it (4096: 28 fps, 1024: 147 fps).
SHADOW_SIZE = 1024
#: Offscreen framebuffer size: the largest image a renderer of the scene can make.
OFFSCREEN_SIZE = (1280, 960)


@functools.lru_cache(maxsize=16)
def look_at_xyaxes(pos: tuple[float, float, float],
                   target: tuple[float, float, float]) -> tuple[float, ...]:
    """MuJoCo camera ``xyaxes`` for a camera at ``pos`` looking at ``target``,
    with world z up in the image.

    Args:
        pos: Camera position.
        target: The point it looks at.

    Returns:
        Six numbers: the image's right and up axes in world coordinates.
    """
    forward = np.asarray(target, float) - np.asarray(pos, float)
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    return fmt([*right, *up])


@functools.lru_cache(maxsize=1)
def table_top() -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Half extents and centre of the table top box (its top face at z = 0).

    Returns:
        (size, pos) as MuJoCo box parameters.
    """
    cx = (TABLE_X[0] + TABLE_X[1]) / 2
    cy = (TABLE_Y[0] + TABLE_Y[1]) / 2
    size = fmt([(TABLE_X[1] - TABLE_X[0]) / 2, (TABLE_Y[1] - TABLE_Y[0]) / 2,
                TABLE_THICKNESS / 2])
    return size, fmt([cx, cy, -TABLE_THICKNESS / 2])


#: The floor plane: half sizes and position.
FLOOR_SIZE = (3.0, 3.0, 0.1)
FLOOR_POS = (0.0, 0.0, -TABLE_HEIGHT)
#: Lights: (name, casts shadow, position, direction, diffuse, specular), all directional.
LIGHTS = (
    ("key", True, (0.5, 0.3, 2.0), fmt([0.0, -0.15, -1.0]), (0.45, 0.45, 0.45),
     (0.05, 0.05, 0.05)),
    ("fill", False, (1.5, 0.0, 1.5), fmt([-0.7, 0.0, -0.7]), (0.15, 0.15, 0.15),
     (0.0, 0.0, 0.0)),
)
#: Top camera position; image right = world -y, image up = world +x (robot at the bottom).
TOP_CAMERA_POS = (WORKSPACE_CENTER[0], WORKSPACE_CENTER[1], TOP_CAMERA_HEIGHT)
TOP_CAMERA_XYAXES = (0.0, -1.0, 0.0, 1.0, 0.0, 0.0)
#: Headlight: dim; the scene's own lights give shape, bright ones wash out the table.
HEADLIGHT_AMBIENT = (0.25, 0.25, 0.25)
HEADLIGHT_DIFFUSE = (0.2, 0.2, 0.2)
HEADLIGHT_SPECULAR = (0.0, 0.0, 0.0)
