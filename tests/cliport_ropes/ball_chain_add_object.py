"""Beads added with add_object (ball template) and linked by constraints."""

import numpy as np
import pybullet as p
from cliport.tasks.task import Task
from cliport.utils import utils


class BallChain(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 20
        self.pos_eps = 0.02
        self.lang_template = "lay the ball chain along the line"

    def reset(self, env):
        super().reset(env)
        n, d = 12, 0.015
        start, _ = self.get_random_pose(env, (0.1, 0.1, 0.1))
        urdf = self.fill_template("ball/ball-template.urdf", {"DIM": (0.012, 0.012, 0.012)})
        ids = []
        for i in range(n):
            ids.append(env.add_object(urdf, ((start[0] + i * d, start[1], 0.006), (0, 0, 0, 1)),
                                      color=utils.COLORS["blue"]))
            if i:
                p.createConstraint(ids[i - 1], -1, ids[i], -1, p.JOINT_POINT2POINT, (0, 0, 0),
                                   (d, 0, 0), (0, 0, 0))
        targets = [((0.4 + i * d, -0.2, 0.006), (0, 0, 0, 1)) for i in range(n)]
        self.add_goal(objs=[(b, (0, None)) for b in ids], matches=np.eye(n) + np.eye(n)[::-1],
                      targ_poses=targets, replace=False, rotations=False, metric="pose",
                      params=None, step_max_reward=1, language_goal=self.lang_template)
