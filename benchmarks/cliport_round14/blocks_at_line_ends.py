import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils

import pybullet as p


class BlocksAtLineEnds(Task):
    """Place a red block at one end of the line and a blue block at the other end."""

    def __init__(self):
        super().__init__()
        self.max_steps = 3
        self.lang_template = "put the red and blue blocks at the two ends of the line"
        self.task_completed_desc = "done placing blocks at the line ends."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        line_length = 0.25
        line_urdf = self.fill_template('line/single-green-line-template.urdf',
                                       {'DIM': (line_length,), 'HALF': (line_length / 2,)})
        line_pos, _ = self.get_random_pose(env, (line_length, 0.05, 0.01))
        line_rot = p.getQuaternionFromEuler((0, 0, np.pi / 2))
        line_pose = (line_pos, line_rot)
        env.add_object(line_urdf, line_pose, 'fixed')

        block_size = (0.04, 0.04, 0.04)
        red = env.add_object('block/block.urdf', self.get_random_pose(env, block_size), color=utils.COLORS['red'])
        blue = env.add_object('block/block.urdf', self.get_random_pose(env, block_size), color=utils.COLORS['blue'])

        end_a = (utils.apply(line_pose, (-line_length / 2, 0, 0.02)), line_rot)
        end_b = (utils.apply(line_pose, (line_length / 2, 0, 0.02)), line_rot)

        self.add_goal(objs=[red, blue], matches=np.ones((2, 2)), targ_poses=[end_a, end_b], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
