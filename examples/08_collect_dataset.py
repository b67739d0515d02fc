"""Example 08: observation modes, a LeRobot v3.0 demonstration dataset, replay, evaluation.

Run: ``python examples/08_collect_dataset.py`` (about half a minute with software
rendering). Writes under ``out/examples/``: ``08_cameras.png`` (Ravens' front, left
and right cameras, then CLIPort's fused colour and height maps of the same scene),
``08_dataset/`` (a LeRobot v3.0 dataset of oracle demonstrations with a states file
per episode), ``08_dataset_control/`` (the same at the control rate: a frame per
low-level command) and ``08_summary.json``.

The same from the command line::

    factask collect place-red-in-green -n 4 --size 160x120 -o out/demo
    factask collect place-red-in-green -n 4 --frames control --no-video -o out/demo_50hz
    factask replay out/demo --episode 0 --video out/replay.mp4
    factask eval-policy oracle place-red-in-green -n 4 --workers 1
"""

# %% Imports and the output folder
import json
import shutil
from pathlib import Path

import gymnasium as gym
import imageio.v3 as iio
import numpy as np

import factask  # registers the gymnasium ids factask/<task>-v0
from factask.datasets.control_frames import default_control_fps
from factask.datasets.replay import compare_states, resimulate
from factask.datasets.shards import CollectConfig, collect
from factask.datasets.states import read_states
from factask.evaluation.policy import evaluate_policy
from factask.sim.render.observations import decode_text

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)
TASK = "place-red-in-green"

# %% A gymnasium id with RGB-D observations: three cameras, language in every observation
env = gym.make(f"factask/{TASK}-v0", obs_mode="rgbd", image_size=(160, 120))
obs, info = env.reset(seed=0)
print("instruction:", decode_text(obs["instruction"]))
print("current goal:", decode_text(obs["goal"]))
labels = env.get_wrapper_attr("segmentation_labels")
print("segmentation ids:", {i: v["variable"] for i, v in labels.items()})
views = [obs["images"][c]["rgb"] for c in ("front", "left", "right")]
env.close()

# %% The height-map mode: CLIPort's top-down colour and height, 3.125 mm per pixel
env = factask.make(TASK, obs_mode="heightmap", image_size=(640, 480))  # as CLIPort
obs, _ = env.reset(seed=0)
color, height = obs["heightmap"]["color"], obs["heightmap"]["height"]
env.close()
# One picture: the three camera views on top, the two maps (rows = y, columns = x) below.
hm = np.repeat((255 * height / max(float(height.max()), 1e-6)).astype(np.uint8)[..., None], 3, -1)
maps = np.concatenate([color, hm], axis=1)  # 320 x 320
row = np.concatenate(views, axis=1)  # 120 x 480
canvas = np.zeros((row.shape[0] + maps.shape[0], max(row.shape[1], maps.shape[1]), 3), np.uint8)
canvas[:row.shape[0], :row.shape[1]] = row
canvas[row.shape[0]:, :maps.shape[1]] = maps
iio.imwrite(OUT / "08_cameras.png", canvas)

# %% Collect oracle demonstrations as a LeRobot v3.0 dataset (train seeds 0, 2, ...)
root = OUT / "08_dataset"
shutil.rmtree(root, ignore_errors=True)
config = CollectConfig(tasks=(TASK,), episodes=2, image_size=(64, 48), shard_size=1)
summary = collect(config, root, workers=1)
info = json.loads((root / "meta" / "info.json").read_text())
print(f"{summary.episodes_kept} episodes, {info['total_frames']} frames, "
      f"features: {sorted(info['features'])}")

# %% The same demonstrations at the control rate: a frame per low-level command (50 Hz)
control_root = OUT / "08_dataset_control"
shutil.rmtree(control_root, ignore_errors=True)
control = collect(CollectConfig(tasks=(TASK,), episodes=1, image_size=None,
                                fps=default_control_fps(), frames="control"),
                  control_root, workers=1)
control_info = json.loads((control_root / "meta" / "info.json").read_text())
print(f"control frames: {control.frames} at {control_info['fps']} fps, action = "
      f"{control_info['features']['action']['names']}, beside action.primitive")

# %% Replay episode 0 from its states file: the physics is deterministic, bit for bit
states = read_states(root / "states" / "episode_000000.npz")
differences = compare_states(states, resimulate(states))
print("replay:", differences or "bit-identical")

# %% Evaluate the two reference policies on test seeds (10001, 10003, ...)
scores = {}
for policy in ("oracle", "random"):
    _, (score,) = evaluate_policy(policy, [TASK], episodes=2, workers=1)
    scores[policy] = score.to_dict()
    print(f"{policy}: success {score.success_at_end:.0%} "
          f"[{score.success_at_end_ci[0]:.0%}, {score.success_at_end_ci[1]:.0%}]")

(OUT / "08_summary.json").write_text(json.dumps(
    {"collect": summary.to_dict(), "control_frames": control.frames,
     "replay_identical": not differences, "scores": scores},
    indent=2))
