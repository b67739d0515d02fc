import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BowlsRowOneBlockEach(Task):
    """Three bowls sit in a row; put one block in each bowl."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "put one block in each bowl"
        self.task_completed_desc = "done filling the bowls."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        row_size = (0.4, 0.14, 0)
        row_pose = self.get_random_pose(env, row_size)

        bowl_poses = []
        for x in [-0.13, 0, 0.13]:
            bowl_pose = (utils.apply(row_pose, (x, 0, 0)), row_pose[1])
            env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed')
            bowl_poses.append(bowl_pose)

        block_size = (0.04, 0.04, 0.04)
        blocks = []
        for color in ['orange', 'pink', 'cyan']:
            pose = self.get_random_pose(env, block_size)
            blocks.append(env.add_object('block/block.urdf', pose, color=utils.COLORS[color]))

        self.add_goal(objs=blocks, matches=np.ones((3, 3)), targ_poses=bowl_poses, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
