import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class CylindersBetweenTwoLines(Task):
    """Place three cylinders in a row between two parallel green lines."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "place the cylinders in a row between the two lines"
        self.task_completed_desc = "done placing cylinders."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        area_size = (0.3, 0.12, 0.01)
        area_pose = self.get_random_pose(env, area_size)

        line_urdf = self.fill_template('line/single-green-line-template.urdf', {'DIM': (0.3,), 'HALF': (0.15,)})
        for dy in [-0.05, 0.05]:
            line_pose = (utils.apply(area_pose, (0, dy, 0.001)), area_pose[1])
            env.add_object(line_urdf, line_pose, 'fixed')

        cylinder_size = (0.04, 0.04, 0.05)
        cylinder_urdf = self.fill_template('cylinder/cylinder-template.urdf',
                                           {'DIM': cylinder_size, 'HALF': np.float32(cylinder_size) / 2})
        cylinders = []
        for color in ['red', 'yellow', 'cyan']:
            pose = self.get_random_pose(env, cylinder_size)
            cylinders.append(env.add_object(cylinder_urdf, pose, color=utils.COLORS[color]))

        targ_poses = [(utils.apply(area_pose, (x, 0, 0.025)), area_pose[1]) for x in [-0.08, 0, 0.08]]
        self.add_goal(objs=cylinders, matches=np.ones((3, 3)), targ_poses=targ_poses, replace=False,
                      rotations=False, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
