"""Example 17: a microwave with a hinged door, and open / closed on doors.

Run: ``python examples/17_doors.py`` (about half a minute). Writes
``out/examples/17_doors.json``, ``out/examples/17_door_shut.png`` and
``out/examples/17_door_open.png``.

A ``microwave`` is fixed to the table, open at its -x side (and at the top: the
robots are top-down suction cups); its ``door`` is a state variable of its own
that starts ``in_cabinet`` of it (how far it is swung out) and turns on a hinge
joint in the scene. ``open`` / ``closed`` read the door's opening (its angle over
its range). A goal ``inside`` the microwave is ordered after the door's ``open``
and before its ``closed`` by the graph itself (the door gates the microwave), so
the task below needs no ``after``. The oracle swings the door by holding its
handle tab from above and moving along the arc about the hinge.
"""

# %% Imports and the output folder
import json
import os
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import imageio.v3 as iio

from factask.graph import parse_graph
from factask.scene.microwave import door_opening
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.oracle.scripted import Oracle
from factask.sim.render.offscreen import SceneRenderer
from factask.vocabulary.kinds import door_size, kind_spec

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)

# %% A task written as data: open the door, put the bowl inside, close the door
microwave = kind_spec("microwave").default_size
graph = parse_graph({
    "name": "bowl-into-microwave",
    "description": "Open the microwave, put the blue bowl inside and close the door.",
    "variables": [
        {"name": "microwave", "kind": "microwave", "color": "gray", "size": list(microwave)},
        {"name": "door", "kind": "door", "color": "gray", "size": list(door_size(microwave)),
         "initial": {"type": "in_cabinet", "cabinet": "microwave"}},
        {"name": "blue_bowl", "kind": "bowl", "color": "blue", "fixed": False},
    ],
    "factors": [
        {"name": "open_door", "goal": {"type": "open", "objects": ["door"]},
         "milestone": True, "weight": 0.3},
        {"name": "close_door", "goal": {"type": "closed", "objects": ["door"]},
         "weight": 0.3},
        {"name": "bowl_in", "weight": 0.4,
         "goal": {"type": "inside", "objects": ["blue_bowl"], "container": "microwave"}},
    ],
}).ensure_valid()
print("order:", graph.factor_order())  # open, put, close: listed otherwise on purpose

# %% One episode by hand: the door's opening after each action, pictures
env = FactaskEnv(graph)
env.reset(seed=0)
oracle = Oracle(env, seed=0)


def opening() -> float:
    """The door's opening, from its pose and its microwave's (the one definition)."""
    objs, poses = env.objects, env.object_poses()
    return door_opening(objs["microwave"], poses["microwave"], objs["door"], poses["door"])


trace = [round(opening(), 3)]
with SceneRenderer(env.model, 480, 360, geom_object=env.scene.geom_object) as renderer:
    iio.imwrite(OUT / "17_door_shut.png", renderer.rgb(env.data, "front"))
    while (action := oracle.act()) is not None:
        env.step(action)
        trace.append(round(opening(), 3))
        if len(trace) == 3:  # opened, bowl inside
            iio.imwrite(OUT / "17_door_open.png", renderer.rgb(env.data, "front"))
status = env.status()
print("opening after each action:", trace)
print("reward", round(status.reward, 3), "success", status.success)
env.close()

# %% The oracle with both robots, a few seeds
rates = {robot: sum(run_episode(graph, seed, robot=robot).success for seed in range(3))
         for robot in ("floating", "arm")}
print("oracle successes of 3:", rates)

# %% Save what happened
(OUT / "17_doors.json").write_text(json.dumps({
    "order": graph.factor_order(),
    "opening_after_each_action": trace,
    "success": bool(status.success),
    "oracle_successes_of_3": rates,
}, indent=2))
print("wrote", OUT / "17_doors.json")
