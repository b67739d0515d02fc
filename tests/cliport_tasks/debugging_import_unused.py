"""A task file that starts with a debugging import it never uses (`import IPython`), as
generated files often do: runs with a stand-in (was a ModuleNotFoundError where IPython
is not installed). Written in the style of GenSim's generated tasks."""

import IPython  # noqa: F401  (unused: the point of this file)
import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class DebuggingImportUnused(Task):
    """Put the yellow block in the green bowl."""

    def __init__(self):
        super().__init__()
        self.max_steps = 3
        self.lang_template = "put the yellow block in the green bowl"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        bowl_pose = self.get_random_pose(env, (0.12, 0.12, 0))
        env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed', color=utils.COLORS['green'])
        block = env.add_object('stacking/block.urdf',
                               self.get_random_pose(env, (0.04, 0.04, 0.04)),
                               color=utils.COLORS['yellow'])
        self.add_goal(objs=[block], matches=np.ones((1, 1)), targ_poses=[bowl_pose],
                      replace=False, rotations=False, metric='pose', params=None,
                      step_max_reward=1, language_goal=self.lang_template)
