import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class SortBlocksIntoTwoContainers(Task):
    """Sort red blocks into the red container and blue blocks into the blue container."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "put the {color} blocks in the {color} container"
        self.task_completed_desc = "done sorting blocks."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        container_size = (0.15, 0.15, 0.05)
        container_template = 'container/container-template.urdf'
        block_size = (0.04, 0.04, 0.04)

        for color in ['red', 'blue']:
            container_pose = self.get_random_pose(env, container_size)
            container_urdf = self.fill_template(container_template,
                                                {'DIM': container_size,
                                                 'HALF': np.float32(container_size) / 2})
            env.add_object(container_urdf, container_pose, 'fixed', color=utils.COLORS[color])

            blocks = []
            for _ in range(2):
                block_pose = self.get_random_pose(env, block_size)
                blocks.append(env.add_object('block/block.urdf', block_pose, color=utils.COLORS[color]))

            self.add_goal(objs=blocks, matches=np.ones((2, 1)), targ_poses=[container_pose], replace=True,
                          rotations=True, metric='zone', params=[(container_pose, container_size)],
                          step_max_reward=1 / 2, language_goal=self.lang_template.format(color=color))
