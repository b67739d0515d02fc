import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class ReverseTowerOnStand(Task):
    """A tower stands on the left plate of the stand; rebuild it upside down on the right plate."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "move the {color} block to the right side of the stand"
        self.task_completed_desc = "done reversing the tower."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        stand_size = (0.05, 0.15, 0.005)
        stand_pose = self.get_random_pose(env, stand_size)
        env.add_object('stacking/stand.urdf', stand_pose, 'fixed')

        # Initial tower on the left plate: red at the bottom, blue on top.
        colors = ['red', 'green', 'blue']
        blocks = []
        for i, color in enumerate(colors):
            pose = (utils.apply(stand_pose, (0, -0.05, 0.025 + 0.04 * i)), stand_pose[1])
            blocks.append(env.add_object('stacking/block.urdf', pose, color=utils.COLORS[color]))

        # Move the top block first, so the tower ends up reversed.
        for i, block_id in enumerate(reversed(blocks)):
            targ = (utils.apply(stand_pose, (0, 0.05, 0.03 + 0.04 * i)), stand_pose[1])
            self.add_goal(objs=[block_id], matches=np.ones((1, 1)), targ_poses=[targ], replace=False,
                          rotations=True, metric='pose', params=None, step_max_reward=1 / 3,
                          language_goal=self.lang_template.format(color=colors[2 - i]))
