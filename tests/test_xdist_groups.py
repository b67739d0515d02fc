"""The suite's parallel run keeps grouped tests on one worker.

Tests that share an expensive, process-wide resource are marked
``pytest.mark.xdist_group`` (the Warp kernels, the llama.cpp server, the CLIPort corpus
run) and ``make test`` runs ``--dist loadgroup``, which sends a group to one worker.
pytest 9 with pytest-xdist 3.8 silently lost the grouping (each group's resource was
built in both workers); this test fails if a run under ``loadgroup`` no longer tags
grouped tests.
"""

from __future__ import annotations

import os

import pytest


@pytest.mark.xdist_group("grouping-check")
def test_a_grouped_test_carries_its_group_under_loadgroup(request: pytest.FixtureRequest) -> None:
    grouping = request.config.getoption("loadgroup", False)  # set on workers under loadgroup
    if not os.environ.get("PYTEST_XDIST_WORKER") or not grouping:
        pytest.skip("only meaningful in a parallel run with --dist loadgroup (make test)")
    assert request.node.nodeid.endswith("@grouping-check"), (
        f"{request.node.nodeid}: --dist loadgroup ignored xdist_group; check the pytest and "
        "pytest-xdist versions pinned in pyproject.toml")
