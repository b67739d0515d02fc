"""Balls into a zone that is only given in the goal params (no zone object added)."""

import numpy as np
import pybullet as p
from cliport.tasks.task import Task
from cliport.utils import utils


class BallsIntoZone(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "put the balls in the target area"

    def reset(self, env):
        super().reset(env)
        size = (0.04, 0.04, 0.04)
        urdf = self.fill_template("ball/ball-template.urdf", {"DIM": size})
        balls = []
        for _ in range(2):
            ball = env.add_object(urdf, self.get_random_pose(env, size))
            p.changeVisualShape(ball, -1, rgbaColor=utils.COLORS["purple"] + [1])
            balls.append(ball)
        quat = p.getQuaternionFromEuler((0, 0, 0.3))
        zone_pose = ((0.4, 0.3, 0.0), quat)
        pos, _ = p.getBasePositionAndOrientation(balls[0])
        assert len(pos) == 3
        self.add_goal(objs=balls, matches=np.ones((2, 1)), targ_poses=[zone_pose], replace=True,
                      rotations=False, metric="zone", params=[(zone_pose, (0.15, 0.1, 0))],
                      step_max_reward=1, language_goal=self.lang_template)
