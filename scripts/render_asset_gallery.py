"""Render every asset kind at its default size into one labelled picture.

Writes ``docs/img/assets.png`` (the picture in ``docs/assets.md``): one tile per
kind, each seen from the same oblique angle, on the factask table.

Usage:
    .venv/bin/python scripts/render_asset_gallery.py [OUT_PNG]
"""

from __future__ import annotations

import sys
from pathlib import Path

import mujoco
import numpy as np
from matplotlib.figure import Figure  # no pyplot: no GUI backend is needed

import factask.sim  # noqa: F401  (picks the headless GL backend before rendering)
from factask.sim.build.mjcf import build_object, build_table, new_root
from factask.sim.render.offscreen import SceneRenderer
from factask.vocabulary.kinds import ASSET_KINDS, KIND_NAMES
from factask.vocabulary.palette import COLOR_NAMES

DEFAULT_OUT = Path(__file__).resolve().parent.parent / "docs" / "img" / "assets.png"
#: Tile size in pixels and grid layout.
TILE = (240, 180)
COLUMNS = 5
#: Free-camera angles (degrees) of every tile.
AZIMUTH, ELEVATION = 135.0, -35.0


def _positions() -> dict[str, tuple[float, float]]:
    """Table spot of each kind: a 0.4 m grid, so each tile shows one object."""
    out = {}
    for i, kind in enumerate(KIND_NAMES):
        row, col = divmod(i, 4)
        out[kind] = (-0.15 + row * 0.4, -0.6 + col * 0.4)
    return out


def render_tiles() -> dict[str, np.ndarray]:
    """One RGB tile per kind.

    Returns:
        Kind -> image (height, width, 3) uint8.
    """
    root = new_root("asset_gallery")
    build_table(root.worldbody)
    spots = _positions()
    for i, kind in enumerate(KIND_NAMES):
        size = ASSET_KINDS[kind].default_size
        x, y = spots[kind]
        build_object(root.worldbody, kind, kind, size, COLOR_NAMES[i % 11],
                     pos=(x, y, size[2] / 2))
    model = mujoco.MjModel.from_xml_string(root.to_xml_string())
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    tiles = {}
    with SceneRenderer(model, *TILE) as renderer:
        for kind in KIND_NAMES:
            size = ASSET_KINDS[kind].default_size
            cam = mujoco.MjvCamera()
            cam.type = mujoco.mjtCamera.mjCAMERA_FREE
            cam.lookat[:] = [*spots[kind], size[2] / 2]
            cam.distance = 1.6 * max(size) + 0.08
            cam.azimuth, cam.elevation = AZIMUTH, ELEVATION
            tiles[kind] = renderer.rgb(data, cam)
    return tiles


def main(out: Path = DEFAULT_OUT) -> Path:
    """Render the gallery and save it as a PNG.

    Args:
        out: Output PNG path.

    Returns:
        The path written.
    """
    tiles = render_tiles()
    rows = -(-len(tiles) // COLUMNS)
    fig = Figure(figsize=(COLUMNS * 2.4, rows * 2.0), dpi=100)
    axes = fig.subplots(rows, COLUMNS)
    for ax in axes.ravel():
        ax.axis("off")
    for ax, (kind, img) in zip(axes.ravel(), tiles.items(), strict=False):
        size = ASSET_KINDS[kind].default_size
        ax.imshow(img)
        ax.set_title(f"{kind}  {size[0] * 100:g}x{size[1] * 100:g}x{size[2] * 100:g} cm",
                     fontsize=9)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out)
    return out


if __name__ == "__main__":
    print(main(Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT_OUT))
