"""Batched factor checks (factask.batch.checks, factask.batch.status) against the scalar
ones: the same progress, satisfied and placed objects on the same states, for every
relation kind and for whole tasks (milestones included), on random states.

Pure NumPy: no Warp needed, so these run everywhere.
"""

from __future__ import annotations

import math
from functools import cache

import numpy as np
import pytest
from helpers import perturbed
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.batch.checks import BATCH_CHECKS, check_factor_batch
from factask.batch.scene import BatchScene
from factask.batch.status import check_task_batch
from factask.batch.targets import BatchTargets
from factask.geometry import Pose, quat_from_axis_angle, quat_mul
from factask.graph import SubtaskFactor, TaskGraph
from factask.library import get_task
from factask.relations import RELATION_TYPES
from factask.relations.solving import SolvedFactor
from factask.relations.status import CheckScene
from factask.scene.objects import objects_by_name
from factask.sim.layout.checks import check_task
from factask.sim.layout.reset import reset_layout
from factask.vocabulary.errors import InvalidValueError

KINDS = sorted(RELATION_TYPES)
#: Library tasks that add what the relation examples lack: supports in a group
#: (a bar on two pillars), round bowls, milestones, many factors, a door and a drawer
#: shut over what was put in them, a shelf's levels (put on, started on).
LIBRARY = ("build-house", "put-block-in-bowl", "towers-of-hanoi", "stack-block-pyramid",
           "align-box-corner", "put-bowl-in-microwave-and-close-it",
           "put-bowl-in-open-drawer-and-close-it", "put-blocks-on-two-shelf-levels",
           "take-block-off-shelf-into-zone")


def _example_graph(kind: str) -> TaskGraph:
    variables, goal = RELATION_TYPES[kind].example()
    factor = SubtaskFactor(name=f"{kind}_goal", description=f"an example of {kind}", goal=goal)
    return TaskGraph(name=f"example-{kind.replace('_', '-')}", variables=variables,
                     factors=[factor]).ensure_valid()


@cache
def _graph(name: str) -> TaskGraph:
    return _example_graph(name) if name in RELATION_TYPES else get_task(name)


@cache
def _reset(name: str, seed: int) -> tuple[dict[str, Pose], dict[str, SolvedFactor]]:
    return reset_layout(_graph(name), np.random.default_rng(seed))


#: Per object: where it starts from (its initial pose, its target, or the target of
#: another object of the factor) and how far it is moved from there.
_offsets = st.tuples(*(st.one_of(st.just(0.0), st.floats(-r, r)) for r in
                       (0.03, 0.03, 0.02, 60.0, 40.0)))
_where = st.sampled_from(["start", "target", "target", "target", "swap", "held"])


def _world(data: st.DataObject, name: str, seed: int
           ) -> tuple[dict[str, Pose], dict[str, SolvedFactor], list[str]]:
    graph = _graph(name)
    layout, solved = _reset(name, seed)
    objs = objects_by_name(graph)
    targets: dict[str, Pose] = {}
    for s in solved.values():
        targets.update(s.targets(objs))
    names = sorted(targets)
    poses = dict(layout)
    held: list[str] = []
    for n in names:
        where = data.draw(_where, label=f"{n} from")
        base = {"start": layout[n], "target": targets[n], "held": targets[n],
                "swap": targets[data.draw(st.sampled_from(names), label=f"{n} swap")]}[where]
        poses[n] = perturbed(base, data.draw(_offsets, label=f"{n} offset"))
        if where == "held" and not held:
            held.append(n)
    return poses, solved, held


def _compare(name: str, worlds: list[tuple[dict[str, Pose], dict[str, SolvedFactor],
                                           list[str]]]) -> None:
    graph = _graph(name)
    objs = objects_by_name(graph)
    scene = BatchScene.from_poses(objs, [w[0] for w in worlds], [w[2] for w in worlds])
    targets = {f.name: BatchTargets.stack([w[1][f.name] for w in worlds])
               for f in graph.factors}
    for f in graph.factors:
        got = check_factor_batch(f.goal, targets[f.name], scene)
        for k, (poses, solved, held) in enumerate(worlds):
            want = f.goal.status(solved[f.name], CheckScene(objs, poses, frozenset(held)))
            where = f"{name} factor {f.name} world {k}: {want.detail}"
            assert bool(got.satisfied[k]) == want.satisfied, where
            assert math.isclose(float(got.progress[k]), want.progress, abs_tol=1e-12), where
            placed = {o for o, p in zip(solved[f.name].objects, got.placed[k], strict=True) if p}
            assert placed == set(want.placed), where
    total = check_task_batch(graph, targets, scene)
    for k, (poses, solved, held) in enumerate(worlds):
        want_task = check_task(graph, solved, poses, frozenset(held), objs)
        assert math.isclose(float(total.reward[k]), want_task.reward, abs_tol=1e-12)
        assert bool(total.success[k]) == want_task.success
        reached = {n for n, r in zip(total.factor_names, total.reached[k], strict=True) if r}
        assert reached == set(want_task.reached)


def test_every_relation_kind_has_a_batched_check() -> None:
    assert set(BATCH_CHECKS) == set(RELATION_TYPES)


@settings(max_examples=25)
@given(st.sampled_from(KINDS), st.lists(st.integers(0, 3), min_size=1, max_size=3), st.data())
def test_batched_checks_equal_the_scalar_ones_for_every_relation(
        kind: str, seeds: list[int], data: st.DataObject) -> None:
    _compare(kind, [_world(data, kind, s) for s in seeds])


@pytest.mark.parametrize("kind", KINDS)
def test_at_targets_and_at_start_agree_for_every_relation(kind: str) -> None:
    """The two states every relation must tell apart, deterministic (no search)."""
    graph = _graph(kind)
    objs = objects_by_name(graph)
    worlds = []
    for seed in (0, 1):
        layout, solved = _reset(kind, seed)
        final = dict(layout)
        for s in solved.values():
            final.update(s.targets(objs))
        worlds += [(final, solved, []), (dict(layout), solved, [])]
    _compare(kind, worlds)
    scene = BatchScene.from_poses(objs, [w[0] for w in worlds])
    targets = {f.name: BatchTargets.stack([w[1][f.name] for w in worlds])
               for f in graph.factors}
    status = check_task_batch(graph, targets, scene)
    assert status.success.tolist() == [True, False, True, False]


@settings(max_examples=12)
@given(st.sampled_from(LIBRARY), st.lists(st.integers(0, 2), min_size=1, max_size=3), st.data())
def test_batched_task_status_equals_check_task_on_library_tasks(
        name: str, seeds: list[int], data: st.DataObject) -> None:
    _compare(name, [_world(data, name, s) for s in seeds])


def test_milestones_latch_per_world() -> None:
    """towers-of-hanoi: a milestone reached in one world stays reached there only."""
    graph = _graph("towers-of-hanoi")
    objs = objects_by_name(graph)
    layout, solved = _reset("towers-of-hanoi", 0)
    scene = BatchScene.from_poses(objs, [layout, layout])
    targets = {f.name: BatchTargets.stack([solved[f.name]] * 2) for f in graph.factors}
    first = graph.factor_order()[0]
    col = graph.factor_names().index(first)
    reached = np.zeros((2, len(graph.factors)), dtype=bool)
    reached[0, col] = True
    status = check_task_batch(graph, targets, scene, reached)
    want = [check_task(graph, solved, layout, objects=objs, reached=r)
            for r in ({first}, set())]
    for k in range(2):
        assert np.allclose(status.progress[k],
                           [want[k].factors[n].progress for n in graph.factor_names()])
    assert status.reached[0, col] and not status.reached[1, col]


def test_non_finite_worlds_score_nothing() -> None:
    graph = _graph("stack")
    objs = objects_by_name(graph)
    layout, solved = _reset("stack", 0)
    final = dict(layout)
    for s in solved.values():
        final.update(s.targets(objs))
    broken = dict(final)
    first = next(iter(broken))
    broken[first] = Pose(np.full(3, np.nan), broken[first].quat)
    scene = BatchScene.from_poses(objs, [final, broken])
    targets = {f.name: BatchTargets.stack([solved[f.name]] * 2) for f in graph.factors}
    status = check_task_batch(graph, targets, scene)
    assert status.finite.tolist() == [True, False]
    assert status.success.tolist() == [True, False] and status.reward[1] == 0.0


def test_worlds_must_agree_on_what_the_relation_fixes() -> None:
    _, a = _reset("stack", 0)
    _, b = _reset("row", 0)
    with pytest.raises(InvalidValueError):
        BatchTargets.stack([next(iter(a.values())), next(iter(b.values()))])
    with pytest.raises(InvalidValueError):
        BatchTargets.stack([])


def rolled_log_worlds() -> list[tuple[dict[str, Pose], dict[str, SolvedFactor], list[str]]]:
    """cylinder-alignment's logs at their targets, rolled about their axes by 0, 90,
    180 and -130 deg (placed), then raised 30 deg at one end (not placed)."""
    name = "cylinder-alignment"
    objs = objects_by_name(_graph(name))
    layout, solved = _reset(name, 0)
    targets: dict[str, Pose] = {}
    for s in solved.values():
        targets.update(s.targets(objs))

    def turned(axis: tuple[float, float, float], degrees: float) -> dict[str, Pose]:
        return {**layout, **{n: Pose(p.pos, quat_mul(p.quat, quat_from_axis_angle(
            axis, math.radians(degrees)))) for n, p in targets.items()}}

    worlds = [(turned((1.0, 0.0, 0.0), roll), solved, []) for roll in (0.0, 90.0, 180.0, -130.0)]
    worlds.append((turned((0.0, 1.0, 0.0), 30.0), solved, []))
    return worlds


def test_a_rolled_log_is_at_its_target_in_both_checks() -> None:
    """A log is placed however far it rolled about its axis, in the scalar and the
    batched check alike; not with its axis raised."""
    graph = _graph("cylinder-alignment")
    objs = objects_by_name(graph)
    worlds = rolled_log_worlds()
    _compare("cylinder-alignment", worlds)
    assert [check_task(graph, solved, poses, objects=objs).success
            for poses, solved, _ in worlds] == [True, True, True, True, False]
