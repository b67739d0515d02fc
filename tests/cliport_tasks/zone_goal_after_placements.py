"""One pose goal per block into a container, then a zone goal "all blocks are in the
container" with no reward of its own: the zone goal keeps the places the earlier goals
gave (Ravens finds it met when it reaches it); was refused at reset: the packer found
the container full of those very blocks. Written here in the style of GenSim's
generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class ColorSequencedBlockInContainer(Task):
    """Put the blocks into the container one by one, then check they all are in it."""

    def __init__(self):
        super().__init__()
        self.max_steps = 12
        self.lang_template = "put the {} block in the container"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        size = (0.15, 0.15, 0.05)
        cpose = self.get_random_pose(env, size)
        urdf = self.fill_template('container/container-template.urdf',
                                  {'DIM': size, 'HALF': (0.075, 0.075, 0.025)})
        env.add_object(urdf, cpose, 'fixed')
        names = ['red', 'blue', 'green', 'yellow']
        blocks = []
        for name in names:
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            blocks.append(env.add_object('block/block.urdf', pose, color=utils.COLORS[name]))
        offsets = [(-0.035, -0.035, 0.02), (0.035, -0.035, 0.02), (-0.035, 0.035, 0.02),
                   (0.035, 0.035, 0.02)]
        for i in range(4):
            targ = (utils.apply(cpose, offsets[i]), cpose[1])
            self.add_goal(objs=[blocks[i]], matches=np.ones((1, 1)), targ_poses=[targ],
                          replace=False, rotations=False, metric='pose', params=None,
                          step_max_reward=1 / 4, language_goal=self.lang_template.format(names[i]))
        self.add_goal(objs=blocks, matches=np.ones((4, 1)), targ_poses=[cpose], replace=True,
                      rotations=False, metric='zone', params=[(cpose, size)], step_max_reward=0,
                      language_goal="all blocks are in the container")
