"""Example 18: a stepped shelf with two levels, and ``on`` a level.

Run: ``python examples/18_shelves.py`` (about half a minute). Writes
``out/examples/18_shelves.json``, ``out/examples/18_shelf_start.png`` and
``out/examples/18_shelf_done.png``.

A ``shelf`` is fixed to the table; its levels rise from its -x side towards its
back panel, each level's top open to the sky, so a top-down suction cup reaches
every one. Each level is a state variable of its own (kind ``shelf_level``) that
starts ``in_cabinet`` of the shelf with its ``level`` (0 the lowest); its size
follows from the shelf's (``shelf_level_size``) and its pose from the shelf's
(``factask.scene.shelf.level_pose``). ``on`` a level is plain ``on``: a level is a
support. Here a block starts on the lower level and goes up; another goes from
the table to the lower level.
"""

# %% Imports and the output folder
import json
import os
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import imageio.v3 as iio

from factask.graph import parse_graph
from factask.scene.objects import bottom_z, rest_surface_z
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.oracle.scripted import Oracle
from factask.sim.render.offscreen import SceneRenderer
from factask.vocabulary.kinds import shelf_level_size

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)

# %% A task written as data: a shelf, its two levels, two blocks
shelf_size = (0.30, 0.34, 0.13)  # two levels 14.5 cm deep, tops at 5 and 10 cm
graph = parse_graph({
    "name": "blocks-on-shelf-levels",
    "description": "Move the green block up to the upper level of the shelf and put the "
                   "red block on the lower level.",
    "variables": [
        {"name": "shelf", "kind": "shelf", "color": "brown", "size": list(shelf_size)},
        {"name": "lower_level", "kind": "shelf_level", "color": "brown",
         "size": list(shelf_level_size(shelf_size, 2, 0)),
         "initial": {"type": "in_cabinet", "cabinet": "shelf", "level": 0}},
        {"name": "upper_level", "kind": "shelf_level", "color": "brown",
         "size": list(shelf_level_size(shelf_size, 2, 1)),
         "initial": {"type": "in_cabinet", "cabinet": "shelf", "level": 1}},
        {"name": "green_block", "kind": "block", "color": "green",
         "initial": {"type": "on", "support": "lower_level"}},
        {"name": "red_block", "kind": "block", "color": "red"},
    ],
    "factors": [
        {"name": "green_up", "weight": 0.5, "goal": {"type": "on", "objects": ["green_block"],
                                      "support": "upper_level"}},
        {"name": "red_low", "weight": 0.5, "goal": {"type": "on", "objects": ["red_block"],
                                     "support": "lower_level"}},
    ],
}).ensure_valid()
print("order:", graph.factor_names())

# %% One episode by hand: where each block stands after each action, pictures
env = FactaskEnv(graph)
env.reset(seed=0)
oracle = Oracle(env, seed=0)


def heights() -> dict[str, float]:
    """Each block's bottom above the table and each level's top (metres)."""
    objs, poses = env.objects, env.object_poses()
    out = {n: round(bottom_z(objs[n], poses[n]), 3) for n in ("green_block", "red_block")}
    out |= {n: round(rest_surface_z(objs[n], poses[n]), 3)
            for n in ("lower_level", "upper_level")}
    return out


trace = [heights()]
with SceneRenderer(env.model, 480, 360, geom_object=env.scene.geom_object) as renderer:
    iio.imwrite(OUT / "18_shelf_start.png", renderer.rgb(env.data, "front"))
    while (action := oracle.act()) is not None:
        env.step(action)
        trace.append(heights())
    iio.imwrite(OUT / "18_shelf_done.png", renderer.rgb(env.data, "front"))
status = env.status()
print("heights after each action:", trace)
print("reward", round(status.reward, 3), "success", status.success)
env.close()

# %% The oracle with both robots, a few seeds
rates = {robot: sum(run_episode(graph, seed, robot=robot).success for seed in range(3))
         for robot in ("floating", "arm")}
print("oracle successes of 3:", rates)

# %% Save what happened
(OUT / "18_shelves.json").write_text(json.dumps({
    "factors": graph.factor_names(),
    "heights_after_each_action": trace,
    "success": bool(status.success),
    "oracle_successes_of_3": rates,
}, indent=2))
print("wrote", OUT / "18_shelves.json")
