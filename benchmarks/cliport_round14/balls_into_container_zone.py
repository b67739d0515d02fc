import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BallsIntoContainerZone(Task):
    """Drop the three balls into the container."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "put the balls in the container"
        self.task_completed_desc = "done putting balls in the container."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        container_size = (0.18, 0.18, 0.05)
        container_pose = self.get_random_pose(env, container_size)
        container_urdf = self.fill_template('container/container-template.urdf',
                                            {'DIM': container_size, 'HALF': np.float32(container_size) / 2})
        env.add_object(container_urdf, container_pose, 'fixed')

        ball_size = (0.04, 0.04, 0.04)
        ball_urdf = self.fill_template('ball/ball-template.urdf', {'DIM': ball_size})
        balls = []
        for color in ['red', 'green', 'blue']:
            ball_pose = self.get_random_pose(env, ball_size)
            balls.append(env.add_object(ball_urdf, ball_pose, color=utils.COLORS[color]))

        self.add_goal(objs=balls, matches=np.ones((3, 1)), targ_poses=[container_pose], replace=True,
                      rotations=False, metric='zone', params=[(container_pose, container_size)],
                      step_max_reward=1, language_goal=self.lang_template)
