"""Pose goals whose objects share targets (``replace=True``, more objects than
targets): every object gets a copy of a target it may take, copies stacked."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.optimize import linear_sum_assignment

from factask.compat.cliport.goals import RecordedGoal
from factask.compat.cliport.recorder import RecordedObject
from factask.compat.cliport.sharing import SEPARATE_GAP, share_targets


def _block(i: int, height: float = 0.04) -> RecordedObject:
    return RecordedObject(obj_id=i, urdf="block/block.urdf", kind="block",
                          size=(0.04, 0.04, height), color="red", category="rigid",
                          pos=np.zeros(3), quat=np.array([0.0, 0.0, 0.0, 1.0]))


def _goal(matches: np.ndarray, replace: bool = True) -> RecordedGoal:
    n, m = matches.shape
    targets = [(np.array([0.4 + 0.1 * j, 0.0, 0.02]), np.array([0.0, 0.0, 0.0, 1.0]))
               for j in range(m)]
    return RecordedGoal(0, [_block(i) for i in range(n)], [0.0] * n, matches, targets,
                        replace, False, "pose", [], 1.0, "goal")


@st.composite
def shared(draw: st.DrawFn) -> np.ndarray:
    m = draw(st.integers(1, 4))
    n = draw(st.integers(m + 1, 8))
    rows = [draw(st.lists(st.booleans(), min_size=m, max_size=m).filter(any))
            for _ in range(n)]
    return np.array(rows, dtype=int)


@given(shared())
def test_every_object_gets_a_copy_of_a_target_it_may_take(matches: np.ndarray) -> None:
    goal = _goal(matches.copy())
    messages: list[str] = []
    share_targets(goal, messages.append)
    n = matches.shape[0]
    assert len(goal.targets) == n and goal.matches.shape == (n, n)
    # Each copy is of an original target, and an object may take it iff it may take that.
    origin = [round((float(pos[0]) - 0.4) / 0.1) for pos, _ in goal.targets]
    for c, j in enumerate(origin):
        assert (goal.matches[:, c] == matches[:, j]).all()
    # A one-to-one assignment of objects to copies exists within the matches.
    rows, cols = linear_sum_assignment(-goal.matches.astype(float))
    assert goal.matches[rows, cols].all()
    # Copies at one point are one object height apart (a stack), lowest first.
    for j in set(origin):
        zs = [float(pos[2]) for (pos, _), o in zip(goal.targets, origin, strict=True) if o == j]
        assert np.allclose(np.diff(zs), 0.04)
    assert messages and "share" in messages[0]


def test_goals_without_shared_targets_are_left_as_they_are() -> None:
    for goal in (_goal(np.ones((2, 2), dtype=int)), _goal(np.ones((3, 1), dtype=int), False)):
        before = [p.copy() for p, _ in goal.targets]
        share_targets(goal, lambda _: None)
        assert [p.tolist() for p, _ in goal.targets] == [p.tolist() for p in before]


def test_targets_are_spread_as_evenly_as_the_matches_allow() -> None:
    goal = _goal(np.ones((5, 2), dtype=int))
    share_targets(goal, lambda _: None)
    xs = [round(float(p[0]), 3) for p, _ in goal.targets]
    assert sorted(xs.count(x) for x in set(xs)) == [2, 3]


@given(st.integers(2, 5), st.floats(0.030, 0.050), st.floats(-3.1, 3.1))
def test_targets_overlapping_a_little_are_moved_apart_within_the_limit(
        n: int, spacing: float, yaw: float) -> None:
    from factask.compat.cliport.sharing import _separation, separate_targets

    quat = np.array([0.0, 0.0, np.sin(yaw / 2), np.cos(yaw / 2)])
    axis = np.array([np.cos(yaw), np.sin(yaw), 0.0])
    goal = _goal(np.eye(n, dtype=int), replace=False)
    goal.targets = [(np.array([0.5, 0.0, 0.02]) + axis * spacing * k, quat) for k in range(n)]
    before = [p.copy() for p, _ in goal.targets]
    limit = 0.0075
    shifted = separate_targets([goal], limit)
    moves = [float(np.linalg.norm(p[:2] - b[:2])) for (p, _), b in zip(goal.targets, before,
                                                                       strict=True)]
    if not shifted:
        assert not any(moves)  # untouched: no overlap, or none fixable within the limit
    else:
        assert max(moves) <= limit + 1e-9 and shifted[0] == pytest.approx(max(moves))
        half = (0.02, 0.02)
        for a in range(n):
            for b in range(a + 1, n):
                assert _separation((goal.targets[a][0][:2], yaw, half),
                                   (goal.targets[b][0][:2], yaw, half)) is None
    if spacing >= 0.04 + 1e-6:
        assert not shifted  # nothing overlapped


def test_a_tower_sent_to_one_point_is_not_spread() -> None:
    from factask.compat.cliport.sharing import separate_targets

    goal = _goal(np.eye(2, dtype=int), replace=False)
    goal.targets = [(np.array([0.5, 0.0, 0.02]), np.array([0.0, 0.0, 0.0, 1.0])),
                    (np.array([0.5, 0.0, 0.02]), np.array([0.0, 0.0, 0.0, 1.0]))]
    assert separate_targets([goal], 0.0075) == {}


def _ball(i: int) -> RecordedObject:
    return RecordedObject(obj_id=i, urdf="sphere/sphere.urdf", kind="ball",
                          size=(0.04, 0.04, 0.04), color="red", category="rigid",
                          pos=np.zeros(3), quat=np.array([0.0, 0.0, 0.0, 1.0]))


@given(st.integers(2, 6), st.floats(0.0, 0.1))
def test_balls_sharing_a_target_go_side_by_side_within_the_spread_else_stacked(
        n: int, spread: float) -> None:
    goal = RecordedGoal(0, [_ball(i) for i in range(n)], [0.0] * n, np.ones((n, 1), dtype=int),
                        [(np.array([0.5, 0.0, 0.02]), np.array([0.0, 0.0, 0.0, 1.0]))], True,
                        False, "pose", [], 1.0, "balls in the bowl")
    messages: list[str] = []
    share_targets(goal, messages.append, spread=spread)
    pos = np.array([p for p, _ in goal.targets])
    assert len(pos) == n and goal.matches.shape == (n, n) and goal.matches.all()
    offsets = np.linalg.norm(pos[:, :2] - [0.5, 0.0], axis=1)
    if np.allclose(pos[:, 2], 0.02):  # side by side: within the spread, clear of each other
        assert offsets.max() <= spread + 1e-9
        gaps = np.linalg.norm(pos[:, None, :2] - pos[None, :, :2], axis=2) + np.eye(n)
        assert gaps.min() >= np.hypot(0.04, 0.04) - 1e-9
        assert "side by side" in messages[0]
    else:  # stacked at the point: the ring would leave the author's tolerance
        assert np.allclose(offsets, 0) and np.allclose(np.diff(pos[:, 2]), 0.04)
        half_width = (np.hypot(0.04, 0.04) + 2 * SEPARATE_GAP) / 2  # touching, plus a gap
        assert half_width / np.sin(np.pi / n) > spread
        assert "stacked" in messages[0]
