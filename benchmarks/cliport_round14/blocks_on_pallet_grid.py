import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlocksOnPalletGrid(Task):
    """Place four blocks on the pallet in a 2x2 grid."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "place the {color} block on the pallet"
        self.task_completed_desc = "done placing blocks on the pallet."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        pallet_size = (0.3, 0.25, 0.0375)
        pallet_pose = self.get_random_pose(env, pallet_size)
        env.add_object('pallet/pallet.urdf', pallet_pose, 'fixed')

        block_size = (0.04, 0.04, 0.04)
        colors = ['red', 'green', 'blue', 'yellow']
        grid = [(-0.05, -0.05), (-0.05, 0.05), (0.05, -0.05), (0.05, 0.05)]

        for color, (dx, dy) in zip(colors, grid):
            block_pose = self.get_random_pose(env, block_size)
            block_id = env.add_object('block/block.urdf', block_pose, color=utils.COLORS[color])
            targ = (utils.apply(pallet_pose, (dx, dy, 0.04)), pallet_pose[1])
            self.add_goal(objs=[block_id], matches=np.ones((1, 1)), targ_poses=[targ], replace=False,
                          rotations=True, metric='pose', params=None, step_max_reward=1 / 4,
                          language_goal=self.lang_template.format(color=color))
