"""Ravens' block-insertion: an ell into its fixed fixture (asymmetric, 2*pi)."""

import numpy as np
import pybullet as p
from cliport.tasks.task import Task


class BlockInsertion(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 3
        self.lang_template = "put the L shaped block in the L shaped hole"

    def reset(self, env):
        super().reset(env)
        size = (0.1, 0.1, 0.04)
        pose = self.get_random_pose(env, size)
        block = env.add_object("insertion/ell.urdf", pose)
        targ_pose = ((0.55, -0.25, 0.02), p.getQuaternionFromEuler((0, 0, np.pi / 4)))
        env.add_object("insertion/fixture.urdf", targ_pose, "fixed")
        self.add_goal(objs=[(block, (2 * np.pi, None))], matches=np.int32([[1]]),
                      targ_poses=[targ_pose], replace=False, rotations=True, metric="pose",
                      params=None, step_max_reward=1, language_goal=self.lang_template)
