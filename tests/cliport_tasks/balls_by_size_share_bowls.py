import numpy as np
from cliport.tasks.task import Task


class BallsBySizeIntoBowls(Task):
    """Small balls go in the left bowl, big balls in the right bowl."""

    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "put the {size} balls in the {side} bowl"
        self.task_completed_desc = "done sorting balls by size."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        bowl_urdf = 'bowl/bowl.urdf'
        left_pose = ((0.45, -0.25, 0.0), (0, 0, 0, 1))
        right_pose = ((0.45, 0.25, 0.0), (0, 0, 0, 1))
        env.add_object(bowl_urdf, left_pose, 'fixed')
        env.add_object(bowl_urdf, right_pose, 'fixed')

        ball_urdf = 'ball/ball-template.urdf'
        for size_name, dim, bowl_pose, side in [('small', 0.03, left_pose, 'left'),
                                                ('big', 0.05, right_pose, 'right')]:
            balls = []
            for _ in range(2):
                replace = {'DIM': (dim, dim, dim), 'HALF': (dim / 2, dim / 2, dim / 2),
                           'COLOR': (0.2, 0.6, 0.9)}
                urdf = self.fill_template(ball_urdf, replace)
                pose = self.get_random_pose(env, (dim, dim, dim))
                balls.append(env.add_object(urdf, pose))
            # Both balls share the bowl's one target (replace=True).
            self.add_goal(objs=balls, matches=np.ones((2, 1)), targ_poses=[bowl_pose], replace=True,
                          rotations=False, metric='pose', params=None, step_max_reward=1 / 2,
                          language_goal=self.lang_template.format(size=size_name, side=side))
