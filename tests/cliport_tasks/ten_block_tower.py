"""Ten blocks stacked into one tower, 40 cm tall: was refused ('height 0.404752 is
outside the workspace z (0.0, 0.3)'); the workspace's height is what the arm reaches.
Written in the style of GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class TenBlockTower(Task):
    """Stack ten blocks into one tower on the base."""

    def __init__(self):
        super().__init__()
        self.max_steps = 20
        self.lang_template = "stack all ten blocks into one tall tower"
        self.task_completed_desc = "done stacking the tower."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        base_size = (0.05, 0.15, 0.005)
        base_pose = self.get_random_pose(env, base_size)
        env.add_object('stacking/stand.urdf', base_pose, 'fixed')
        block_size = (0.04, 0.04, 0.04)
        colors = [utils.COLORS[c] for c in utils.COLORS_NAMES[:10]]
        blocks = [env.add_object('stacking/block.urdf', self.get_random_pose(env, block_size),
                                 color=colors[i]) for i in range(10)]
        targets = [(utils.apply(base_pose, (0, 0, 0.025 + i * 0.04)), base_pose[1])
                   for i in range(10)]
        self.add_goal(objs=blocks, matches=np.eye(10), targ_poses=targets, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
