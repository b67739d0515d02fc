"""A packing plan whose boxes are added at their planned poses and never moved out
(Ravens' packing tasks move them to random spots afterwards; this file forgets):
the goal would be met before any action. factask starts them at random free
spots (was refused: 'met at the start')."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class PackPlannedBoxesInPlace(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "pack the boxes into the container"

    def reset(self, env):
        super().reset(env)
        zone_size = (0.2, 0.14, 0.05)
        zone_pose = self.get_random_pose(env, zone_size)
        urdf = self.fill_template("container/container-template.urdf",
                                  {"DIM": zone_size, "HALF": np.float32(zone_size) / 2})
        env.add_object(urdf, zone_pose, "fixed")
        box_size = (0.06, 0.06, 0.04)
        boxes, targs = [], []
        for k, dx in enumerate((-0.05, 0.05)):
            pose = utils.multiply(zone_pose, ((dx, 0, 0.02), (0, 0, 0, 1)))
            box_urdf = self.fill_template("box/box-template.urdf", {"DIM": box_size})
            boxes.append(env.add_object(box_urdf, pose, color=utils.COLORS[["red", "blue"][k]]))
            targs.append(pose)
        self.add_goal(objs=boxes, matches=np.eye(2), targ_poses=targs, replace=False,
                      rotations=True, metric="zone", params=[(zone_pose, zone_size)],
                      step_max_reward=1, language_goal=self.lang_template)
