import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlocksOnStandPlatesColorOrder(Task):
    """Put the red, green and blue blocks on the three plates of the stand, in that order."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "put the red, green and blue blocks on the stand in order"
        self.task_completed_desc = "done ordering blocks on the stand."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        stand_size = (0.05, 0.15, 0.005)
        stand_pose = self.get_random_pose(env, stand_size)
        env.add_object('stacking/stand.urdf', stand_pose, 'fixed')

        colors = ['red', 'green', 'blue']
        block_size = (0.04, 0.04, 0.04)
        blocks = []
        for color in colors:
            block_pose = self.get_random_pose(env, block_size)
            blocks.append(env.add_object('stacking/block.urdf', block_pose, color=utils.COLORS[color]))

        place_pos = [(0, -0.05, 0.03), (0, 0, 0.03), (0, 0.05, 0.03)]
        targs = [(utils.apply(stand_pose, i), stand_pose[1]) for i in place_pos]

        self.add_goal(objs=blocks, matches=np.eye(3), targ_poses=targs, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      symmetries=[np.pi / 2] * 3, language_goal=self.lang_template)
