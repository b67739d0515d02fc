"""Pose goals whose objects share targets (``replace=True``, more objects than
targets): every object gets a copy of a target it may take, copies stacked."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from scipy.optimize import linear_sum_assignment

from factask.compat.cliport.goals import RecordedGoal, share_targets
from factask.compat.cliport.recorder import RecordedObject


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
