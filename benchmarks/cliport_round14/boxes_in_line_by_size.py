import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BoxesInLineBySize(Task):
    """Line up three boxes from smallest to largest along the line."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "line up the boxes from smallest to largest"
        self.task_completed_desc = "done lining up boxes."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        line_urdf = self.fill_template('line/single-green-line-template.urdf', {'DIM': (0.35,), 'HALF': (0.175,)})
        line_pose = self.get_random_pose(env, (0.35, 0.05, 0.01))
        env.add_object(line_urdf, line_pose, 'fixed')

        sizes = [(0.03, 0.03, 0.03), (0.045, 0.045, 0.045), (0.06, 0.06, 0.06)]
        boxes = []
        for size in sizes:
            box_urdf = self.fill_template('box/box-template.urdf', {'DIM': size})
            box_pose = self.get_random_pose(env, size)
            boxes.append(env.add_object(box_urdf, box_pose, color=utils.COLORS['yellow']))

        xs = [-0.1, 0.0, 0.1]
        targ_poses = []
        for x, size in zip(xs, sizes):
            targ_poses.append((utils.apply(line_pose, (x, 0, size[2] / 2)), line_pose[1]))

        self.add_goal(objs=boxes, matches=np.eye(3), targ_poses=targ_poses, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
