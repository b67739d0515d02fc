"""Example 16: a stove with a switch, and the switched_on / switched_off relations.

Run: ``python examples/16_switches.py`` (a few seconds). Writes
``out/examples/16_switches.json``, ``out/examples/16_switch_off.png`` and
``out/examples/16_switch_on.png``.

A ``stove`` is fixed to the table; its ``switch`` is a state variable of its own
that starts ``mounted_on`` it (off or on): a push button on a vertical slide joint
in the scene, standing on the stove's control strip. ``switched_on`` /
``switched_off`` read how far the button is pressed (a fraction of its travel,
from its pose and the stove's). The oracle presses the button down with the
suction cup, or holds it and pulls it back up; "switch the stove on, then put the
pot on it" is two goals in order, and ``on`` keeps the pot off the control strip.
"""

# %% Imports and the output folder
import json
import os
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import imageio.v3 as iio

from factask.graph import parse_graph
from factask.scene.switch import switch_pressed
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.oracle.scripted import Oracle
from factask.sim.render.offscreen import SceneRenderer

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)

# %% A task written as data: switch the stove on, put the pot on it
graph = parse_graph({
    "name": "cook",
    "description": "Turn on the stove, then put the blue pot on it.",
    "variables": [
        {"name": "stove", "kind": "stove", "color": "gray"},
        {"name": "knob", "kind": "switch", "color": "red",
         "initial": {"type": "mounted_on", "host": "stove", "on": False}},
        {"name": "pot", "kind": "bowl", "color": "blue", "fixed": False},
    ],
    "factors": [
        {"name": "stove_on", "weight": 0.5,
         "goal": {"type": "switched_on", "objects": ["knob"]}},
        {"name": "pot_on", "after": ["stove_on"], "weight": 0.5,
         "goal": {"type": "on", "objects": ["pot"], "support": "stove"}},
    ],
}).ensure_valid()
print("order:", graph.factor_names())

# %% One episode by hand: the button's press after each action, pictures
env = FactaskEnv(graph)
env.reset(seed=0)
oracle = Oracle(env, seed=0)


def pressed() -> float:
    """The knob's press, from its pose and the stove's (the one definition)."""
    objs, poses = env.objects, env.object_poses()
    return switch_pressed(objs["stove"], poses["stove"], poses["knob"])[0]


trace = [round(pressed(), 3)]
with SceneRenderer(env.model, 480, 360, geom_object=env.scene.geom_object) as renderer:
    iio.imwrite(OUT / "16_switch_off.png", renderer.rgb(env.data, "front"))
    while (action := oracle.act()) is not None:
        env.step(action)
        trace.append(round(pressed(), 3))
    iio.imwrite(OUT / "16_switch_on.png", renderer.rgb(env.data, "front"))
status = env.status()
print("press after each action:", trace)
print("reward", round(status.reward, 3), "success", status.success)
env.close()

# %% The oracle with both robots, a few seeds
rates = {robot: sum(run_episode(graph, seed, robot=robot).success for seed in range(3))
         for robot in ("floating", "arm")}
print("oracle successes of 3:", rates)

# %% Save what happened
(OUT / "16_switches.json").write_text(json.dumps({
    "factors": graph.factor_names(),
    "press_after_each_action": trace,
    "success": bool(status.success),
    "oracle_successes_of_3": rates,
}, indent=2))
print("wrote", OUT / "16_switches.json")
