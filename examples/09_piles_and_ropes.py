"""Example 09: a pile swept with the spatula, a rope laid along a line (issue 15).

Run: ``python examples/09_piles_and_ropes.py`` (about half a minute). Writes under
``out/examples/``: ``09_piles_and_ropes.png`` (top view of each task before and
after the oracle's episode, side by side) and ``09_results.json`` (each
episode's actions, progress after each action and success).

A ``pile`` variable is ``count`` small blocks that start as one cluster; its
``pile_in_zone`` goal's progress is the share of the blocks inside (continuous),
reached by pushes with a spatula. A ``rope`` variable is ``count`` segments
linked in a chain; ``rope_along`` lays it straight along a line, one segment at
a time, each carried 2 cm over the table. See docs/deformables.md.
"""

# %% Imports and the output folder
import json
from pathlib import Path

import imageio.v3 as iio
import numpy as np

from factask.graph import parse_graph
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)

# %% Two small tasks: a pile of 30 blocks into a zone, a rope of 20 segments along a line
sweep = parse_graph({
    "name": "sweep-pile",
    "variables": [{"name": "red_pile", "kind": "pile", "color": "red", "count": 30},
                  {"name": "green_zone", "kind": "zone", "color": "green"}],
    "factors": [{"name": "sweep", "goal": {"type": "pile_in_zone", "objects": ["red_pile"],
                                           "zone": "green_zone", "fraction": 0.95}}],
})
rope = parse_graph({
    "name": "lay-rope",
    "variables": [{"name": "blue_rope", "kind": "rope", "color": "blue", "count": 20},
                  {"name": "green_line", "kind": "line", "color": "green"}],
    "factors": [{"name": "lay", "goal": {"type": "rope_along", "objects": ["blue_rope"],
                                         "along": "green_line",
                                         "tolerances": {"xy": 0.02}}}],
})

# %% Run the oracle on each; keep the progress after every action and the pictures
results, rows = {}, []
for graph, seed in ((sweep, 0), (rope, 0)):
    env = FactaskEnv(graph, render_size=(320, 240))
    env.reset(seed=seed)
    before = env.render_rgb("top")
    progress: list[tuple[str, float]] = []

    def note(i, planned, info, progress=progress):  # after each action
        progress.append((planned.purpose, round(info["total_reward"], 3)))

    result = run_episode(graph, seed, env=env, on_action=note)
    after = env.render_rgb("top")
    env.close()
    results[graph.name] = {"success": result.success, "actions": result.steps,
                           "progress": progress, "failure": result.failure}
    print(f"{graph.name}: success={result.success} in {result.steps} action(s); "
          f"progress {[p for _, p in progress]}")
    rows.append(np.concatenate([before, after], axis=1))

# %% Save: one row per task (before | after), and the numbers
iio.imwrite(OUT / "09_piles_and_ropes.png", np.concatenate(rows, axis=0))
(OUT / "09_results.json").write_text(json.dumps(results, indent=2))
