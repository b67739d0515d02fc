"""Stack three blue boxes into a column (the brief's example, unchanged)."""
# ruff: noqa: UP031 - kept exactly as the CLIPort-style example was written

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class StackBoxesColumn(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 15
        self.lang_template = "stack the boxes into a column"
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        size = (0.07, 0.07, 0.07)
        base = ((0.5, 0.0, 0.035), (0, 0, 0, 1))
        ids = []
        for _ in range(3):
            ids.append(env.add_object("box/box-template.urdf", self.get_random_pose(env, size),
                                      color=utils.COLORS["blue"]))
        for i, obj in enumerate(ids):
            target = (utils.apply(base, (0, 0, i * size[2])), base[1])
            self.add_goal(objs=[obj], matches=np.ones((1, 1)), targ_poses=[target],
                          replace=False, rotations=True, metric="pose", params=None,
                          step_max_reward=1 / 3, language_goal="stack box %d" % i)
