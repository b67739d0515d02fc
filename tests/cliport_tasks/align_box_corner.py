"""Align a box with a fixed corner marker (symmetry pi, a fixed object)."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class AlignBoxCorner(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 3
        self.lang_template = "align the box with the corner"

    def reset(self, env):
        super().reset(env)
        box_size = self.get_random_size(0.05, 0.15, 0.05, 0.15, 0.01, 0.06)
        corner_pose = ((0.62, -0.18, 0.0), utils.eulerXYZ_to_quatXYZW((0, 0, np.pi / 2)))
        replace = {"DIMX": (box_size[0] / 2, 0), "DIMY": (0, box_size[1] / 2)}
        corner_urdf = self.fill_template("corner/corner-template.urdf", replace)
        env.add_object(corner_urdf, corner_pose, "fixed")
        box_urdf = self.fill_template("box/box-template.urdf", {"DIM": box_size})
        box = env.add_object(box_urdf, self.get_random_pose(env, box_size))
        target = ((0.62, -0.18, box_size[2] / 2), corner_pose[1])
        self.add_goal(objs=[box], matches=np.int32([[1]]), targ_poses=[target], replace=False,
                      rotations=True, metric="pose", params=None, step_max_reward=1,
                      symmetries=[np.pi], language_goal=self.lang_template)
