"""A file with a base task that only sets the scene up and a task derived from it
whose reset calls super().reset(env), adds a block and queues the goal: the
derived class is the task (was: the base picked, 'reset added no goals')."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils

BLOCK_SIZE = (0.04, 0.04, 0.04)


class BlocksOnPalletBase(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "put the blocks on the pallet"

    def reset(self, env):
        super().reset(env)
        self.pallet_pose = self.get_random_pose(env, (0.3, 0.25, 0.0375))
        env.add_object("pallet/pallet.urdf", self.pallet_pose, "fixed")
        self.blocks = []
        for _ in range(2):
            pose = self.get_random_pose(env, BLOCK_SIZE)
            self.blocks.append(env.add_object("block/block.urdf", pose,
                                              color=utils.COLORS["red"]))


class BlocksOnPalletInARow(BlocksOnPalletBase):
    def reset(self, env):
        super().reset(env)
        pose = self.get_random_pose(env, BLOCK_SIZE)
        self.blocks.append(env.add_object("block/block.urdf", pose, color=utils.COLORS["blue"]))
        offsets = [(0, -0.06, 0.04), (0, 0, 0.04), (0, 0.06, 0.04)]
        targs = [(utils.apply(self.pallet_pose, o), self.pallet_pose[1]) for o in offsets]
        self.add_goal(objs=self.blocks, matches=np.eye(3), targ_poses=targs, replace=False,
                      rotations=True, metric="pose", params=None, step_max_reward=1,
                      language_goal="put the blocks on the pallet in a row")
