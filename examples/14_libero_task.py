"""Example 14: LIBERO's task files (BDDL) as factask task graphs.

Run: ``python examples/14_libero_task.py`` (about half a minute). Writes
``out/examples/14_libero.json`` and ``out/examples/14_libero_scene.png``.

LIBERO describes each task as a BDDL problem: objects, fixtures, regions, the
initial predicates and the goal. ``factask.compat.libero`` reads the file into typed
values (``load_bddl``), then ``import_libero`` turns it into a factask task graph:
objects become state variables (stand-in kinds from one table), ``:init`` becomes
their starts, ``:goal`` becomes factors, the language line the description. The
files of three LIBERO suites ship with factask (MIT licence). A file that needs
what factask does not model (a bowl resting on a smaller bowl, a fridge's door) is
refused with a typed error naming the predicate; the cabinet's drawers, the
microwave's door and the stove's switch are variables of their own (examples 15,
17, 16).
"""

# %% Imports and the output folder
import json
import os
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import imageio.v3 as iio

from factask.compat.libero import (
    LiberoUnsupported,
    import_libero,
    load_bddl,
    shipped_bddl_files,
)
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.render.offscreen import SceneRenderer

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)

# %% The shipped files, and one read as LIBERO wrote it
files = shipped_bddl_files()
print(len(files), "shipped BDDL files")
path = next(p for p in shipped_bddl_files("libero_spatial") if "next_to_the_plate" in p.name)
problem = load_bddl(path)
print("language:", problem.language)
print("objects:", problem.objects)
print("goal:", [(g.name, g.args) for g in problem.goal])

# %% The task graph: variables, starts and the goal as factors
imported = import_libero(path)
graph = imported.graph
for v in graph.variables:
    print(f"variable {v.name}: {v.kind} {v.size} {v.color} starts {v.initial.type}")
for f in graph.factors:
    print(f"factor {f.name}: {f.goal.type} -> {f.description!r}")

# %% The scene, and the oracle on it
env = FactaskEnv(graph)
env.reset(seed=0)
with SceneRenderer(env.model, 480, 360, geom_object=env.scene.geom_object) as renderer:
    iio.imwrite(OUT / "14_libero_scene.png", renderer.rgb(env.data, "front"))
env.close()
episodes = [run_episode(graph, seed) for seed in range(2)]
print("oracle:", [(e.success, e.steps) for e in episodes])

# %% A file that needs what factask does not model is refused, and says why
refused = {}
for p in shipped_bddl_files():
    try:
        import_libero(p)
    except LiberoUnsupported as exc:
        refused[p.stem] = str(exc)
print(f"{len(refused)} shipped files refused, e.g.:", next(iter(refused.values())))

# %% Save what happened
(OUT / "14_libero.json").write_text(json.dumps({
    "file": path.name,
    "language": problem.language,
    "variables": [v.name for v in graph.variables],
    "factors": [f.goal.type for f in graph.factors],
    "oracle_success": [e.success for e in episodes],
    "refused": refused,
}, indent=2))
print("wrote", OUT / "14_libero.json")
