"""Put each yellow block into a gray bowl (N blocks, M >= N bowls, any match)."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class PutBlockInBowl(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "put the yellow blocks in a bowl"
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        bowl_size = (0.12, 0.12, 0)
        bowl_poses = []
        for _ in range(3):
            pose = self.get_random_pose(env, bowl_size)
            env.add_object("bowl/bowl.urdf", pose, "fixed")
            bowl_poses.append(pose)
        blocks = []
        for _ in range(2):
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            blocks.append(env.add_object("block/block.urdf", pose, color=utils.COLORS["yellow"]))
        self.add_goal(objs=blocks, matches=np.ones((2, 3)), targ_poses=bowl_poses, replace=False,
                      rotations=True, metric="pose", params=None, step_max_reward=1,
                      language_goal=self.lang_template)
