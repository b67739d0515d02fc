import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlockAndBallIntoContainer(Task):
    """Put the green block and the blue ball into the container."""

    def __init__(self):
        super().__init__()
        self.max_steps = 3
        self.lang_template = "put the {obj} in the container"
        self.task_completed_desc = "done filling the container."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        container_size = (0.16, 0.16, 0.06)
        container_pose = self.get_random_pose(env, container_size)
        container_urdf = self.fill_template('container/container-template.urdf',
                                            {'DIM': container_size, 'HALF': np.float32(container_size) / 2})
        env.add_object(container_urdf, container_pose, 'fixed')

        block_size = (0.04, 0.04, 0.04)
        block = env.add_object('block/block.urdf', self.get_random_pose(env, block_size),
                               color=utils.COLORS['green'])

        ball_size = (0.04, 0.04, 0.04)
        ball_urdf = self.fill_template('ball/ball-template.urdf', {'DIM': ball_size})
        ball = env.add_object(ball_urdf, self.get_random_pose(env, ball_size), color=utils.COLORS['blue'])

        # Both go to the container.
        self.add_goal(objs=[block], matches=np.ones((1, 1)), targ_poses=[container_pose], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 2,
                      language_goal=self.lang_template.format(obj='green block'))
        self.add_goal(objs=[ball], matches=np.ones((1, 1)), targ_poses=[container_pose], replace=False,
                      rotations=False, metric='pose', params=None, step_max_reward=1 / 2,
                      language_goal=self.lang_template.format(obj='blue ball'))
