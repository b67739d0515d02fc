"""The workspace's height comes from what the default arm reaches (issue 35, item 4)."""

from __future__ import annotations

import itertools

import pytest

from factask.sim.robots.ik import TopDownIK, top_down_pose
from factask.sim.robots.registry import UR10E
from factask.vocabulary.world import (
    CARRY_ROOM,
    RAVENS_Z,
    TIP_REACH_Z,
    WORKSPACE_X,
    WORKSPACE_Y,
    WORKSPACE_Z,
)

CORNERS = list(itertools.product(WORKSPACE_X, WORKSPACE_Y))


@pytest.mark.parametrize(("x", "y"), CORNERS)
def test_the_default_arm_reaches_the_tip_height_over_every_corner(x: float, y: float) -> None:
    ik = TopDownIK(UR10E)
    _, pos_err, rot_err = ik.solve(top_down_pose([x, y, TIP_REACH_Z], 0.0), max_iterations=600)
    assert pos_err < 0.005 and rot_err < 0.02, (x, y, pos_err, rot_err)


def test_the_tip_height_is_the_arms_reach_not_less() -> None:
    # 5 cm higher the far corner is out of reach: the constant is the reach, not a guess
    ik = TopDownIK(UR10E)
    _, pos_err, _ = ik.solve(top_down_pose([WORKSPACE_X[1], WORKSPACE_Y[1], TIP_REACH_Z + 0.05],
                                           0.0), max_iterations=600)
    assert pos_err > 0.005


def test_the_workspace_top_leaves_room_to_carry_over_it_and_is_above_cliports() -> None:
    assert WORKSPACE_Z[1] == pytest.approx(TIP_REACH_Z - CARRY_ROOM)
    assert WORKSPACE_Z[1] >= 0.4 + 0.04  # a tower of ten 4 cm blocks, and one more
    assert RAVENS_Z == (0.0, 0.3)  # CLIPort's bounds and height maps stay its own
