"""Which class of a task file is the task, and task code probing the recording env
(``hasattr(env, ...)``): the habits of task files written in GenSim's style."""

from __future__ import annotations

from pathlib import Path

import pytest

from factask.compat.cliport import import_cliport
from factask.compat.cliport.errors import CliportImportError, NoGoals, Unsupported

TASKS = Path(__file__).parent / "cliport_tasks"

_HEAD = """
import numpy as np
from cliport.tasks.task import Task


class Base(Task):
    def reset(self, env):
        super().reset(env)
        self.block = env.add_object("block/block.urdf", self.get_random_pose(env, 0.04))
"""

_CHILD = """

class {name}(Base):
    def reset(self, env):
        super().reset(env)
        targ = self.get_random_pose(env, 0.04)
        self.add_goal(objs=[self.block], matches=np.ones((1, 1)), targ_poses=[targ],
                      replace=False, rotations=True, metric="pose", params=None,
                      step_max_reward=1)
"""


def test_a_base_without_goals_gives_way_to_the_one_class_derived_from_it() -> None:
    result = import_cliport(TASKS / "base_class_without_goals.py")
    assert result.class_name == "BlocksOnPalletInARow"
    assert "queues no goals" in result.warnings[0]
    assert len(result.graph.factors) == 1


def test_a_base_with_two_unrelated_derived_classes_stays_an_error(tmp_path: Path) -> None:
    path = tmp_path / "two_children.py"
    path.write_text(_HEAD + _CHILD.format(name="Left") + _CHILD.format(name="Right"))
    with pytest.raises(NoGoals, match="Base: reset added no goals"):
        import_cliport(path)
    assert import_cliport(path, "Left").class_name == "Left"  # a class named still works


def test_a_base_named_explicitly_is_not_replaced(tmp_path: Path) -> None:
    path = tmp_path / "chain.py"
    path.write_text(_HEAD + _CHILD.format(name="Child"))
    assert import_cliport(path).class_name == "Child"
    with pytest.raises(NoGoals):
        import_cliport(path, "Base")


def test_hasattr_on_the_env_is_false_and_leaves_a_warning() -> None:
    result = import_cliport(TASKS / "env_probed_with_hasattr.py")
    assert any("env.set_object_pose is not available" in w for w in result.warnings)


def test_using_a_missing_env_method_is_still_refused_by_name(tmp_path: Path) -> None:
    path = tmp_path / "renders.py"
    path.write_text(_HEAD.replace('self.get_random_pose(env, 0.04))',
                                  'self.get_random_pose(env, 0.04))\n'
                                  '        env.render_camera(None)'))
    with pytest.raises(Unsupported, match=r"env\.render_camera is not available"):
        import_cliport(path)
    assert issubclass(NoGoals, CliportImportError)
