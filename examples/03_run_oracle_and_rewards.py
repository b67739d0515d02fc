"""Example 03: run the oracle step by step and read the per-factor rewards.

Run: ``python examples/03_run_oracle_and_rewards.py`` (about half a minute).
Writes ``out/examples/03_rewards.json`` (the reward after every action).

``FactaskEnv`` is a gymnasium environment whose action is one suction
pick-and-place; ``info["factors"]`` holds every factor's progress in [0, 1],
``info["total_reward"]`` their weighted sum, and the step reward is its change.
Every factor is re-checked after every action, so undoing a finished subtask
(knocking over a stack) lowers the reward again.
"""

# %% Imports and the output folder
import json
from pathlib import Path

import mujoco
import numpy as np

import factask as ft
from factask.geometry import Pose
from factask.library import get_task
from factask.sim.build.compile import set_object_pose
from factask.sim.env import FactaskEnv
from factask.sim.episode import evaluate_task, run_episode
from factask.sim.oracle.scripted import Oracle

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)

# %% A two-factor task: a block into a bowl, then three boxes into a column
task = ft.compose(get_task("put-block-in-bowl"), get_task("stack-boxes-column"),
                  name="bowl-and-column")
print("factors:", {f.name: round(f.weight, 2) for f in task.factors})

# %% Reset: a seeded layout, relations solved into target poses
env = FactaskEnv(task, robot="floating")
obs, info = env.reset(seed=0)
print("objects:", env.object_names, "observation", obs["object_poses"].shape)
print("after reset:", info["factors"], "total", round(info["total_reward"], 3))
for factor, t in info["targets"].items():
    print(f"  targets of {factor}: " + ", ".join(
        f"{o} -> ({p[0]:.2f}, {p[1]:.2f}, {p[2]:.3f})" for o, p in t["targets"].items()))

# %% The oracle, one action at a time
oracle = Oracle(env, seed=0)
log = [{"action": 0, "total": info["total_reward"], "factors": info["factors"]}]
terminated = truncated = False
while not (terminated or truncated):
    planned = oracle.plan()
    if planned is None:
        print("oracle stops:", oracle.failure or "done")
        break
    _, reward, terminated, truncated, info = env.step(planned.as_env_action())
    progress = {k: round(v, 2) for k, v in info["factors"].items()}
    print(f"action {env.actions_taken}: {planned.purpose:22s} reward {reward:+.3f} "
          f"total {info['total_reward']:.3f}  {progress}  "
          f"({env.history[-1].sim_steps * env.model.opt.timestep:.1f} s simulated)")
    log.append({"action": env.actions_taken, "purpose": planned.purpose,
                "total": info["total_reward"], "factors": info["factors"]})
print("success:", info["success"])

# %% Knock the top box off the finished column: the stack factor's progress drops
poses = env.object_poses()
boxes = sorted((n for n in env.object_names if n.startswith("boxes__")),
               key=lambda n: poses[n].pos[2])
top = boxes[-1]
handle = env.scene.objects[top]
base_xy = poses[boxes[0]].pos[:2]
# A free table spot for the fallen box: the candidate farthest from every other object.
others = np.array([p.pos[:2] for n, p in poses.items() if n != top])
candidates = [base_xy + np.array(d) for d in
              ((0.15, 0.0), (-0.15, 0.0), (0.0, 0.15), (0.0, -0.15), (0.12, 0.12))]
spot = max(candidates, key=lambda c: np.min(np.linalg.norm(others - c, axis=1)))
# It lands upright, turned by 30 degrees: a top-down suction primitive turns objects
# about the vertical only, so a box lying on its side could not be set right again
# (the stack check would report it "tilted 90 deg" after every attempt).
fallen = Pose.from_xyz_yaw(spot[0], spot[1], handle.size[2] / 2 + 0.002, np.radians(30))
set_object_pose(env.model, env.data, handle, fallen)
mujoco.mj_forward(env.model, env.data)
for _ in range(200):  # let it come to rest
    mujoco.mj_step(env.model, env.data)
status = env.status()
print(f"knocked {top} over: total {status.reward:.3f}, success {status.success}")
for name, s in status.factors.items():
    print(f"  {name}: progress {s.progress:.2f} satisfied {s.satisfied} {s.detail}")
log.append({"action": "knock-over", "total": status.reward,
            "factors": {n: s.progress for n, s in status.factors.items()}})

# %% The oracle re-plans from the current state and repairs the column
# env.step's reward is the change from the total it saw after its own last step, so
# the repair's step reward (0) nets the knock-over (-1/6) and the repair (+1/6).
while (planned := oracle.plan()) is not None:
    _, reward, terminated, _, info = env.step(planned.as_env_action())
    print(f"repair: {planned.purpose} reward {reward:+.3f} total {info['total_reward']:.3f}")
    log.append({"action": env.actions_taken, "purpose": planned.purpose,
                "total": info["total_reward"], "factors": info["factors"]})
    if terminated:
        break
env.close()
(OUT / "03_rewards.json").write_text(json.dumps(log, indent=2))

# %% run_episode: the same loop in one call (a new environment, another seed)
result = run_episode(task, seed=1, robot="floating",
                     on_action=lambda i, a, inf: print(f"  {i}: {a.purpose} -> "
                                                       f"{inf['total_reward']:.2f}"))
print(f"episode seed 1: success {result.success}, reward {result.reward:.2f}, "
      f"{result.steps} actions, {result.sim_seconds:.1f} s simulated")

# %% evaluate_task: several seeds; a task is completed when half of them succeed
summary = evaluate_task(task, episodes=2, seed=10)
print(f"evaluate_task: success rate {summary.success_rate:.0%}, completed {summary.completed}, "
      f"failures {[e.failure for e in summary.episodes if e.failure]}")
print("wrote", OUT / "03_rewards.json")
