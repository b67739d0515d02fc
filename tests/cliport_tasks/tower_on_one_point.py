"""Ravens-style: build a tower by sending every block to the same point, one goal each.

Ravens ignores target z, so the author gives every goal the same target (the
tower's base point); the blocks stack in the order the goals are queued.
"""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class TowerOnOnePoint(Task):
    """Stack the red, green and blue blocks on the gray marker, red at the bottom."""

    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "put the {color} block on the tower"
        self.task_completed_desc = "done building the tower."

    def reset(self, env):
        super().reset(env)
        base_size = (0.05, 0.05, 0.005)
        base_pose = self.get_random_pose(env, base_size)
        env.add_object("stacking/stand.urdf", base_pose, "fixed")
        target = (utils.apply(base_pose, (0, 0, 0.02)), base_pose[1])
        for color in ("red", "green", "blue"):
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            block = env.add_object("block/block.urdf", pose, color=utils.COLORS[color])
            self.goals.append(([(block, (np.pi / 2, None))], np.int32([[1]]), [target],
                               False, True, "pose", None, 1 / 3))
            self.lang_goals.append(self.lang_template.format(color=color))
