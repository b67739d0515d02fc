"""GenSim habits: re-filling a filled template in a loop, one long language goal for
every goal, and a matches matrix with fewer columns than targets."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class RefillTemplateInLoop(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 8
        self.lang_template = ("sort the blocks according to color into three zones "
                              "and then stack them carefully")

    def reset(self, env):
        super().reset(env)
        ball_urdf = "ball/ball-template.urdf"
        balls = []
        for color in ("red", "blue"):
            ball_urdf = self.fill_template(ball_urdf, {"DIM": (0.04, 0.04, 0.04),
                                                       "COLOR": utils.COLORS[color]})
            balls.append(env.add_object(ball_urdf, self.get_random_pose(env, (0.04,) * 3)))
        targs = [((0.4 + 0.1 * i, -0.3, 0.02), (0, 0, 0, 1)) for i in range(4)]
        for i, ball in enumerate(balls):
            self.add_goal(objs=[ball], matches=np.ones((1, 2)), targ_poses=targs[2 * i:2 * i + 2]
                          + targs[:2], replace=False, rotations=False, metric="pose",
                          params=None, step_max_reward=1 / 2, language_goal=self.lang_template)
