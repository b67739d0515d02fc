"""Shared pytest configuration: headless rendering and offline litellm."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")
os.environ.setdefault("LITELLM_LOCAL_MODEL_COST_MAP", "True")

from hypothesis import HealthCheck, settings

settings.register_profile(
    "factask", deadline=None, suppress_health_check=[HealthCheck.too_slow], max_examples=60
)
# CI replays the same examples every run (derandomize), so a landing is decided by
# the change under test, not by which random examples a run drew; developers' runs
# keep exploring new examples (and hypothesis keeps the failures they find).
settings.register_profile("factask-ci", parent=settings.get_profile("factask"),
                          derandomize=True)
settings.load_profile("factask-ci" if os.environ.get("CI") else "factask")


def pytest_collection_modifyitems(config, items) -> None:
    """The tests marked slow first (a stable sort: the order is otherwise kept).

    xdist hands tests to its two workers in collection order; a sweep of several
    minutes collected last starts when the other worker has run out of work, and the
    suite waits for it alone. Started first, the long ones overlap the short ones.
    """
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)
