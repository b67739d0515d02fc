"""Example 04: render a scene - RGB, depth, segmentation images and an episode GIF.

Run: ``python examples/04_render_scene.py`` (about twenty seconds with software
rendering). Writes under ``out/examples/``: ``04_rgb_front.png``,
``04_rgb_top.png``, ``04_depth_top.png``, ``04_segmentation_top.png`` and
``04_episode.gif``.

Rendering is headless: importing :mod:`factask.sim` picks EGL (else OSMesa)
unless ``MUJOCO_GL`` is set. A :class:`SceneRenderer` holds one GL context; use it
as a context manager. Goal markers (translucent copies of objects at their
targets) are drawn in RGB by default and hidden in depth and segmentation.
"""

# %% Imports and the output folder
from pathlib import Path

import imageio.v3 as iio
import numpy as np

from factask.library import get_task
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.render.offscreen import BACKGROUND_ID, SceneRenderer, active_gl_backend

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)

# %% A reset scene of a library task
task = get_task("put-block-in-bowl")
env = FactaskEnv(task, robot="floating")
env.reset(seed=0)
print("objects (segmentation ids in this order):", env.object_names)

# %% RGB from the two fixed cameras, depth and segmentation from the top camera
with SceneRenderer(env.model, 480, 360, geom_object=env.scene.geom_object) as renderer:
    front = renderer.rgb(env.data, "front")
    top = renderer.rgb(env.data, "top")
    top_clean = renderer.rgb(env.data, "top", show_markers=False)
    depth = renderer.depth(env.data, "top")
    seg = renderer.segmentation(env.data, "top")
print("GL backend:", active_gl_backend())
print(f"rgb {front.shape} {front.dtype}; depth {depth.shape} {depth.dtype} "
      f"{depth.min():.3f}..{depth.max():.3f} m; segmentation {seg.shape} ids {np.unique(seg)}")
print("pixels changed by the goal markers:", int((top != top_clean).any(axis=2).sum()))

# %% Save as PNG: depth scaled to 8 bits (near = bright), segmentation in colours
iio.imwrite(OUT / "04_rgb_front.png", front)
iio.imwrite(OUT / "04_rgb_top.png", top)
near, far = float(depth.min()), float(np.percentile(depth, 99))
depth8 = (255 * (1 - np.clip((depth - near) / max(far - near, 1e-6), 0, 1))).astype(np.uint8)
iio.imwrite(OUT / "04_depth_top.png", depth8)
palette = (np.random.default_rng(0).uniform(60, 255, (len(env.object_names), 3))
           .astype(np.uint8))
seg_rgb = np.zeros((*seg.shape, 3), np.uint8)
for index, name in enumerate(env.object_names):
    mask = seg == index
    seg_rgb[mask] = palette[index]
    print(f"  {name}: {int(mask.sum())} pixels")
print(f"  background ({BACKGROUND_ID}): {int((seg == BACKGROUND_ID).sum())} pixels")
iio.imwrite(OUT / "04_segmentation_top.png", seg_rgb)

# %% env.render(): the same RGB image through the gymnasium API
env.close()
env = FactaskEnv(task, robot="floating", render_mode="rgb_array", camera="top")
env.reset(seed=0)
print("env.render():", env.render().shape)
env.close()

# %% A short GIF of an oracle episode (a frame every 0.12 s of simulated time)
result = run_episode(task, seed=0, robot="floating", video=OUT / "04_episode.gif")
frames = iio.imread(OUT / "04_episode.gif")
print(f"episode: success {result.success}, {result.steps} action(s); "
      f"GIF of {len(frames)} frames {frames.shape[1:]}")
print("wrote", ", ".join(sorted(p.name for p in OUT.glob("04_*"))))
