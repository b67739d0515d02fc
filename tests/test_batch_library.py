"""The batched oracle held to the single one over the library (issue 39).

``compare_task`` runs the lockstep oracle (one world per seed, Warp's CPU device) and
``run_episode`` on seeds 0 and 1 and compares success and action counts. On the CI
machine (2 cores) the whole library takes over an hour on Warp's CPU device, so the
suite runs a stacking, a packing and a roof-on-walls task (whose worlds need the
scalar oracle's obstacle moves); ``FACTASK_BATCH_LIBRARY=1`` runs every batched
library task (``scripts/batch_agreement.py`` writes the same as a table, resumable).
The planning of every library task is held to the scalar oracle's without Warp in
``tests/test_batch_planner.py``.
"""

from __future__ import annotations

import importlib.util
import os

import pytest

from factask.batch.agreement import batched, compare_task
from factask.library import get_task, task_names

pytestmark = pytest.mark.xdist_group("warp")
if importlib.util.find_spec("mujoco_warp") is None:  # pragma: no cover - make test installs it
    pytest.skip("the gpu extra is not installed (make test installs it)",
                allow_module_level=True)

SAMPLE = ("stack-block-pyramid", "packing-boxes", "build-house")
ALL = os.environ.get("FACTASK_BATCH_LIBRARY") == "1"


def _tasks() -> list[str]:
    if not ALL:
        return list(SAMPLE)
    return [n for n in task_names() if batched(get_task(n))]


@pytest.mark.slow
@pytest.mark.parametrize("name", _tasks())
def test_the_batched_oracle_agrees_with_the_single_one(name: str) -> None:
    rows = compare_task(name, get_task(name), (0, 1), device="cpu")
    for row in rows:
        assert row.agrees, row

