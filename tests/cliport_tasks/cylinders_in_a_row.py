"""Cylinders in a row with rotations=False; a language goal given as a list."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class CylindersInARow(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "line up the cylinders"

    def reset(self, env):
        super().reset(env)
        size = (0.04, 0.04, 0.08)
        urdf = self.fill_template("cylinder/cylinder-template.urdf", {"DIM": size})
        cylinders = [env.add_object(urdf, self.get_random_pose(env, size), color=c)
                     for c in ("cyan", "pink")]
        targs = [((0.4 + 0.06 * i, -0.35, size[2] / 2), (0, 0, 0, 1)) for i in range(2)]
        self.add_goal(objs=cylinders, matches=np.ones((2, 2)), targ_poses=targs, replace=False,
                      rotations=False, metric="pose", params=None, step_max_reward=1,
                      language_goal=["line up the cylinders", "left to right"])
        assert utils.TRAIN_COLORS
