"""``row ... along`` a corner marker's arm, or between two anchors.

``along`` takes one variable (a line, zone, ...; or a corner: the row runs along
its longer arm from the inner vertex) or a list of two (the row lies on the table
in the gap between them, first object nearest the first). The schema is
property-tested; the solver's geometry and the check are tested on small scenes.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from pydantic import TypeAdapter, ValidationError

from factask.geometry import Pose
from factask.graph import Row, StateVariable, SubtaskFactor, TaskGraph
from factask.relations import Relation
from factask.scene.collision import LayoutError
from factask.scene.objects import corner_vertex, objects_by_name, yaw_rotation_2d
from factask.sim.layout.checks import check_task
from factask.sim.layout.reset import reset_layout

names = st.from_regex(r"[a-z][a-z0-9]{0,6}(_[a-z0-9]{1,4})?", fullmatch=True)
BLOCK = (0.04, 0.04, 0.04)


@given(st.lists(names, min_size=1, max_size=2, unique=True))
def test_along_takes_one_or_two_names_and_round_trips(guide: list[str]) -> None:
    for along in (guide, guide[0]):
        goal = Row(objects=["blocks_x"], along=along)
        again = TypeAdapter(Relation).validate_json(goal.model_dump_json())
        assert again == goal
        assert again.anchors() == ([along] if isinstance(along, str) else guide)


@pytest.mark.parametrize("bad", [[], ["a", "b", "c"], ["A"], "a__b"])
def test_along_rejects_other_lists(bad: object) -> None:
    with pytest.raises(ValidationError):
        Row(objects=["blocks_x"], along=bad)


def _graph(variables: list[StateVariable], goal: Row) -> TaskGraph:
    return TaskGraph(name="g", variables=variables,
                     factors=[SubtaskFactor(name="row", description="a row", goal=goal)])


def _blocks(n: int = 3) -> StateVariable:
    return StateVariable(name="blocks", kind="block", size=BLOCK, count=n)


def test_problems_name_a_repeated_or_misplaced_guide() -> None:
    zone = StateVariable(name="zone", kind="zone")
    corner = StateVariable(name="corner", kind="corner", size=(0.2, 0.2, 0.001))
    block = StateVariable(name="block", kind="block", fixed=True)
    twice = _graph([_blocks(), zone], Row(objects=["blocks"], along=["zone", "zone"]))
    assert any("listed twice" in p.message for p in twice.problems())
    mixed = _graph([_blocks(), zone, corner], Row(objects=["blocks"], along=["zone", "corner"]))
    assert any("is a corner" in p.message for p in mixed.problems())
    assert _graph([_blocks(), corner], Row(objects=["blocks"], along="corner")).problems() == []
    solid = _graph([_blocks(), block], Row(objects=["blocks"], along="block"))
    assert any("or a corner" in p.message for p in solid.problems())


def _solve(graph: TaskGraph, seed: int) -> tuple[dict, dict, dict[str, Pose]]:
    layout, solved = reset_layout(graph, np.random.default_rng(seed))
    poses = dict(layout)
    for s in solved.values():
        poses.update(s.targets(objects_by_name(graph)))
    return layout, solved, poses


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("size", [(0.22, 0.22, 0.001), (0.08, 0.25, 0.001)])
def test_a_row_along_a_corner_starts_at_its_vertex_along_the_longer_arm(
        seed: int, size: tuple[float, float, float]) -> None:
    corner = StateVariable(name="corner", kind="corner", size=size)
    graph = _graph([_blocks(), corner], Row(objects=["blocks"], along="corner"))
    layout, solved, poses = _solve(graph, seed)
    objs = objects_by_name(graph)
    vertex = corner_vertex(objs["corner"], layout["corner"])
    rot = yaw_rotation_2d(layout["corner"].yaw)
    arm = rot[:, 0] if size[0] >= size[1] else rot[:, 1]
    inward = rot[:, 1] if size[0] >= size[1] else rot[:, 0]
    for k, name in enumerate(["blocks__0", "blocks__1", "blocks__2"]):
        local = poses[name].pos[:2] - vertex
        assert local @ arm == pytest.approx(0.02 + 0.05 * k, abs=1e-6)
        assert local @ inward == pytest.approx(0.02, abs=1e-6)  # touching the arm
    assert check_task(graph, solved, poses).success


def test_a_row_longer_than_the_corner_arm_is_infeasible() -> None:
    corner = StateVariable(name="corner", kind="corner", size=(0.12, 0.12, 0.001))
    graph = _graph([_blocks(4), corner], Row(objects=["blocks"], along="corner"))
    with pytest.raises(LayoutError, match="arm"):
        reset_layout(graph, np.random.default_rng(0))


def _zones(gap_y: float) -> list[StateVariable]:
    from factask.graph import AtFixedPose

    return [StateVariable(name=n, kind="zone", size=(0.12, 0.12, 0.001),
                          initial=AtFixedPose(x=0.55, y=y, yaw_deg=yaw))
            for n, y, yaw in (("near_zone", gap_y, 0.0), ("far_zone", -gap_y, 30.0))]


@pytest.mark.parametrize("seed", [0, 1])
def test_a_row_between_two_zones_lies_in_the_gap_from_the_first(seed: int) -> None:
    graph = _graph([_blocks(), *_zones(0.22)],
                   Row(objects=["blocks"], along=["near_zone", "far_zone"]))
    _, solved, poses = _solve(graph, seed)
    ys = [poses[f"blocks__{k}"].pos[1] for k in range(3)]
    assert ys[0] > ys[1] > ys[2], "first object nearest the first zone (at +y)"
    near_edge, far_edge = 0.22 - 0.06, -0.22 + 0.06 * (np.cos(np.pi / 6) + np.sin(np.pi / 6))
    assert all(far_edge + 0.02 < y < near_edge - 0.02 for y in ys), "in the gap, clear of both"
    assert all(abs(poses[f"blocks__{k}"].pos[0] - 0.55) < 1e-6 for k in range(3))
    assert np.mean(ys) == pytest.approx((near_edge + far_edge) / 2, abs=1e-6)
    assert check_task(graph, solved, poses).success


def test_a_row_longer_than_the_gap_is_infeasible() -> None:
    graph = _graph([_blocks(4), *_zones(0.14)],
                   Row(objects=["blocks"], along=["near_zone", "far_zone"]))
    with pytest.raises(LayoutError, match="gap"):
        reset_layout(graph, np.random.default_rng(0))


def test_the_check_counts_each_block_in_its_slot() -> None:
    graph = _graph([_blocks(), *_zones(0.22)],
                   Row(objects=["blocks"], along=["near_zone", "far_zone"]))
    _, solved, poses = _solve(graph, 0)
    assert check_task(graph, solved, poses).factors["row"].progress == 1.0
    last = 1.0
    for dx in np.linspace(0.0, 0.05, 11):
        moved = dict(poses)
        p = poses["blocks__1"]
        moved["blocks__1"] = Pose(p.pos + np.array([dx, 0.0, 0.0]), p.quat)
        fs = check_task(graph, solved, moved).factors["row"]
        assert fs.satisfied == (dx < 0.0099)
        assert fs.progress in (pytest.approx(2 / 3), 1.0) and fs.progress <= last
        last = fs.progress
    assert not fs.satisfied and fs.targets == {"blocks__1": 1}


def test_align_along_line_binds_one_guide_as_a_name_and_two_as_a_list() -> None:
    from factask.library.templates import get_template

    tpl = get_template("align_along_line")
    blocks = _blocks()
    zones = _zones(0.22)
    assert tpl.instantiate(objects=blocks, line=zones[0]).factors[0].goal.along == "near_zone"
    pair = tpl.instantiate(objects=blocks, line=zones).factors[0]
    assert pair.goal.along == ["near_zone", "far_zone"]
    assert set(pair.scope_names) == {"blocks", "near_zone", "far_zone"}


@pytest.mark.parametrize("along", [None, "line"])
def test_a_row_spaced_closer_than_its_objects_are_wide_is_refused_at_once(along) -> None:
    boxes = StateVariable(name="boxes", kind="container", size=(0.16, 0.16, 0.05), count=3,
                          fixed=False)
    line = StateVariable(name="line", kind="line", size=(0.6, 0.01, 0.001))
    graph = _graph([boxes, line], Row(objects=["boxes"], spacing=0.15, along=along))
    with pytest.raises(LayoutError, match="neighbours would overlap") as info:
        reset_layout(graph, np.random.default_rng(0))
    assert not info.value.retryable  # no search: it can never fit
    wide = _graph([boxes, line], Row(objects=["boxes"], spacing=0.17, along=along))
    reset_layout(wide, np.random.default_rng(0))  # as wide as needed: laid out
