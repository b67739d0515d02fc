"""Demonstration datasets: recording episodes, LeRobot v3.0 files, shards, replay.

* :mod:`factask.datasets.splits` — the train / val / test seed ranges;
* :mod:`factask.datasets.recording` — one episode's frames, images and simulator states;
* :mod:`factask.datasets.control_frames` — frames at the control rate (the low-level command);
* :mod:`factask.datasets.states` — the states file beside each episode;
* :mod:`factask.datasets.layout` — LeRobot v3.0's paths and size targets (no pyarrow);
* :mod:`factask.datasets.lerobot` — the LeRobot v3.0 writer (pyarrow + PyAV);
* :mod:`factask.datasets.shards` — (task, seed range) shards, a process pool, resume;
* :mod:`factask.datasets.replay` — re-simulate and re-render an episode from its states.

Submodules are imported explicitly; this package imports nothing heavy.
"""
