"""Example 10: many worlds of one task at once on MuJoCo Warp (the batched backend).

Run: ``python examples/10_batched.py`` (needs the ``gpu`` extra; about half a minute
once Warp has compiled its kernels — the first run on a machine compiles them, a few
minutes on a CPU). Writes ``out/examples/10_batched.json``.

``make_batch`` compiles the task once and keeps ``num_envs`` worlds of it on a Warp
device: a GPU when there is one, else Warp's CPU device (slow, but the same code).
A world reset with seed *s* starts from the single env's state for seed *s*; a
low-level command (here the floating cup's pose) steps every world at once, the
suction switches per world, and the batched checks score every factor in every
world. The pick-and-place below is scripted in a few lines (no guarded moves): the
batched primitive and oracle are still to come.
"""

# %% Imports and the output folder
import json
import time
from pathlib import Path

import numpy as np

import factask as ft
from factask.batch import BatchScene, check_task_batch
from factask.geometry import Pose
from factask.sim.env import FactaskEnv

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)

# %% Four worlds of one task; seeds 0..3, as a gymnasium vector env seeds them
batch = ft.make_batch("put-block-in-bowl", num_envs=4, device="cpu")
obs = batch.reset(seed=0)
print("device", batch.device, "worlds", batch.num_envs, "objects", batch.object_names,
      "object_poses", obs["object_poses"].shape)

# %% World 2 starts where the single env starts for seed 2
single = FactaskEnv(batch.graph)
single_obs, _ = single.reset(seed=2)
gap = float(np.abs(obs["object_poses"][2] - single_obs["object_poses"]).max())
print(f"world 2 vs the single env's seed 2: {gap:.1e} m apart (Warp computes in float32)")
single.close()

# %% A scripted pick-and-place in lockstep: every cup takes its world's block to its bowl
mover = batch.graph.factors[0].goal.objects[0]  # the block the task moves
block = batch.object_names.index(mover)
half = float(batch.objects[mover].half[2])
start = obs["object_poses"][:, block, :3]
goal = np.array([s.targets(batch.objects)[mover].pos for s in
                 (batch.solved[w][batch.graph.factors[0].name] for w in range(batch.num_envs))])


def move(a: np.ndarray, b: np.ndarray, steps: int) -> np.ndarray:
    """The cup from a to b (x, y, z, yaw per world) in a straight line, all worlds."""
    for s in np.linspace(0.0, 1.0, steps):
        batch.step(a + s * (b - a))
    return b


def at(xyz: np.ndarray, dz: float) -> np.ndarray:
    return np.concatenate([xyz[:, :2], xyz[:, 2:3] + dz, np.zeros((len(xyz), 1))], axis=1)


t0 = time.perf_counter()
cmd = move(batch.home_command(), at(start, half + 0.1), 150)
cmd = move(cmd, at(start, half - 0.001), 100)  # onto the block's top
held = batch.suction_on()
print("holding:", batch.held_objects())
cmd = move(cmd, at(start, half + 0.1), 100)
cmd = move(cmd, at(goal, half + 0.1), 150)
cmd = move(cmd, at(goal, half + 0.005), 100)
batch.suction_off()
batch.step(cmd, substeps=150)
steps = 750
elapsed = time.perf_counter() - t0
print(f"{steps} steps of {batch.num_envs} worlds in {elapsed:.1f} s "
      f"({steps * batch.num_envs / elapsed:,.0f} world steps/s on {batch.device})")

# %% Every factor in every world, checked at once
status = batch.status()
print("reward per world:", status.reward.round(3).tolist(), "success:", status.success.tolist())

# %% The batched checks on any states: here every block put at its target
solved_poses = []
for w in range(batch.num_envs):
    poses = {n: Pose(p[:3], p[3:]) for n, p in
             zip(batch.object_names, batch.object_poses()[w], strict=True)}
    for s in batch.solved[w].values():
        poses.update(s.targets(batch.objects))
    solved_poses.append(poses)
done = check_task_batch(batch.graph, batch.targets,
                        BatchScene.from_poses(batch.objects, solved_poses))
print("every block at its target:", done.reward.round(3).tolist(), done.success.tolist())

# %% Save what happened
(OUT / "10_batched.json").write_text(json.dumps({
    "device": batch.device,
    "seeds": batch.seeds.tolist(),
    "gap_to_single_env_m": gap,
    "world_steps_per_second": steps * batch.num_envs / elapsed,
    "held": [bool(h) for h in held],
    "reward": status.reward.tolist(),
    "success": status.success.tolist(),
    "reward_at_targets": done.reward.tolist(),
}, indent=2))
batch.close()
print("wrote", OUT / "10_batched.json")
