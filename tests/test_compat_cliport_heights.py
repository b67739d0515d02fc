"""Where pose targets rest (compat.cliport.goals.resting_heights) when the author's
row is turned: footprints are compared as the author turned them, not by the boxes
around them, so a neighbour never carries a target it does not reach."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from factask.compat.cliport.goals import RecordedGoal, resting_heights
from factask.compat.cliport.recorder import RecordedObject
from factask.compat.cliport.transforms import footprint_separation

BLOCK = (0.04, 0.04, 0.04)
TALL = (0.04, 0.04, 0.1)


def _obj(i: int, kind: str, size: tuple[float, float, float]) -> RecordedObject:
    return RecordedObject(obj_id=i, urdf=f"{kind}/{kind}.urdf", kind=kind, size=size,
                          color="red", category="rigid", pos=np.array([0.5, 0.0, size[2] / 2]),
                          quat=np.array([0.0, 0.0, 0.0, 1.0]), random_start=True)


def _goal(index: int, obj: RecordedObject, xy: np.ndarray, z: float, yaw: float
          ) -> RecordedGoal:
    quat = np.array([0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)])
    return RecordedGoal(index, [obj], [0.0], np.ones((1, 1), dtype=int),
                        [(np.array([xy[0], xy[1], z]), quat)], False, True, "pose", [], 0.5, "")


def _row(yaw: float, gap: float, kind: str, size: tuple[float, float, float],
         author_z: float) -> dict[tuple[int, int], float]:
    """A block's target, then another object's target ``gap`` further along a row
    turned by ``yaw`` (both turned with the row), the second at ``author_z``."""
    base = np.array([0.5, 0.0])
    along = np.array([math.cos(yaw), math.sin(yaw)])
    block, other = _obj(5, "block", BLOCK), _obj(6, kind, size)
    goals = [_goal(0, block, base, 0.02, yaw), _goal(1, other, base + gap * along, author_z, yaw)]
    return resting_heights(goals, [block, other], {5, 6})


@given(st.floats(0.0, 2 * math.pi), st.floats(0.045, 0.12),
       st.sampled_from([("cylinder", TALL), ("block", BLOCK), ("ball", (0.05, 0.05, 0.05))]),
       st.floats(0.03, 0.08))
def test_a_target_beside_another_in_a_turned_row_rests_on_the_table(
        yaw: float, gap: float, other: tuple[str, tuple[float, float, float]],
        author_z: float) -> None:
    # A taller neighbour (or one the author put higher: Ravens ignores z) whose
    # footprint does not reach the block's stands on the table at every turn of
    # the row; at 45 degrees the boxes around the two footprints overlap.
    kind, size = other
    heights = _row(yaw, gap, kind, size, author_z)
    assert heights[(0, 0)] == 0.02
    assert heights[(1, 0)] == size[2] / 2


@given(st.floats(0.0, 2 * math.pi), st.floats(0.0, 0.015))
def test_a_target_over_another_rests_on_it_at_any_turn(yaw: float, offset: float) -> None:
    heights = _row(yaw, offset, "block", BLOCK, 0.06)
    assert heights[(1, 0)] == 0.04 + 0.02


@given(st.floats(-0.2, 0.2), st.floats(-0.2, 0.2), st.floats(0.0, 2 * math.pi),
       st.floats(0.0, 2 * math.pi))
def test_the_separating_move_clears_the_footprints(dx: float, dy: float, ya: float,
                                                  yb: float) -> None:
    a = (np.array([0.0, 0.0]), ya, (0.05, 0.02))
    b = (np.array([dx, dy]), yb, (0.03, 0.01))
    move = footprint_separation(a, b)
    if move is None:
        return
    assert float(np.linalg.norm(move)) > 0.0
    # Moved a hair further than the move, b no longer overlaps a.
    cleared = (b[0] + move * 1.001, yb, b[2])
    assert footprint_separation(a, cleared) is None


def _container(i: int, size: tuple[float, float, float], yaw: float) -> RecordedObject:
    return RecordedObject(obj_id=i, urdf="container/container-template.urdf", kind="container",
                          size=size, color="brown", category="fixed",
                          pos=np.array([0.5, 0.0, size[2] / 2]),
                          quat=np.array([0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)]))


@given(st.floats(0.0, 2 * math.pi), st.floats(-0.5, 0.5), st.floats(0.0, 0.01))
def test_a_box_too_wide_to_go_in_rests_on_the_rim_and_a_narrow_one_on_the_floor(
        yaw: float, turn: float, above: float) -> None:
    # A lid wider than the container's opening, put at (or a little above) the rim,
    # rests on the walls; a box that fits, at the same author z, drops to the floor.
    host = _container(5, (0.1, 0.1, 0.05), yaw)
    for i, (size, expect) in enumerate([((0.12, 0.12, 0.01), 0.05 + 0.005),
                                        ((0.05, 0.05, 0.01), 0.005)]):
        box = RecordedObject(obj_id=6 + i, urdf="box/box-template.urdf", kind="box", size=size,
                             color="red", category="rigid", pos=np.array([0.3, 0.3, 0.005]),
                             quat=np.array([0.0, 0.0, 0.0, 1.0]), random_start=True)
        goal = _goal(0, box, np.array([0.5, 0.0]), 0.055 + above, yaw + turn)
        assert resting_heights([goal], [host, box], {box.obj_id})[(0, 0)] == \
            pytest.approx(expect)
