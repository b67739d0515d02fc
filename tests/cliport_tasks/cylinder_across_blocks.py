"""Two blocks in a row with a gap, and a cylinder laid across them on its side
(its targets turned by pi / 2 about x, as an author writes "horizontally"). The
cylinder was made to stand upright at its target -- in the gap between the
blocks, another task -- with a warning; now it is a ``log`` lying across them.
Written here in the style of GenSim's generated tasks."""

import numpy as np
import pybullet as p
from cliport.tasks.task import Task
from cliport.utils import utils


class CylinderAcrossBlocks(Task):
    """Place two red blocks parallel with a gap and balance the green cylinder
    horizontally on top of them."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "balance the green cylinder horizontally on the red blocks"
        self.task_completed_desc = "done balancing the cylinder."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        block_size = (0.04, 0.04, 0.04)
        block_urdf = 'block/block.urdf'
        base_pose = ((0.5, 0.0, 0.02), (0, 0, 0, 1))
        blocks = []
        for _ in range(2):
            pose = self.get_random_pose(env, block_size)
            blocks.append(env.add_object(block_urdf, pose, color=utils.COLORS['red']))
        gap = 0.04
        offsets = [(0, -(block_size[1] + gap) / 2, 0), (0, (block_size[1] + gap) / 2, 0)]
        block_targets = [(utils.apply(base_pose, o), base_pose[1]) for o in offsets]
        self.add_goal(objs=blocks, matches=np.ones((2, 2)), targ_poses=block_targets,
                      replace=False, rotations=True, metric='pose', params=None,
                      step_max_reward=2 / 3, language_goal="place the red blocks with a gap")

        radius, length = 0.02, 0.14
        cylinder_size = (2 * radius, 2 * radius, length)
        cylinder_urdf = self.fill_template('cylinder/cylinder-template.urdf',
                                           {'DIM': cylinder_size})
        lying = p.getQuaternionFromEuler((np.pi / 2, 0, 0))  # its axis along y
        pose = self.get_random_pose(env, (length, 2 * radius, 2 * radius))
        cylinder = env.add_object(cylinder_urdf, (pose[0], lying), color=utils.COLORS['green'])
        top = (base_pose[0][0], base_pose[0][1], block_size[2] + radius)
        self.add_goal(objs=[cylinder], matches=np.ones((1, 1)), targ_poses=[(top, lying)],
                      replace=False, rotations=True, metric='pose', params=None,
                      step_max_reward=1 / 3, language_goal=self.lang_template)
