import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class CylinderTowerOnStand(Task):
    """Stack three flat cylinders on the centre of the stand, largest at the bottom."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "stack the {size} cylinder on the stand"
        self.task_completed_desc = "done stacking cylinders."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        stand_size = (0.05, 0.15, 0.005)
        stand_pose = self.get_random_pose(env, stand_size)
        env.add_object('stacking/stand.urdf', stand_pose, 'fixed')

        sizes = [(0.07, 0.07, 0.02), (0.06, 0.06, 0.02), (0.05, 0.05, 0.02)]
        names = ['large', 'medium', 'small']
        colors = ['blue', 'green', 'red']
        cylinders = []
        for size, color in zip(sizes, colors):
            urdf = self.fill_template('cylinder/cylinder-template.urdf', {'DIM': size, 'HALF': np.float32(size) / 2})
            pose = self.get_random_pose(env, size)
            cylinders.append(env.add_object(urdf, pose, color=utils.COLORS[color]))

        z = 0.005
        for i, cyl in enumerate(cylinders):
            z += sizes[i][2] / 2
            targ = (utils.apply(stand_pose, (0, 0, z)), stand_pose[1])
            z += sizes[i][2] / 2
            self.add_goal(objs=[cyl], matches=np.ones((1, 1)), targ_poses=[targ], replace=False,
                          rotations=False, metric='pose', params=None, step_max_reward=1 / 3,
                          language_goal=self.lang_template.format(size=names[i]))
