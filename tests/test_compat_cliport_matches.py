"""A goal's objects, symmetries and ``matches`` rows read as GenSim and Ravens read
them: ``zip_obj_ids`` keeps as many objects as there are symmetries, and Ravens reads
row ``i`` of ``matches`` for object ``i`` only, so rows past the objects are never
read (a short symmetries list, or a matrix written for more objects)."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from factask.compat.cliport import import_cliport
from factask.compat.cliport.errors import CliportImportError
from factask.relations import AtPose

TASKS = Path(__file__).parent / "cliport_tasks"

SOURCE = """
import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class Row(Task):
    def reset(self, env):
        super().reset(env)
        boxes = [env.add_object('block/block.urdf', self.get_random_pose(env, (0.04, 0.04, 0.04)))
                 for _ in range({n})]
        targs = [((0.4, -0.2 + 0.1 * j, 0.02), (0, 0, 0, 1)) for j in range({m})]
        self.add_goal(objs=boxes, matches=np.ones(({rows}, {cols})), targ_poses=targs,
                      replace=False, rotations=True, metric='pose', params=None,
                      step_max_reward=1, symmetries={syms}, language_goal='line up')
"""


def _write(tmp_path: Path, n: int, rows: int, syms: str, m: int | None = None,
           cols: int | None = None) -> Path:
    m = n if m is None else m
    cols = m if cols is None else cols
    path = tmp_path / f"row_{n}_{rows}_{m}_{cols}.py"
    path.write_text(textwrap.dedent(SOURCE.format(n=n, rows=rows, syms=syms, m=m, cols=cols)))
    return path


def _import(tmp_path: Path, n: int, rows: int, syms: str, m: int | None = None,
            cols: int | None = None):
    return import_cliport(_write(tmp_path, n, rows, syms, m, cols), seed=0)


def test_a_short_symmetries_list_keeps_the_first_objects_as_gensim_does() -> None:
    imported = import_cliport(TASKS / "short_symmetries_list.py", seed=0)
    (factor,) = imported.graph.factors
    assert isinstance(factor.goal, AtPose)
    # One symmetry for three boxes: GenSim's zip keeps the first box; the matrix
    # written for three boxes has its two extra rows dropped (was refused).
    assert factor.goal.objects == ["box_orange_0"]
    assert factor.goal.matches == [[1, 1, 1]]
    assert any("keeps the first 1 object" in w for w in imported.warnings)
    assert any("3 row(s) for 1 object(s)" in w for w in imported.warnings)


@settings(max_examples=8, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.integers(1, 3), st.integers(0, 2))
def test_rows_past_the_objects_are_ignored(tmp_path: Path, n: int, extra: int) -> None:
    imported = _import(tmp_path, n, n + extra, "None")
    (factor,) = imported.graph.factors
    assert len(factor.goal.objects) == n
    assert factor.goal.matches == [[1] * n] * n
    assert any("row(s) for" in w for w in imported.warnings) == (extra > 0)


def test_a_matrix_written_targets_by_objects_is_read_as_ravens_reads_it(tmp_path: Path) -> None:
    # Two blocks, three targets, matches (3, 2): Ravens reads rows 0 and 1, each two
    # long, so each block may take the first two targets and never the third.
    imported = _import(tmp_path, 2, 3, "None", m=3, cols=2)
    (factor,) = imported.graph.factors
    assert factor.goal.matches == [[1, 1, 0], [1, 1, 0]]


def test_too_few_rows_are_still_refused(tmp_path: Path) -> None:
    # Ravens would index past the matrix for the third object.
    with pytest.raises(CliportImportError, match=r"matches is \(2, 3\)"):
        _import(tmp_path, 3, 2, "None")


def test_one_number_is_every_objects_symmetry(tmp_path: Path) -> None:
    imported = _import(tmp_path, 3, 3, "np.pi")
    (factor,) = imported.graph.factors
    assert len(factor.goal.objects) == 3
    assert all(imported.graph.variable(o).symmetry_deg == pytest.approx(180.0)
               for o in factor.goal.objects)
    assert any("is one number" in w for w in imported.warnings)

