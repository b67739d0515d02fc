import numpy as np
import IPython
from cliport.tasks.task import Task
from cliport.utils import utils


class CubesInContainerCorners(Task):
    """Place four cubes into the four corners of a large container."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "put a cube in each corner of the container"
        self.task_completed_desc = "done filling the container corners."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        container_size = (0.22, 0.22, 0.05)
        container_pose = self.get_random_pose(env, container_size)
        container_urdf = self.fill_template('container/container-template.urdf',
                                            {'DIM': container_size, 'HALF': np.float32(container_size) / 2})
        env.add_object(container_urdf, container_pose, 'fixed')

        block_size = (0.04, 0.04, 0.04)
        cubes = []
        for color in ['red', 'green', 'blue', 'yellow']:
            pose = self.get_random_pose(env, block_size)
            cubes.append(env.add_object('block/block.urdf', pose, color=utils.COLORS[color]))

        d = 0.07
        corners = [(d, d, 0.02), (d, -d, 0.02), (-d, d, 0.02), (-d, -d, 0.02)]
        targs = [(utils.apply(container_pose, c), container_pose[1]) for c in corners]

        self.add_goal(objs=cubes, matches=np.ones((4, 4)), targ_poses=targs, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
