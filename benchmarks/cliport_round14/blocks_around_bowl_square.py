import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlocksAroundBowlSquare(Task):
    """Place four blocks around a bowl, one on each side, forming a square."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "place the blocks around the bowl"
        self.task_completed_desc = "done placing blocks around the bowl."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        bowl_size = (0.12, 0.12, 0)
        bowl_pose = self.get_random_pose(env, (0.3, 0.3, 0))
        env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed')

        block_size = (0.04, 0.04, 0.04)
        colors = ['red', 'blue', 'green', 'yellow']
        blocks = []
        for color in colors:
            block_pose = self.get_random_pose(env, block_size)
            blocks.append(env.add_object('block/block.urdf', block_pose, color=utils.COLORS[color]))

        offsets = [(0.1, 0, 0.02), (-0.1, 0, 0.02), (0, 0.1, 0.02), (0, -0.1, 0.02)]
        targ_poses = [(utils.apply(bowl_pose, o), bowl_pose[1]) for o in offsets]

        self.add_goal(objs=blocks, matches=np.ones((4, 4)), targ_poses=targ_poses, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
