"""The slot relations' check on the device (factask.batch.device_checks, Warp kernels on
Warp's CPU device) against the NumPy batched check, which tests/test_batch_checks.py
holds to the scalar one: the same placed objects, satisfied and progress in every
world, on random states (the same generator) and where the host must solve."""

from __future__ import annotations

import importlib.util

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_batch_checks import LIBRARY, _graph, _reset, _world, rolled_log_worlds

from factask.batch.checks import check_factor_batch
from factask.batch.scene import BatchScene
from factask.batch.targets import BatchTargets
from factask.geometry import Pose
from factask.relations.solving import SolvedFactor
from factask.scene.objects import objects_by_name

pytestmark = pytest.mark.xdist_group("warp")
if importlib.util.find_spec("warp") is None:
    pytest.skip("the gpu extra is not installed (make test installs it)",
                allow_module_level=True)

from factask.batch.device_checks import DEVICE_SLOT_KINDS, DeviceSlotCheck  # noqa: E402

#: Relation examples of the slot kinds, and library tasks with slot factors.
NAMES = (*DEVICE_SLOT_KINDS, *(n for n in LIBRARY if n != "put-block-in-bowl"))


def _compare(name: str, worlds: list[tuple[dict[str, Pose], dict[str, SolvedFactor],
                                           list[str]]]) -> list[np.ndarray]:
    """Device and NumPy agree on every slot factor; returns each factor's host-solved
    worlds."""
    import warp as wp

    graph = _graph(name)
    objs = objects_by_name(graph)
    scene = BatchScene.from_poses(objs, [w[0] for w in worlds], [w[2] for w in worlds])
    poses = wp.array(np.concatenate([scene.pos, scene.quat], axis=-1), dtype=wp.float64,
                     device="cpu")
    held = wp.array(scene.held.astype(np.int32), dtype=wp.int32, device="cpu")
    solved_on_host = []
    for f in graph.factors:
        if f.goal.kind() not in DEVICE_SLOT_KINDS:
            continue
        targets = BatchTargets.stack([w[1][f.name] for w in worlds])
        want = check_factor_batch(f.goal, targets, scene)
        status = DeviceSlotCheck(f.goal, targets, objs, scene.names, "cpu").check(poses, held)
        got = status.to_host()
        where = f"{name} factor {f.name}"
        assert np.array_equal(got.placed, want.placed), where
        assert np.array_equal(got.satisfied, want.satisfied), where
        assert np.array_equal(got.progress, want.progress), where
        solved_on_host.append(status.solved_on_host)
    return solved_on_host


@settings(max_examples=30, deadline=None)
@given(st.sampled_from(NAMES), st.lists(st.integers(0, 2), min_size=1, max_size=4), st.data())
def test_device_slot_checks_equal_the_numpy_ones(name: str, seeds: list[int],
                                                 data: st.DataObject) -> None:
    _compare(name, [_world(data, name, s) for s in seeds])


def test_a_rolled_log_fits_its_slot_on_the_device_as_in_numpy() -> None:
    _compare("cylinder-alignment", rolled_log_worlds())


def test_worlds_that_are_not_one_to_one_are_solved_as_numpy_solves_them() -> None:
    """Two blocks of a pyramid at one slot: fits are not one-to-one there, so that
    world's assignment is the host's solver; the other world stays on the device."""
    name = "stack-block-pyramid"
    objs = objects_by_name(_graph(name))
    worlds = []
    for seed in (0, 1):
        layout, solved = _reset(name, seed)
        final = dict(layout)
        for s in solved.values():
            final.update(s.targets(objs))
        worlds.append((final, solved, []))
    base = next(s for s in worlds[0][1].values() if len(s.objects) > 1)
    first, second = base.objects[:2]
    worlds[0][0][second] = worlds[0][0][first]
    hosted = _compare(name, worlds)
    assert any(h.tolist() == [0] for h in hosted)
    assert all(1 not in h.tolist() for h in hosted)


def test_a_stack_counts_from_the_bottom_up_on_the_device() -> None:
    """Every block of a stack at its target but the bottom one at its start: the blocks
    above a gap are not placed (the chain rule), on the device as in NumPy."""
    name = "stack"
    objs = objects_by_name(_graph(name))
    layout, solved = _reset(name, 0)
    (factor,) = solved.values()
    targets = factor.targets(objs)
    complete = dict(layout) | targets
    gap = complete | {factor.objects[0]: layout[factor.objects[0]]}
    _compare(name, [(complete, solved, []), (gap, solved, [])])
    scene = BatchScene.from_poses(objs, [complete, gap])
    (goal,) = (f.goal for f in _graph(name).factors)
    status = check_factor_batch(goal, BatchTargets.stack([factor, factor]), scene)
    assert status.satisfied.tolist() == [True, False] and not status.placed[1].any()
