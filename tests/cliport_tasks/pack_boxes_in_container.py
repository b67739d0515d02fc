"""Pack two filled-template boxes into a filled-template container (zone metric)."""

import os

import numpy as np
from cliport.tasks.task import Task


class PackBoxesInContainer(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 8
        self.lang_template = "pack the {color} boxes into the brown container"

    def reset(self, env):
        super().reset(env)
        container_size = (0.24, 0.18, 0.06)
        container_pose = ((0.45, -0.2, 0.03), (0, 0, 0, 1))
        half = np.float32(container_size) / 2
        urdf = self.fill_template("container/container-template.urdf",
                                  {"DIM": container_size, "HALF": (half[0], half[1], half[2])})
        container = env.add_object(urdf, container_pose, "fixed")
        os.remove(urdf)
        boxes = []
        for _ in range(2):
            size = (0.05, 0.05, 0.04)
            box_urdf = self.fill_template("box/box-template.urdf", {"DIM": size})
            pose = self.get_random_pose(env, size)
            boxes.append(env.add_object(box_urdf, pose, color="orange"))
            os.remove(box_urdf)
        assert container in env.obj_ids["fixed"]
        self.add_goal(objs=boxes, matches=np.ones((2, 1)), targ_poses=[container_pose],
                      replace=True, rotations=True, metric="zone",
                      params=[(container_pose, container_size)], step_max_reward=1,
                      language_goal=self.lang_template.format(color="orange"))
