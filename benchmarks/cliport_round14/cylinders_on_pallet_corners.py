import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class CylindersOnPalletCorners(Task):
    """Place four cylinders on the four corners of the pallet."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "place the cylinders on the corners of the pallet"
        self.task_completed_desc = "done placing cylinders on the pallet."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        pallet_size = (0.3, 0.25, 0.0375)
        pallet_pose = self.get_random_pose(env, pallet_size)
        env.add_object('pallet/pallet.urdf', pallet_pose, 'fixed')

        cylinder_size = (0.04, 0.04, 0.06)
        cylinder_template = 'cylinder/cylinder-template.urdf'
        replace = {'DIM': cylinder_size, 'HALF': (cylinder_size[0] / 2, cylinder_size[1] / 2, cylinder_size[2] / 2)}
        cylinder_urdf = self.fill_template(cylinder_template, replace)

        colors = ['red', 'blue', 'green', 'yellow']
        cylinders = []
        for color in colors:
            cylinder_pose = self.get_random_pose(env, cylinder_size)
            cylinders.append(env.add_object(cylinder_urdf, cylinder_pose, color=utils.COLORS[color]))

        corner_offsets = [(0.1, 0.08, 0.07), (0.1, -0.08, 0.07), (-0.1, 0.08, 0.07), (-0.1, -0.08, 0.07)]
        targ_poses = [(utils.apply(pallet_pose, offset), pallet_pose[1]) for offset in corner_offsets]

        self.add_goal(objs=cylinders, matches=np.ones((4, 4)), targ_poses=targ_poses, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
