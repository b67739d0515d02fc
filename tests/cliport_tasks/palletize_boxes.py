"""Boxes stacked on a fixed pallet (targets with z via utils.apply); rewards sum to 1.5."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class PalletizeBoxes(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "stack the boxes on the pallet"

    def reset(self, env):
        super().reset(env)
        pallet_pose = ((0.5, 0.3, 0.01875), (0, 0, 0, 1))
        env.add_object("pallet/pallet.urdf", pallet_pose, "fixed")
        size = (0.06, 0.06, 0.06)
        urdf = self.fill_template("box/box-template.urdf", {"DIM": size})
        boxes, targs = [], []
        for i in range(3):
            boxes.append(env.add_object(urdf, self.get_random_pose(env, size), color="brown"))
            offset = (0.0, 0.07 * (i - 1), 0.0375 + size[2] / 2)
            targs.append((utils.apply(pallet_pose, offset), pallet_pose[1]))
        top_urdf = self.fill_template("box/box-template.urdf", {"DIM": size})
        top = env.add_object(top_urdf, self.get_random_pose(env, size), color="white")
        top_target = (utils.apply(pallet_pose, (0, 0, 0.0375 + 1.5 * size[2])), pallet_pose[1])
        self.add_goal(objs=boxes, matches=np.ones((3, 3)), targ_poses=targs, replace=False,
                      rotations=True, metric="pose", params=None, step_max_reward=1,
                      language_goal="put the brown boxes on the pallet")
        self.add_goal(objs=[top], matches=np.ones((1, 1)), targ_poses=[top_target],
                      replace=False, rotations=True, metric="pose", params=None,
                      step_max_reward=0.5, language_goal="put the white box on top")
