import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class PlusShapeOfBlocksOnPallet(Task):
    """Form a plus sign with five blocks on the pallet: a yellow centre and four blue arms."""

    def __init__(self):
        super().__init__()
        self.max_steps = 7
        self.lang_template = "make a plus shape with the blocks on the pallet"
        self.task_completed_desc = "done making the plus shape."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        pallet_size = (0.3, 0.25, 0.0375)
        pallet_pose = self.get_random_pose(env, pallet_size)
        env.add_object('pallet/pallet.urdf', pallet_pose, 'fixed')

        block_size = (0.04, 0.04, 0.04)
        center = env.add_object('block/block.urdf', self.get_random_pose(env, block_size),
                                color=utils.COLORS['yellow'])
        arms = []
        for _ in range(4):
            arms.append(env.add_object('block/block.urdf', self.get_random_pose(env, block_size),
                                       color=utils.COLORS['blue']))

        z = 0.04
        center_targ = (utils.apply(pallet_pose, (0, 0, z)), pallet_pose[1])
        arm_offsets = [(0.05, 0, z), (-0.05, 0, z), (0, 0.05, z), (0, -0.05, z)]
        arm_targs = [(utils.apply(pallet_pose, o), pallet_pose[1]) for o in arm_offsets]

        self.add_goal(objs=[center], matches=np.ones((1, 1)), targ_poses=[center_targ], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 5,
                      language_goal="put the yellow block in the middle of the pallet")
        self.add_goal(objs=arms, matches=np.ones((4, 4)), targ_poses=arm_targs, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=4 / 5,
                      language_goal="put the blue blocks around the yellow block")
