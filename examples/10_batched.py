"""Example 10: many worlds of one task at once on MuJoCo Warp (the batched backend).

Run: ``python examples/10_batched.py`` (needs the ``gpu`` extra; about half a minute
once Warp has compiled its kernels — the first run on a machine compiles them, a few
minutes on a CPU). Writes ``out/examples/10_batched.json``.

``make_batch`` compiles the task once and keeps ``num_envs`` worlds of it on a Warp
device: a GPU when there is one, else Warp's CPU device (slow, but the same code).
A world reset with seed *s* starts from the single env's state for seed *s*; a
low-level command (here the floating cup's pose) steps every world at once; a
suction pick-and-place runs in every world in lockstep; the batched checks score
every factor in every world; the oracle runs in every world at once, its next
action planned for all the worlds as array work.
"""

# %% Imports and the output folder
import json
import time
from pathlib import Path

import numpy as np

import factask as ft
from factask.batch import BatchScene, check_task_batch, run_oracle
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

# %% A low-level command for every world: each cup 10 cm lower, 100 physics steps
cmd = batch.home_command()
cmd[:, 2] -= 0.1
t0 = time.perf_counter()
batch.step(cmd, substeps=100)
elapsed = time.perf_counter() - t0
print(f"100 steps of {batch.num_envs} worlds in {elapsed:.2f} s "
      f"({100 * batch.num_envs / elapsed:,.0f} world steps/s on {batch.device})")

# %% The observation as device arrays: torch (wp.to_torch) or JAX take them via DLPack
device_obs = batch.observe_device()
view = np.from_dlpack(device_obs["ee_pose"])  # NumPy on the CPU device: no copy
print("tip poses on the device:", view.shape, "same memory:",
      view.ctypes.data == device_obs["ee_pose"].ptr)

# %% One pick-and-place per world, in lockstep: every block to its bowl
factor = batch.graph.factors[0]
mover = factor.goal.objects[0]  # the block the task moves
block = batch.object_names.index(mover)
half = float(batch.objects[mover].half[2])
start = batch.object_poses()[:, block, :3]
goal = np.array([batch.solved[w][factor.name].targets(batch.objects)[mover].pos
                 for w in range(batch.num_envs)])
zeros = np.zeros(batch.num_envs)
pick = np.c_[start[:, :2], start[:, 2] + half, zeros]  # the tip on the block's top
place = np.c_[goal[:, :2], goal[:, 2] + half, zeros]
result = batch.pick_and_place(pick, place)
held = result.ok
print(f"pick-and-place: ok {result.ok.tolist()} in {result.sim_steps} physics steps")

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

# %% The oracle in every world at once: planned as array work over the worlds
batch.reset(seed=10)
episodes = run_oracle(batch)
print(f"oracle in lockstep: success {episodes.success.tolist()}, actions "
      f"{episodes.actions.tolist()}; {episodes.planned_arrays} action(s) planned as arrays, "
      f"{episodes.planned_fallback} by the scalar oracle; planning "
      f"{1e3 * max(episodes.planning_seconds):.1f} ms per lockstep action")

# %% Save what happened
(OUT / "10_batched.json").write_text(json.dumps({
    "device": batch.device,
    "seeds": batch.seeds.tolist(),
    "gap_to_single_env_m": gap,
    "world_steps_per_second": 100 * batch.num_envs / elapsed,
    "pick_and_place_ok": [bool(h) for h in held],
    "reward": status.reward.tolist(),
    "success": status.success.tolist(),
    "reward_at_targets": done.reward.tolist(),
    "oracle_success": episodes.success.tolist(),
    "oracle_planned_arrays": episodes.planned_arrays,
}, indent=2))
batch.close()
print("wrote", OUT / "10_batched.json")
