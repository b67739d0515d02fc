"""Fill a thin-walled container with boxes cut from its own volume by GenSim's
utils.TreeNode / utils.KDTree split (1 cm apart, 1 cm from the container's edge),
each box's true place given as its target (zone metric)."""

import os

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class PackSplitBoxes(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "pack all the boxes inside the brown box"

    def reset(self, env):
        super().reset(env)
        zone_size = (0.2, 0.14, 0.05)
        zone_pose = ((0.5, 0.15, 0.025), (0, 0, 0, 1))
        half = np.float32(zone_size) / 2
        urdf = self.fill_template("container/container-template.urdf",
                                  {"DIM": zone_size, "HALF": (half[0], half[1], half[2])})
        env.add_object(urdf, zone_pose, "fixed")
        os.remove(urdf)

        stack_size = np.array(zone_size)
        stack_size[:2] -= 0.01
        root = utils.TreeNode(None, [], bbox=np.array((0.01, 0.01, 0, *stack_size)))
        bboxes = []
        utils.KDTree(root, 0.05, 0.01, bboxes)

        boxes, true_poses, points = [], [], {}
        for bbox in np.array(bboxes):
            size = bbox[3:] - bbox[:3]
            position = size / 2.0 + bbox[:3]
            position[0] -= zone_size[0] / 2
            position[1] -= zone_size[1] / 2
            true_pose = utils.multiply(zone_pose, (position, (0, 0, 0, 1)))
            box_urdf = self.fill_template("box/box-template.urdf", {"DIM": size})
            box = env.add_object(box_urdf, self.get_random_pose(env, size), color="yellow")
            os.remove(box_urdf)
            boxes.append((box, (0, None)))
            points[box] = self.get_box_object_points(box)
            true_poses.append(true_pose)
        self.goals.append((boxes, np.eye(len(boxes)), true_poses, False, True, "zone",
                           (points, [(zone_pose, zone_size)]), 1))
        self.lang_goals.append(self.lang_template)
