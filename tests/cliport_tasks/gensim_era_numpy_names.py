"""Code written for GenSim's stack (Python 3.8, NumPy before 1.24): ``np.int``,
``np.float``, ``np.product`` and ``random.sample`` of a dict's keys all worked there.

factask runs on NumPy 2 and Python 3.11, which removed them; the loader lends them
while the file runs (factask.compat.cliport.legacy). Before, the reset failed with
``AttributeError: module 'numpy' has no attribute 'int'``.
"""

import random

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class GensimEraNumpyNames(Task):
    """Stack blocks of randomly drawn colours on the pallet, the largest count first."""

    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "stack the {} block on the pallet"
        self.task_completed_desc = "done stacking."

    def reset(self, env):
        super().reset(env)
        n_blocks = np.int(np.random.randint(2, 4))
        block_size = np.array([0.04, 0.04, 0.04], dtype=np.float)
        color_names = random.sample(utils.COLORS.keys(), n_blocks)
        pallet_size = (0.3, 0.25, 0.0375)
        assert np.product(pallet_size) > 0
        pallet_pose = self.get_random_pose(env, pallet_size)
        env.add_object('pallet/pallet.urdf', pallet_pose, 'fixed')
        for i, name in enumerate(color_names):
            block = env.add_object('block/block.urdf', self.get_random_pose(env, block_size),
                                   color=utils.COLORS[name])
            z = np.float(pallet_size[2] / 2 + block_size[2] / 2 + i * block_size[2])
            targ = (utils.apply(pallet_pose, (0, 0, z)), pallet_pose[1])
            self.add_goal(objs=[block], matches=np.ones((1, 1)), targ_poses=[targ], replace=False,
                          rotations=True, metric='pose', params=None, step_max_reward=1 / n_blocks,
                          language_goal=self.lang_template.format(name))
