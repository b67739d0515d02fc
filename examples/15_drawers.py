"""Example 15: cabinets with sliding drawers, and the open / closed relations.

Run: ``python examples/15_drawers.py`` (about half a minute). Writes
``out/examples/15_drawers.json``, ``out/examples/15_drawer_shut.png`` and
``out/examples/15_drawer_open.png``.

A ``cabinet`` is fixed to the table; each ``drawer`` is a state variable of its own
that starts ``in_cabinet`` (its level, 0 at the bottom, and how far it is pulled
out) and slides on a joint in the scene. ``open`` / ``closed`` read the drawer's
opening (a fraction of its travel); ``inside`` a drawer needs nothing new: the
drawer is a receptacle whose inside moves with it. The oracle slides a drawer by
holding its handle with the suction cup; "open, then put inside" comes from the
graph (the put is anchored to the drawer the open goal moves).
"""

# %% Imports and the output folder
import json
import os
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import imageio.v3 as iio

from factask.graph import parse_graph
from factask.scene.cabinet import drawer_opening
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.oracle.scripted import Oracle
from factask.sim.render.offscreen import SceneRenderer
from factask.vocabulary.kinds import drawer_size

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)

# %% A task written as data: open the top drawer, put the block inside, close it
cabinet_size = (0.22, 0.30, 0.20)  # two drawers, 7 cm deep inside
drawer = list(drawer_size(cabinet_size, 2))  # a drawer's size follows its cabinet's
graph = parse_graph({
    "name": "block-into-drawer",
    "description": "Open the top drawer, put the red block inside and close it.",
    "variables": [
        {"name": "cabinet", "kind": "cabinet", "color": "brown", "size": list(cabinet_size)},
        {"name": "bottom_drawer", "kind": "drawer", "color": "brown", "size": drawer,
         "initial": {"type": "in_cabinet", "cabinet": "cabinet", "level": 0}},
        {"name": "top_drawer", "kind": "drawer", "color": "brown", "size": drawer,
         "initial": {"type": "in_cabinet", "cabinet": "cabinet", "level": 1}},
        {"name": "red_block", "kind": "block", "color": "red"},
    ],
    "factors": [
        {"name": "open_top", "goal": {"type": "open", "objects": ["top_drawer"]},
         "milestone": True, "weight": 0.3},
        {"name": "block_in", "weight": 0.4,
         "goal": {"type": "inside", "objects": ["red_block"], "container": "top_drawer"}},
        {"name": "close_top", "goal": {"type": "closed", "objects": ["top_drawer"]},
         "after": ["block_in"], "weight": 0.3},
    ],
}).ensure_valid()
print("order:", graph.factor_names())

# %% One episode by hand: the drawer's opening after each action, pictures
env = FactaskEnv(graph)
env.reset(seed=0)
oracle = Oracle(env, seed=0)


def opening() -> float:
    """The top drawer's opening, from its pose and its cabinet's (the one definition)."""
    objs, poses = env.objects, env.object_poses()
    return drawer_opening(objs["cabinet"], poses["cabinet"], objs["top_drawer"],
                          poses["top_drawer"])


trace = [round(opening(), 3)]
with SceneRenderer(env.model, 480, 360, geom_object=env.scene.geom_object) as renderer:
    iio.imwrite(OUT / "15_drawer_shut.png", renderer.rgb(env.data, "front"))
    while (action := oracle.act()) is not None:
        env.step(action)
        trace.append(round(opening(), 3))
        if len(trace) == 3:  # opened, block inside
            iio.imwrite(OUT / "15_drawer_open.png", renderer.rgb(env.data, "front"))
status = env.status()
print("opening after each action:", trace)
print("reward", round(status.reward, 3), "success", status.success)
env.close()

# %% The oracle with both robots, a few seeds
rates = {robot: sum(run_episode(graph, seed, robot=robot).success for seed in range(3))
         for robot in ("floating", "arm")}
print("oracle successes of 3:", rates)

# %% Save what happened
(OUT / "15_drawers.json").write_text(json.dumps({
    "factors": graph.factor_names(),
    "opening_after_each_action": trace,
    "success": bool(status.success),
    "oracle_successes_of_3": rates,
}, indent=2))
print("wrote", OUT / "15_drawers.json")
