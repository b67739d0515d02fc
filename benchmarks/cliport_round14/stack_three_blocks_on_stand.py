import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class StackThreeBlocksOnStand(Task):
    """Stack a red, a green and a blue block on the middle plate of the stand, red at the bottom."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "stack the {color} block on the stand"
        self.task_completed_desc = "done stacking blocks on the stand."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        # Add the stand.
        stand_size = (0.05, 0.15, 0.005)
        stand_pose = self.get_random_pose(env, stand_size)
        env.add_object('stacking/stand.urdf', stand_pose, 'fixed')

        # Add blocks.
        block_size = (0.04, 0.04, 0.04)
        block_urdf = 'stacking/block.urdf'
        colors = ['red', 'green', 'blue']
        blocks = []
        for color in colors:
            block_pose = self.get_random_pose(env, block_size)
            block_id = env.add_object(block_urdf, block_pose, color=utils.COLORS[color])
            blocks.append(block_id)

        # Goal: stack the blocks in order, one at a time.
        for i, block_id in enumerate(blocks):
            targ_pos = utils.apply(stand_pose, (0, 0, 0.03 + i * 0.04))
            self.add_goal(objs=[block_id], matches=np.ones((1, 1)), targ_poses=[(targ_pos, stand_pose[1])],
                          replace=False, rotations=True, metric='pose', params=None,
                          step_max_reward=1 / 3,
                          language_goal=self.lang_template.format(color=colors[i]))
