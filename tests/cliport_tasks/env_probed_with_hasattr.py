"""Task code that probes the env for a method before using it
(``hasattr(env, 'set_object_pose')``, ``getattr(env, ..., None)``): on an env
without it the file takes its own fallback (was: factask's refusal escaped
hasattr and the reset failed)."""

import numpy as np
import pybullet as p
from cliport.tasks.task import Task
from cliport.utils import utils


class MoveBoxesOffThenBack(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "put the boxes back into the container"

    def reset(self, env):
        super().reset(env)
        zone_size = (0.2, 0.2, 0.05)
        zone_pose = self.get_random_pose(env, zone_size)
        urdf = self.fill_template("container/container-template.urdf",
                                  {"DIM": zone_size, "HALF": (0.1, 0.1, 0.025)})
        env.add_object(urdf, zone_pose, "fixed")
        box_size = (0.06, 0.06, 0.04)
        targs, boxes = [], []
        for dx in (-0.05, 0.05):
            targ = utils.multiply(zone_pose, ((dx, 0, 0.02), (0, 0, 0, 1)))
            box_urdf = self.fill_template("box/box-template.urdf", {"DIM": box_size})
            boxes.append(env.add_object(box_urdf, targ, color=utils.COLORS["brown"]))
            targs.append(targ)
        for box in boxes:
            pose = self.get_random_pose(env, box_size)
            if hasattr(env, "set_object_pose"):
                env.set_object_pose(box, pose)
            elif getattr(env, "reset_object_pose", None) is not None:
                env.reset_object_pose(box, pose)
            else:
                p.resetBasePositionAndOrientation(box, pose[0], pose[1])
        self.add_goal(objs=boxes, matches=np.eye(2), targ_poses=targs, replace=False,
                      rotations=True, metric="pose", params=None, step_max_reward=1,
                      language_goal=self.lang_template)
