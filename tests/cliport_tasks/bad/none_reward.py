"""A task that passes step_max_reward=None (fails while the graph is built)."""

import numpy as np
from cliport.tasks.task import Task


class NoneReward(Task):
    def reset(self, env):
        super().reset(env)
        size = (0.04, 0.04, 0.04)
        block = env.add_object("block/block.urdf", self.get_random_pose(env, size))
        target = ((0.5, 0.1, 0.02), (0, 0, 0, 1))
        self.add_goal(objs=[block], matches=np.ones((1, 1)), targ_poses=[target],
                      replace=False, rotations=True, metric="pose", params=None,
                      step_max_reward=None, language_goal="place the block")
