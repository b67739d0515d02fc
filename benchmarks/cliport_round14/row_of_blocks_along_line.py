import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class RowOfBlocksAlongLine(Task):
    """Arrange four blocks in a straight row on top of a green line."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "arrange the blocks in a row along the green line"
        self.task_completed_desc = "done arranging blocks in a row."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        # Add the line.
        line_size = (0.3, 0.01, 0.01)
        line_pose = self.get_random_pose(env, line_size)
        line_template = 'line/single-green-line-template.urdf'
        replace = {'DIM': (0.3,), 'HALF': (0.15,)}
        line_urdf = self.fill_template(line_template, replace)
        env.add_object(line_urdf, line_pose, 'fixed')

        # Add blocks.
        block_size = (0.04, 0.04, 0.04)
        colors = ['red', 'green', 'blue', 'yellow']
        blocks = []
        for color in colors:
            block_pose = self.get_random_pose(env, block_size)
            blocks.append(env.add_object('block/block.urdf', block_pose, color=utils.COLORS[color]))

        # Target positions along the line.
        spacing = 0.035
        targ_poses = []
        for i in range(len(blocks)):
            offset = ((i - 1.5) * spacing, 0, 0.02)
            targ_poses.append((utils.apply(line_pose, offset), line_pose[1]))

        self.add_goal(objs=blocks, matches=np.ones((4, 4)), targ_poses=targ_poses, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
