import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class StackRandomSizeBoxes(Task):
    """Stack three boxes of decreasing size on top of each other at the marked spot."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "stack the boxes from largest to smallest"
        self.task_completed_desc = "done stacking boxes."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        base_size = (0.12, 0.12, 0)
        base_pose = self.get_random_pose(env, base_size)
        env.add_object('zone/zone.urdf', base_pose, 'fixed')

        sizes = [self.get_random_size(0.08, 0.1, 0.08, 0.1, 0.03, 0.04),
                 self.get_random_size(0.06, 0.07, 0.06, 0.07, 0.03, 0.04),
                 self.get_random_size(0.04, 0.05, 0.04, 0.05, 0.03, 0.04)]
        colors = ['blue', 'green', 'red']

        z = 0
        for i, size in enumerate(sizes):
            urdf = self.fill_template('box/box-template.urdf', {'DIM': size})
            pose = self.get_random_pose(env, size)
            box_id = env.add_object(urdf, pose, color=utils.COLORS[colors[i]])
            z += size[2] / 2
            targ = (utils.apply(base_pose, (0, 0, z)), base_pose[1])
            z += size[2] / 2
            self.add_goal(objs=[box_id], matches=np.ones((1, 1)), targ_poses=[targ], replace=False,
                          rotations=True, metric='pose', params=None, step_max_reward=1 / 3,
                          language_goal=f"put the {colors[i]} box on the stack")
