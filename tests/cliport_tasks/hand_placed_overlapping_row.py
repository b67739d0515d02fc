"""Blocks an author puts in a row by hand, 3.5 cm apart for 4 cm blocks (PyBullet
pushes them apart at its first step): factask starts them touching, each a few mm off
(was refused at reset: 'its fixed pose overlaps'). Written here in the style of
GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class SortHandPlacedBlocks(Task):
    """Blocks start in a hand-placed row; put each into the bowl of its colour."""

    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "put the {} block in the {} bowl"
        self.task_completed_desc = "done sorting."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        names = ['red', 'green', 'blue']
        bowl_poses = []
        for name in names:
            bowl_pose = self.get_random_pose(env, (0.12, 0.12, 0))
            env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed', color=utils.COLORS[name])
            bowl_poses.append(bowl_pose)
        blocks = []
        for i, name in enumerate(names):
            pose = ((0.3, -0.035 + 0.035 * i, 0.02), (0, 0, 0, 1))
            blocks.append(env.add_object('block/block.urdf', pose, color=utils.COLORS[name]))
        for i in range(3):
            self.add_goal(objs=[blocks[i]], matches=np.ones((1, 1)), targ_poses=[bowl_poses[i]],
                          replace=False, rotations=False, metric='pose', params=None,
                          step_max_reward=1 / 3,
                          language_goal=self.lang_template.format(names[i], names[i]))
