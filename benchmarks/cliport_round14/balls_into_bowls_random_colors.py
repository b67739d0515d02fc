import random

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BallsIntoBowlsRandomColors(Task):
    """Put each ball into the bowl of its colour; colours are drawn at random."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "place the {color} ball in the {color} bowl"
        self.task_completed_desc = "done placing balls in bowls."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        all_colors = ['red', 'green', 'blue', 'yellow', 'orange', 'purple', 'pink']
        colors = random.sample(all_colors, 3)

        bowl_size = (0.12, 0.12, 0)
        ball_size = (0.04, 0.04, 0.04)
        ball_urdf = self.fill_template('ball/ball-template.urdf', {'DIM': ball_size})

        for color in colors:
            bowl_pose = self.get_random_pose(env, bowl_size)
            env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed', color=utils.COLORS[color])

            ball_pose = self.get_random_pose(env, ball_size)
            ball_id = env.add_object(ball_urdf, ball_pose, color=utils.COLORS[color])

            self.add_goal(objs=[ball_id], matches=np.ones((1, 1)), targ_poses=[bowl_pose],
                          replace=False, rotations=False, metric='pose', params=None,
                          step_max_reward=1 / 3,
                          language_goal=self.lang_template.format(color=color))
