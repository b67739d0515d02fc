"""Each coloured block to its own slot (identity matches); colours as tuples and names."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class ColorMatchedSlots(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "put each block on the slot of its colour"

    def reset(self, env):
        super().reset(env)
        colors = [utils.COLORS["red"], tuple(utils.COLORS["green"] + [1]), "blue"]
        slot_xs = [0.35, 0.5, 0.65]
        blocks, targs = [], []
        for color, x in zip(colors, slot_xs, strict=True):
            blocks.append(env.add_object("block/block.urdf",
                                         self.get_random_pose(env, (0.04, 0.04, 0.04)),
                                         color=color))
            targs.append(((x, 0.35, 0.02), (0, 0, 0, 1)))
        self.add_goal(objs=blocks, matches=np.eye(3), targ_poses=targs, replace=False,
                      rotations=True, metric="pose", params=None, step_max_reward=1,
                      language_goal=self.lang_template)
