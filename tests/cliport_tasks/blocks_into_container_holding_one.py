"""A container already holds a block the author put in at a height of its own; two more
blocks go in, one goal each, both targets the container's pose, two actions allowed
(Ravens' budget: one per goal). Was 0.5 at 'action budget of 2 used up': the targets
were measured from the author's height of the block inside, so the second block was
'1.5 cm below its target height' and the oracle placed it again. Written in the style
of GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlockIntoContainerHoldingOne(Task):
    """A container already holds a gray block at its centre; put the red and blue
    blocks into it, targets at the container's pose."""

    def __init__(self):
        super().__init__()
        self.max_steps = 2
        self.lang_template = "put the {color} block in the container"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        size = (0.15, 0.15, 0.05)
        pose = self.get_random_pose(env, size)
        urdf = self.fill_template('container/container-template.urdf',
                                  {'DIM': size, 'HALF': (0.075, 0.075, 0.025)})
        env.add_object(urdf, pose, 'fixed')
        env.add_object('block/block.urdf', (utils.apply(pose, (0, 0, 0.02)), pose[1]),
                       color=utils.COLORS['gray'])
        for color in ['red', 'blue']:
            block = env.add_object('block/block.urdf',
                                   self.get_random_pose(env, (0.04, 0.04, 0.04)),
                                   color=utils.COLORS[color])
            self.add_goal(objs=[block], matches=np.ones((1, 1)), targ_poses=[pose],
                          replace=False, rotations=True, metric='pose', params=None,
                          step_max_reward=1 / 2,
                          language_goal=self.lang_template.format(color=color))
