# %% [markdown]
# # Milestones, goal queues and Ravens' scoring
#
# Some tasks pass through states: a block goes to one zone, then to another. In
# factask such a step is a **milestone** factor: it counts once reached, in the
# order its `after` edges give, and keeps its progress when a later factor moves
# its objects again. A factor that must hold at the end is a **final** factor (the
# default). CLIPort task code expresses the same with its goal queue; the importer
# keeps that meaning, and `scored_episode` scores an episode both as factask
# checks it and as Ravens would have.
#
# Run with `python examples/07_milestones_and_ravens_scoring.py`.

# %%
import json
import os

os.environ.setdefault("MUJOCO_GL", "egl")

from pathlib import Path

import factask as ft
from factask.compat.cliport import example_tasks_dir, import_cliport
from factask.compat.cliport.scoring import scored_episode

out = Path("out/examples")
out.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## A milestone written by hand: visit the yellow zone, end in the green one

# %%
block = ft.StateVariable(name="red_block", kind="block", color="red")
yellow = ft.StateVariable(name="yellow_zone", kind="zone", color="yellow")
green = ft.StateVariable(name="green_zone", kind="zone", color="green")
visit = ft.SubtaskFactor(name="visit_yellow", description="put the red block in the yellow zone",
                         goal=ft.InZone(objects=["red_block"], zone="yellow_zone"),
                         weight=0.5, milestone=True)
finish = ft.SubtaskFactor(name="end_in_green", description="then put it in the green zone",
                          goal=ft.InZone(objects=["red_block"], zone="green_zone"),
                          weight=0.5, after=["visit_yellow"])
graph = ft.TaskGraph(name="visit-then-place", variables=[block, yellow, green],
                     factors=[visit, finish]).ensure_valid()
print("order:", graph.factor_order(), "milestones:", graph.milestones())

env = ft.FactaskEnv(graph)
oracle_runs = []
try:
    for seed in (0, 1):
        episode, ravens = scored_episode(graph, seed, env=env)
        oracle_runs.append({"task": graph.name, "seed": seed, "factask": episode.success,
                            "ravens": ravens.success, "actions": episode.steps})
        print(f"{graph.name} seed {seed}: factask success {episode.success}, "
              f"Ravens success {ravens.success} after {episode.steps} actions")
finally:
    env.close()

# %% [markdown]
# ## A CLIPort task whose queue moves one block twice

# %%
TASK = '''
import numpy as np
from cliport.tasks.task import Task


class BlockTour(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "move the blue block to each marked spot in turn"

    def reset(self, env):
        super().reset(env)
        size = (0.04, 0.04, 0.04)
        block = env.add_object("stacking/block.urdf", self.get_random_pose(env, size),
                               color="blue")
        for i, (x, y) in enumerate([(0.4, 0.2), (0.6, -0.2)]):
            target = ((x, y, 0.02), (0, 0, 0, 1))
            self.add_goal(objs=[block], matches=np.ones((1, 1)), targ_poses=[target],
                          replace=False, rotations=False, metric="pose", params=None,
                          step_max_reward=0.5, language_goal=f"move the block to spot {i}")
'''
path = out / "07_block_tour.py"
path.write_text(TASK)
result = import_cliport(path, seed=0)
for f in result.graph.factors:
    kind = "milestone" if f.milestone else "final"
    print(f"factor {f.name}: {kind}, after {f.after}")
for seed in (0, 1):
    episode, ravens = scored_episode(result, seed)
    oracle_runs.append({"task": result.task_name, "seed": seed, "factask": episode.success,
                        "ravens": ravens.success, "actions": episode.steps})
    print(f"{result.task_name} seed {seed}: factask {episode.success}, "
          f"Ravens {ravens.success} ({ravens.goals_done}/{len(result.goals)} goals)")

# %% [markdown]
# ## The CLIPort original, shipped with factask (Apache-2.0, unchanged)

# %%
original = import_cliport(example_tasks_dir() / "towers_of_hanoi.py", seed=0)
print(f"{original.task_name}: {len(original.graph.factors)} goals in queue order, "
      f"milestones {len(original.graph.milestones())}")
episode, ravens = scored_episode(original, 0)
oracle_runs.append({"task": original.task_name, "seed": 0, "factask": episode.success,
                    "ravens": ravens.success, "actions": episode.steps})
print(f"factask {episode.success}, Ravens {ravens.success} in {episode.steps} actions")

(out / "07_scores.json").write_text(json.dumps(oracle_runs, indent=2))

# %% [markdown]
# The same from the command line: `factask run towers-of-hanoi --ravens`, or
# `factask run out/examples/07_block_tour.py --ravens`; over a folder of task
# files, `python benchmarks/cliport_corpus.py FOLDER` prints the syntax / runtime
# / completion table under both scorings.
