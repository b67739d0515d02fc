"""Stepped shelves and their levels (issue 38: ``on`` a shelf level): the kinds, a
level's pose from its shelf's, the collision rule over the levels, starts on a
level, the oracle putting things on levels with both robots, validation."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from factask.geometry import Pose
from factask.graph import GraphValidationError, parse_graph
from factask.library import get_task
from factask.library.catalog_shelves import SHELF, shelf
from factask.scene.collision import Occupancy
from factask.scene.objects import bottom_z, objects_by_name, placement_area, rest_surface_z
from factask.scene.shelf import level_pose, level_seat, shelf_boxes
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.layout.reset import reset_layout
from factask.vocabulary.kinds import (
    SHELF_RISE,
    WALL_THICKNESS,
    shelf_level_offset,
    shelf_level_size,
    shelf_level_top,
)


def test_levels_tile_the_shelf_rising_towards_its_back() -> None:
    size = SHELF
    for levels in (1, 2, 3):
        sizes = [shelf_level_size(size, levels, k) for k in range(levels)]
        offsets = [shelf_level_offset(size, levels, k) for k in range(levels)]
        # Side by side from the -x face to the back panel, each on the shelf's bottom.
        assert offsets[0][0] - sizes[0][0] / 2 == pytest.approx(-size[0] / 2)
        assert offsets[-1][0] + sizes[-1][0] / 2 == pytest.approx(size[0] / 2 - WALL_THICKNESS)
        for k in range(levels):
            assert offsets[k][2] - sizes[k][2] / 2 == pytest.approx(-size[2] / 2)
            assert sizes[k][1] == pytest.approx(size[1] - 2 * WALL_THICKNESS)
            if k:
                assert sizes[k][2] > sizes[k - 1][2]
                assert offsets[k][0] - sizes[k][0] / 2 == pytest.approx(
                    offsets[k - 1][0] + sizes[k - 1][0] / 2)
        assert shelf_level_top(size, levels, levels - 1) == pytest.approx(size[2] - SHELF_RISE)
        # The panels' bounding box is the shelf's size.
        boxes = shelf_boxes(size, levels)
        lo = np.min([b[1] for b in boxes], axis=0)
        hi = np.max([b[2] for b in boxes], axis=0)
        np.testing.assert_allclose(hi - lo, size, atol=1e-12)


def test_a_levels_pose_follows_its_shelfs_in_the_layout_and_the_scene() -> None:
    graph = get_task("put-blocks-on-two-shelf-levels")
    objs = objects_by_name(graph)
    for seed in range(4):
        poses, _ = reset_layout(graph, np.random.default_rng(seed))
        for name in ("lower_level", "upper_level"):
            want = level_pose(objs["shelf"], poses["shelf"], level_seat(graph, name))
            np.testing.assert_allclose(poses[name].pos, want.pos, atol=1e-9)
            np.testing.assert_allclose(poses[name].quat, want.quat, atol=1e-9)
    # Turned a quarter: the offset turns with the shelf.
    turned = Pose.from_xyz_yaw(0.5, 0.0, SHELF[2] / 2, np.pi / 2)
    pose = level_pose(objs["shelf"], turned, level_seat(graph, "upper_level"))
    dx = shelf_level_offset(SHELF, 2, 1)[0]
    np.testing.assert_allclose(pose.pos[:2], [0.5, dx], atol=1e-9)
    assert rest_surface_z(objs["upper_level"], pose) == pytest.approx(SHELF[2] - SHELF_RISE)
    env = FactaskEnv(graph)
    env.reset(seed=3)
    try:
        live = env.object_poses()
        want = level_pose(env.objects["shelf"], live["shelf"], level_seat(graph, "upper_level"))
        np.testing.assert_allclose(live["upper_level"].pos, want.pos, atol=1e-6)
        body = env.scene.objects["upper_level"].body_id
        np.testing.assert_allclose(env.data.xpos[body], want.pos, atol=1e-6)
    finally:
        env.close()


def test_over_its_levels_a_block_meets_the_levels_never_the_shelf() -> None:
    graph = get_task("put-blocks-on-two-shelf-levels")
    objs = objects_by_name(graph)
    shelf_pose = Pose.from_xyz_yaw(0.5, 0.0, SHELF[2] / 2, 0.0)
    occ = Occupancy()
    occ.put("shelf", objs["shelf"], shelf_pose)
    levels = {n: level_pose(objs["shelf"], shelf_pose, level_seat(graph, n))
              for n in ("lower_level", "upper_level")}
    for n, p in levels.items():
        occ.put(n, objs[n], p)
    block = objs["red_block"]
    lower = levels["lower_level"]
    on_lower = Pose.from_xyz_yaw(lower.pos[0], 0.0,
                                 rest_surface_z(objs["lower_level"], lower) + 0.02, 0.0)
    assert occ.blockers(block, on_lower, ignore=["lower_level"]) == []
    # On the table inside the shelf it is in the lower level; over the back panel, the
    # shelf; pushed against the upper step, the upper level.
    on_table = Pose.from_xyz_yaw(lower.pos[0], 0.0, 0.02, 0.0)
    assert "lower_level" in occ.blockers(block, on_table)
    at_back = Pose.from_xyz_yaw(0.5 + SHELF[0] / 2, 0.0, 0.2, 0.0)
    assert occ.blockers(block, at_back) == []  # above it
    against = Pose.from_xyz_yaw(lower.pos[0] + objs["lower_level"].size[0] / 2 - 0.01, 0.0,
                                on_lower.pos[2], 0.0)
    assert occ.blockers(block, against, ignore=["lower_level"]) == ["upper_level"]


@pytest.mark.parametrize("task,level", [("move-block-up-a-shelf-level", "lower_level"),
                                        ("take-block-off-shelf-into-zone", "upper_level")])
def test_a_block_starts_on_its_level(task: str, level: str) -> None:
    graph = get_task(task)
    objs = objects_by_name(graph)
    block = next(v.name for v in graph.variables if v.kind == "block")
    for seed in range(5):
        poses, _ = reset_layout(graph, np.random.default_rng(seed))
        top = rest_surface_z(objs[level], poses[level])
        assert bottom_z(objs[block], poses[block]) == pytest.approx(top)
        assert placement_area(objs[level], poses[level]).contains(poses[block].pos[:2])[0]


@pytest.mark.parametrize("robot", ["floating", "arm"])
def test_the_oracle_puts_a_block_on_the_upper_level_and_it_reads_on(robot: str) -> None:
    graph = get_task("put-block-on-upper-shelf-level")
    env = FactaskEnv(graph, robot=robot)
    try:
        _, info = env.reset(seed=0)
        assert not info["success"]
        result = run_episode(graph, 0, robot=robot, env=env)
        assert result.success and result.failure is None, result.details
        poses = env.object_poses()
        top = rest_surface_z(env.objects["upper_level"], poses["upper_level"])
        assert bottom_z(env.objects["red_block"], poses["red_block"]) == pytest.approx(
            top, abs=0.005)
    finally:
        env.close()


def test_the_oracle_puts_three_blocks_side_by_side_on_one_level() -> None:
    result = run_episode(get_task("put-three-blocks-on-upper-shelf-level"), 1)
    assert result.success and result.steps == 3, (result.failure, result.details)


def test_a_block_moves_from_one_level_to_the_other_with_the_arm() -> None:
    result = run_episode(get_task("move-block-up-a-shelf-level"), 2, robot="arm")
    assert result.success, (result.failure, result.details)


# ----------------------------------------------------------------- validation
def _vars(**change: Any) -> list[dict[str, Any]]:
    box, levels = shelf()
    out = [box.model_dump(), *(v.model_dump() for v in levels.values()),
           {"name": "block", "kind": "block"}]
    for name, fields in change.items():
        var = next(v for v in out if v["name"] == name)
        var.update(fields)
    return out


def _problems(variables: list[dict[str, Any]]) -> list[tuple[str, str, str]]:
    data = {"name": "shelf-task", "description": "Put the block on the upper level.",
            "variables": variables,
            "factors": [{"name": "on_level", "goal": {"type": "on", "objects": ["block"],
                                                      "support": "upper_level"}}]}
    with pytest.raises(GraphValidationError) as err:
        parse_graph(data).ensure_valid()
    return [(p.node, p.field, p.fix) for p in err.value.problems]


def test_a_valid_shelf_graph_passes() -> None:
    parse_graph({"name": "shelf-task", "description": "Put the block on the upper level.",
                 "variables": _vars(),
                 "factors": [{"name": "on_level", "goal": {
                     "type": "on", "objects": ["block"], "support": "upper_level"}}]}
                ).ensure_valid()


def test_a_level_off_any_shelf_is_refused_naming_initial() -> None:
    found = _problems(_vars(upper_level={"initial": {"type": "table"}}))
    assert any(n == "upper_level" and f == "initial" and "in_cabinet" in fix
               for n, f, fix in found), found


def test_a_level_of_the_wrong_size_is_refused_with_the_size_to_give() -> None:
    found = _problems(_vars(upper_level={"size": [0.1, 0.1, 0.1]}))
    want = [round(w, 6) for w in shelf_level_size(SHELF, 2, 1)]
    assert ("upper_level", "size", f"give size {want}") in found


def test_levels_must_be_0_to_n_minus_1() -> None:
    found = _problems(_vars(upper_level={"initial": {"type": "in_cabinet", "cabinet": "shelf",
                                                     "level": 2}}))
    assert any(f == "initial.level" and "0..1" in fix for _, f, fix in found), found


def test_a_level_in_a_cabinet_an_opened_level_a_free_level_are_refused() -> None:
    variables = _vars(upper_level={"initial": {"type": "in_cabinet", "cabinet": "shelf",
                                               "level": 1, "opening": 0.5}, "fixed": False})
    variables.append({"name": "cabinet", "kind": "cabinet"})
    variables.append({"name": "drawer", "kind": "drawer", "initial": {
        "type": "in_cabinet", "cabinet": "cabinet"}, "size": [0.201, 0.252, 0.072]})
    found = {(n, f) for n, f, _ in _problems(variables)}
    assert {("upper_level", "initial.opening"), ("upper_level", "fixed")} <= found
    moved = _vars(lower_level={"initial": {"type": "in_cabinet", "cabinet": "block"}})
    assert ("lower_level", "initial.cabinet") in {(n, f) for n, f, _ in _problems(moved)}


def test_a_shelf_without_levels_is_refused_naming_the_fix() -> None:
    variables = [v for v in _vars() if v["kind"] != "shelf_level"]
    variables.append({"name": "pallet", "kind": "pallet"})
    data = {"name": "shelf-task", "description": "Put the block on the pallet.",
            "variables": variables,
            "factors": [{"name": "on_pallet", "goal": {"type": "on", "objects": ["block"],
                                                       "support": "pallet"}}]}
    with pytest.raises(GraphValidationError) as err:
        parse_graph(data).ensure_valid()
    assert any(p.node == "shelf" and p.field == "kind" and "shelf_level" in p.fix
               for p in err.value.problems)


def test_nothing_on_the_table_starts_inside_the_shelf() -> None:
    # The levels are placed after what starts on the table: the shelf stands in for
    # them (a block once started inside the lower step and fell through the table).
    graph = get_task("put-three-blocks-on-upper-shelf-level")
    objs = objects_by_name(graph)
    for seed in range(12):
        poses, _ = reset_layout(graph, np.random.default_rng(seed))
        occ = Occupancy(clearance=0.0)
        for name in ("shelf", "lower_level", "upper_level"):
            occ.put(name, objs[name], poses[name])
        for k in range(3):
            block = f"yellow_blocks__{k}"
            assert bottom_z(objs[block], poses[block]) == pytest.approx(0.0, abs=1e-9)
            assert occ.blockers(objs[block], poses[block]) == [], (seed, block)


def test_on_the_shelf_itself_is_refused_naming_its_levels_kind() -> None:
    data = {"name": "shelf-task", "description": "Put the block on the shelf.",
            "variables": _vars(),
            "factors": [{"name": "on_shelf", "goal": {"type": "on", "objects": ["block"],
                                                      "support": "shelf"}}]}
    with pytest.raises(GraphValidationError) as err:
        parse_graph(data).ensure_valid()
    assert any("shelf" in p.message for p in err.value.problems), err.value.problems


def test_a_three_level_shelf_the_arm_moves_a_block_from_the_lowest_to_the_top() -> None:
    levels = [{"name": f"level{k}", "kind": "shelf_level", "color": "brown",
               "size": list(shelf_level_size(SHELF, 3, k)),
               "initial": {"type": "in_cabinet", "cabinet": "shelf", "level": k}}
              for k in range(3)]
    graph = parse_graph({
        "name": "three-level-shelf", "description": "Move the block up to the top level.",
        "variables": [{"name": "shelf", "kind": "shelf", "size": list(SHELF)}, *levels,
                      {"name": "block", "kind": "block",
                       "initial": {"type": "on", "support": "level0"}}],
        "factors": [{"name": "up", "goal": {"type": "on", "objects": ["block"],
                                            "support": "level2"}}]}).ensure_valid()
    result = run_episode(graph, 0, robot="arm")
    assert result.success and result.steps == 1, (result.failure, result.details)
