"""compat: a CLIPort cylinder laid on its side is a ``log`` (factask.compat.cliport.lying)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from factask.compat.cliport import import_cliport
from factask.compat.cliport.lying import is_lying, log_quat

TASKS = Path(__file__).parent / "cliport_tasks"


def _xyzw(roll: float, pitch: float, yaw: float) -> np.ndarray:
    return Rotation.from_euler("xyz", [roll, pitch, yaw]).as_quat()


@given(st.floats(-math.pi, math.pi), st.floats(-0.2, 0.2))
def test_a_cylinder_turned_a_quarter_about_a_horizontal_axis_lies(yaw: float,
                                                                  wobble: float) -> None:
    assert is_lying(_xyzw(math.pi / 2 + wobble, 0.0, yaw))
    assert is_lying(_xyzw(0.0, math.pi / 2 + wobble, yaw))
    assert not is_lying(_xyzw(wobble, 0.0, yaw))
    assert not is_lying(_xyzw(math.pi + wobble, 0.0, yaw))  # upside down: still upright


@given(st.floats(-math.pi, math.pi), st.floats(-0.3, 0.3))
def test_the_logs_axis_is_the_cylinders_axis_in_the_table_plane(yaw: float,
                                                                wobble: float) -> None:
    cylinder = _xyzw(math.pi / 2 + wobble, 0.0, yaw)
    # Roll a quarter turn, then yaw: the cylinder's axis (its body z) points along
    # (sin yaw, -cos yaw) in the plane; the log's own axis is its body x.
    log_axis = Rotation.from_quat(log_quat(cylinder)).as_matrix()[:, 0]
    want = np.array([math.sin(yaw), -math.cos(yaw)])
    assert abs(abs(float(log_axis[:2] @ want)) - 1.0) < 1e-9
    assert abs(float(log_axis[2])) < 1e-12


def test_a_cylinder_laid_across_blocks_is_a_log_across_them() -> None:
    imported = import_cliport(TASKS / "cylinder_across_blocks.py", seed=0)
    graph = imported.graph
    log = next(v for v in graph.variables if v.color == "green")
    assert log.kind == "log"
    np.testing.assert_allclose(log.size, (0.14, 0.04, 0.04))
    goal = next(f.goal for f in graph.factors if log.name in f.goal.objects)
    # Its axis along y at the target: a log turned by 90 degrees (or -90).
    assert abs(abs(goal.poses[0].yaw_deg) - 90.0) < 1e-6
    assert goal.poses[0].z is not None and abs(goal.poses[0].z - 0.06) < 1e-6
