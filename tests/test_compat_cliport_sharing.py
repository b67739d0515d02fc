"""Objects that share one target side by side (balls in one bowl, ``replace=True``)
are told apart: the position tolerance is half the distance between their copies,
so no object is within tolerance of a copy but its own."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from factask.compat.cliport import import_cliport
from factask.compat.cliport.goals import RecordedGoal
from factask.compat.cliport.recorder import RecordedObject
from factask.compat.cliport.sharing import share_targets
from factask.relations import AtPose

TASKS = Path(__file__).parent / "cliport_tasks"


def _ball(i: int, d: float) -> RecordedObject:
    return RecordedObject(obj_id=i, urdf="ball/ball-template.urdf", kind="ball",
                          size=(d, d, d), color="red", category="rigid", pos=np.zeros(3),
                          quat=np.array([0.0, 0.0, 0.0, 1.0]))


@given(st.integers(2, 5), st.floats(0.02, 0.06), st.integers(1, 2))
def test_the_spacing_is_the_closest_two_copies(n: int, d: float, m: int) -> None:
    n = max(n, m + 1)
    targets = [(np.array([0.4 + 0.3 * j, 0.0, 0.0]), np.array([0.0, 0.0, 0.0, 1.0]))
               for j in range(m)]
    goal = RecordedGoal(0, [_ball(i, d) for i in range(n)], [0.0] * n, np.ones((n, m), int),
                        targets, True, False, "pose", [], 1.0, "balls in the bowl")
    spacing = share_targets(goal, lambda _: None, spread=1.0)
    xy = np.array([pos[:2] for pos, _ in goal.targets])
    gaps = [float(np.linalg.norm(a - b)) for i, a in enumerate(xy) for b in xy[i + 1:]]
    assert spacing is not None  # more balls than targets: some target has two
    assert math.isclose(spacing, min(gaps), rel_tol=1e-9)
    # Side by side, clear of each other: at least a ball apart.
    assert spacing >= d


def test_stacked_copies_report_no_spacing() -> None:
    blocks = [RecordedObject(i, "block/block.urdf", "block", (0.04, 0.04, 0.04), "red", "rigid",
                             np.zeros(3), np.array([0.0, 0.0, 0.0, 1.0])) for i in range(3)]
    goal = RecordedGoal(0, blocks, [0.0] * 3, np.ones((3, 1), int),
                        [(np.array([0.4, 0.0, 0.02]), np.array([0.0, 0.0, 0.0, 1.0]))],
                        True, False, "pose", [], 1.0, "stack")
    assert share_targets(goal, lambda _: None, spread=1.0) is None


def test_two_small_balls_in_one_bowl_are_checked_against_their_own_copy() -> None:
    imported = import_cliport(TASKS / "balls_by_size_share_bowls.py", seed=0)
    factor = imported.graph.factors[0]  # the small balls
    assert isinstance(factor.goal, AtPose)
    a, b = factor.goal.poses
    spacing = math.hypot(a.x - b.x, a.y - b.y)
    # 3 cm balls 4.3 cm apart: the bowl's 5 cm tolerance reached both copies.
    assert spacing < 0.05
    assert math.isclose(factor.goal.tolerances.xy, spacing / 2, rel_tol=1e-3)
