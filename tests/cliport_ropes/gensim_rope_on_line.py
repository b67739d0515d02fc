"""GenSim style: a rope from ``make_ropes`` laid along a line between two anchors."""

import numpy as np
from cliport.tasks import primitives
from cliport.tasks.task import Task
from cliport.utils import utils


class RopeOnLine(Task):
    """Lay the blue rope along the line."""

    def __init__(self):
        super().__init__()
        self.max_steps = 20
        self.pos_eps = 0.02
        self.primitive = primitives.PickPlace(height=0.02, speed=0.001)
        self.lang_template = "lay the blue rope along the line"
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        length = 0.3
        line_size = (length, 0.01, 0.001)
        line_pose = self.get_random_pose(env, line_size)
        urdf = self.fill_template("line/line-template.urdf", {"DIM": (length,), "HALF": (0.005,)})
        env.add_object(urdf, line_pose, "fixed", color=utils.COLORS["green"])
        a = utils.apply(line_pose, (-length / 2, 0, 0.001))
        b = utils.apply(line_pose, (length / 2, 0, 0.001))
        objects, targets, matches = self.make_ropes(env, corners=(a, b), n_parts=20,
                                                    color_name="blue")
        self.add_goal(objs=objects, matches=matches, targ_poses=targets, replace=False,
                      rotations=False, metric="pose", params=None, step_max_reward=1,
                      language_goal=self.lang_template)
        for _ in range(480):
            import pybullet as p
            p.stepSimulation()
        np.random.rand()
