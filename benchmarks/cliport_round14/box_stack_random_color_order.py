import random

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BoxStackRandomColorOrder(Task):
    """Stack three boxes in a randomly chosen colour order, bottom to top."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "put the {color} box {where}"
        self.task_completed_desc = "done stacking boxes in order."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        colors = random.sample(['red', 'green', 'blue', 'yellow', 'purple'], 3)

        base_pose = self.get_random_pose(env, (0.1, 0.1, 0))
        box_size = (0.05, 0.05, 0.05)
        box_urdf = self.fill_template('box/box-template.urdf', {'DIM': box_size})

        boxes = []
        for color in colors:
            pose = self.get_random_pose(env, box_size)
            boxes.append(env.add_object(box_urdf, pose, color=utils.COLORS[color]))

        for i, box_id in enumerate(boxes):
            targ = (utils.apply(base_pose, (0, 0, box_size[2] / 2 + i * box_size[2])), base_pose[1])
            if i == 0:
                where = "on the table"
            else:
                where = f"on the {colors[i - 1]} box"
            self.add_goal(objs=[box_id], matches=np.ones((1, 1)), targ_poses=[targ], replace=False,
                          rotations=True, metric='pose', params=None, step_max_reward=1 / 3,
                          language_goal=self.lang_template.format(color=colors[i], where=where))
