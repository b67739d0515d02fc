"""Where the oracle takes an object (sim.pick_points), and the scene questions it asks
about free receptacles (what rests inside one, what a target inside one collides with)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from factask.geometry import Pose
from factask.library import get_task
from factask.scene.collision import occupying, resting_on
from factask.scene.objects import SceneObject
from factask.sim.episode import run_episode
from factask.sim.oracle.pick_points import (
    CUP_GAP,
    grasp_offset,
    pick_and_place_points,
    takes_by_rim,
)
from factask.sim.robots.suction import CUP_RADIUS
from factask.vocabulary.kinds import WALL_THICKNESS


def _obj(name: str, kind: str, size: tuple[float, float, float], fixed: bool = False,
         round_: bool = False) -> SceneObject:
    return SceneObject(name=name, variable=name, index=0, kind=kind, size=size, color="red",
                       fixed=fixed, symmetry_deg=0.0 if round_ else 90.0, mass=0.1,
                       collides=True)


def _on_table(obj: SceneObject, x: float, y: float, yaw: float = 0.0, z0: float = 0.0) -> Pose:
    return Pose.from_xyz_yaw(x, y, z0 + obj.size[2] / 2, yaw)


BLOCK = _obj("block", "block", (0.04, 0.04, 0.04))
BOWL = _obj("bowl", "bowl", (0.12, 0.12, 0.05), round_=True)


def test_a_solid_object_is_taken_at_its_top_centre() -> None:
    pose = _on_table(BLOCK, 0.5, 0.1, 0.3)
    assert not takes_by_rim(BLOCK)
    pick, place = pick_and_place_points(BLOCK, pose, _on_table(BLOCK, 0.4, -0.2), 0.3, 1.0,
                                        {"block": BLOCK}, {"block": pose})
    np.testing.assert_allclose(pick, [0.5, 0.1, 0.04, 0.3], atol=1e-9)
    np.testing.assert_allclose(place, [0.4, -0.2, 0.04, 1.0], atol=1e-9)


def test_a_fixed_receptacle_is_never_taken_by_its_rim() -> None:
    assert not takes_by_rim(_obj("bowl", "bowl", (0.12, 0.12, 0.05), fixed=True))


def test_a_free_bowl_is_taken_on_its_rim_nearest_the_robot() -> None:
    pose = _on_table(BOWL, 0.5, 0.0)
    offset = grasp_offset(BOWL, pose, {"bowl": BOWL}, {"bowl": pose})
    assert np.linalg.norm(offset) == pytest.approx(0.06 - WALL_THICKNESS / 2)
    assert offset[0] < 0 and abs(offset[1]) < 1e-9  # the robot stands at the origin


def test_the_place_point_turns_with_the_object() -> None:
    box = _obj("box", "container", (0.16, 0.10, 0.05))
    pose = _on_table(box, 0.5, 0.2, 0.0)
    target = _on_table(box, 0.6, -0.1, math.pi / 2)
    pick, place = pick_and_place_points(box, pose, target, 0.0, math.pi / 2, {"box": box},
                                        {"box": pose})
    offset = pick[:2] - pose.pos[:2]
    turned = np.array([-offset[1], offset[0]])  # a quarter turn
    np.testing.assert_allclose(place[:2] - target.pos[:2], turned, atol=1e-9)
    assert pick[2] == pytest.approx(0.05) and place[2] == pytest.approx(0.05)


def test_the_rim_point_keeps_the_cup_off_a_nested_receptacle() -> None:
    outer = _obj("outer", "bowl", (0.165, 0.165, 0.05), round_=True)
    inner = _obj("inner", "bowl", (0.12, 0.12, 0.05), round_=True)
    po = _on_table(outer, 0.5, 0.0)
    # The inner bowl stands on the outer one's floor, pushed towards the robot: the
    # rim nearest the robot is under its wall, the far one is clear.
    pi = _on_table(inner, 0.49, 0.0, z0=WALL_THICKNESS)
    objs, poses = {"outer": outer, "inner": inner}, {"outer": po, "inner": pi}
    offset = grasp_offset(outer, po, objs, poses)
    point = po.pos[:2] + offset
    gap = np.linalg.norm(point - pi.pos[:2]) - inner.size[0] / 2 - CUP_RADIUS
    assert gap >= CUP_GAP
    assert offset[0] > 0


def test_what_lies_inside_a_free_receptacle_comes_off_before_it_moves() -> None:
    pb = _on_table(BOWL, 0.5, 0.0)
    pk = _on_table(BLOCK, 0.5, 0.01, z0=WALL_THICKNESS)
    objs, poses = {"bowl": BOWL, "block": BLOCK}, {"bowl": pb, "block": pk}
    assert resting_on("bowl", objs, poses) == ["block"]
    fixed = _obj("bowl", "bowl", (0.12, 0.12, 0.05), fixed=True, round_=True)
    assert resting_on("bowl", {"bowl": fixed, "block": BLOCK}, poses) == []


def test_a_free_receptacle_does_not_occupy_a_target_inside_it() -> None:
    pb = _on_table(BOWL, 0.5, 0.0)
    pk = _on_table(BLOCK, 0.3, 0.3)
    objs, poses = {"bowl": BOWL, "block": BLOCK}, {"bowl": pb, "block": pk}
    inside = _on_table(BLOCK, 0.5, 0.0, z0=WALL_THICKNESS)
    assert occupying("block", inside, objs, poses) == []
    beside = _on_table(BLOCK, 0.5 + 0.06, 0.0)  # on its wall: it is in the way
    assert occupying("block", beside, objs, poses) == ["bowl"]


def test_round_objects_occupy_by_their_disks() -> None:
    a = _obj("a", "bowl", (0.16, 0.16, 0.05), round_=True)
    b = _obj("b", "bowl", (0.16, 0.16, 0.05), round_=True)
    pa, pb = _on_table(a, 0.4, 0.0), _on_table(b, 0.4 + 0.115, 0.115)
    # Their boxes turned 45 degrees would overlap, the disks (16.3 cm apart) do not.
    target = Pose.from_xyz_yaw(0.4, 0.0, 0.025, math.pi / 4)
    assert occupying("a", target, {"a": a, "b": b}, {"a": pa, "b": pb}) == []
    near = Pose.from_xyz_yaw(0.4 + 0.05, 0.05, 0.025)
    assert occupying("a", near, {"a": a, "b": b}, {"a": pa, "b": pb}) == ["b"]


def test_the_oracle_carries_a_bowl_by_its_rim_into_the_corner() -> None:
    # At the top centre the cup would find only air over the bowl's floor.
    r = run_episode(get_task("move-bowl-from-pallet-to-corner"), 0, robot="floating")
    assert r.success and r.steps == 1, r.failure
