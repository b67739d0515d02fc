# %% [markdown]
# # Running CLIPort / GenSim task code on MuJoCo
#
# Task classes written against the CLIPort/Ravens `Task` API (PyBullet) load
# unchanged: `import_cliport` runs the class's `reset(env)` against a recording
# environment — **this executes the file: only import code you trust** — and turns
# each `env.add_object` into a state variable and each `add_goal` into a subtask
# factor. The result is an ordinary factask task graph: validated, compiled into
# MuJoCo, solved by the oracle, scored by factask's checks.
#
# Run with `python examples/05_import_cliport_task.py`.

# %%
import os

os.environ.setdefault("MUJOCO_GL", "egl")

from pathlib import Path

from factask.compat.cliport import import_cliport
from factask.sim.episode import evaluate_task

out = Path("out/examples")
out.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## A task class in CLIPort style (as GenSim's LLM would write it)

# %%
TASK = '''
import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class StackBoxesColumn(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 15
        self.lang_template = "stack the boxes into a column"
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        size = (0.07, 0.07, 0.07)
        base = ((0.5, 0.0, 0.035), (0, 0, 0, 1))
        ids = []
        for i in range(3):
            ids.append(env.add_object("box/box-template.urdf",
                                      self.get_random_pose(env, size),
                                      color=utils.COLORS["blue"]))
        for i, obj in enumerate(ids):
            target = (utils.apply(base, (0, 0, i * size[2])), base[1])
            self.add_goal(objs=[obj], matches=np.ones((1, 1)), targ_poses=[target],
                          replace=False, rotations=True, metric="pose", params=None,
                          step_max_reward=1 / 3, language_goal="stack box %d" % i)
'''
path = out / "05_stack_boxes_column.py"
path.write_text(TASK)

# %% [markdown]
# ## Import: the recorded graph

# %%
result = import_cliport(path, seed=0)
graph = result.graph
for v in graph.variables:
    print(f"variable {v.name}: {v.kind} {v.size} {v.color}")
for f in graph.factors:
    print(f"factor {f.name} (weight {f.weight:.3f}): {f.goal.type} -> {f.description!r}")
for w in result.warnings:
    print("warning:", w)
(out / "05_imported.json").write_text(graph.to_json())

# %% [markdown]
# ## Run the oracle on MuJoCo (the research's definitions: an episode succeeds at
# reward >= 0.99, the task is completed when at least half of its episodes do)

# %%
task_result = evaluate_task(graph, episodes=2, seed=0, robot="floating")
for e in task_result.episodes:
    print(f"seed {e.seed}: reward {e.reward:.3f}, success {e.success}, {e.steps} actions")
print("completed:", task_result.completed)
