import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class ColorSortedBlocksInBowls(Task):
    """Place each coloured block into the bowl of the same colour."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "put the {color} block in the {color} bowl"
        self.task_completed_desc = "done sorting blocks into bowls."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        colors = ['red', 'blue', 'yellow']
        bowl_size = (0.12, 0.12, 0)
        block_size = (0.04, 0.04, 0.04)

        bowl_poses = []
        for color in colors:
            bowl_pose = self.get_random_pose(env, bowl_size)
            env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed', color=utils.COLORS[color])
            bowl_poses.append(bowl_pose)

        blocks = []
        for color in colors:
            block_pose = self.get_random_pose(env, block_size)
            block_id = env.add_object('block/block.urdf', block_pose, color=utils.COLORS[color])
            blocks.append(block_id)

        # One goal per colour.
        for i, color in enumerate(colors):
            self.add_goal(objs=[blocks[i]], matches=np.ones((1, 1)), targ_poses=[bowl_poses[i]],
                          replace=False, rotations=True, metric='pose', params=None,
                          step_max_reward=1 / len(colors),
                          language_goal=self.lang_template.format(color=color))
