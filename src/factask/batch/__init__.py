"""Many worlds of one task at once: a batched backend on MuJoCo Warp (issue 21).

* :mod:`factask.batch.device` — the optional ``gpu`` extra and the Warp device
  (:class:`BatchBackendMissing`, :class:`DeviceUnavailableError`).
* :mod:`factask.batch.env` — :class:`BatchEnv` / :func:`make_batch`: one compiled
  model, many worlds; seeded resets of chosen worlds, a low-level command stepped
  in every world, every world's status.
* :mod:`factask.batch.suction`, :mod:`factask.batch.primitive` — the suction grasp
  per world; one pick-and-place per world in lockstep.
* :mod:`factask.batch.oracle` — the single env's oracle in every world, in lockstep.
* :mod:`factask.batch.vector` — the batch as a gymnasium ``VectorEnv``.
* :mod:`factask.batch.checks` — each relation's vectorised check (NumPy over worlds),
  :mod:`factask.batch.status` — the whole task's status per world.

Importing this package does not import Warp; only making a batch does. See
docs/batch.md for what exists and what does not yet.
"""

from __future__ import annotations

from factask.batch.checks import BATCH_CHECKS, BatchFactorStatus, check_factor_batch
from factask.batch.device import BatchBackendMissing, DeviceUnavailableError, resolve_device
from factask.batch.env import BatchEnv, make_batch
from factask.batch.oracle import BatchEpisodeResult, run_oracle
from factask.batch.primitive import BatchActionResult
from factask.batch.scene import BatchScene
from factask.batch.status import BatchTaskStatus, check_task_batch
from factask.batch.targets import BatchTargets
from factask.batch.vector import BatchVectorEnv

__all__ = ["BATCH_CHECKS", "BatchActionResult", "BatchBackendMissing", "BatchEnv",
           "BatchEpisodeResult", "BatchFactorStatus", "BatchScene", "BatchTargets",
           "BatchTaskStatus", "BatchVectorEnv", "DeviceUnavailableError", "check_factor_batch",
           "check_task_batch", "make_batch", "resolve_device", "run_oracle"]
