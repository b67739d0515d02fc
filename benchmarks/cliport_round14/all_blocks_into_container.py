import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class AllBlocksIntoContainer(Task):
    """Pick up all four blocks and drop them into the brown container."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "put the {color} block in the container"
        self.task_completed_desc = "done putting blocks in the container."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        # Add container.
        container_size = (0.2, 0.2, 0.06)
        container_pose = self.get_random_pose(env, container_size)
        container_template = 'container/container-template.urdf'
        half = np.float32(container_size) / 2
        replace = {'DIM': container_size, 'HALF': half}
        container_urdf = self.fill_template(container_template, replace)
        env.add_object(container_urdf, container_pose, 'fixed')

        # Add blocks.
        colors = ['red', 'green', 'blue', 'yellow']
        block_size = (0.04, 0.04, 0.04)
        for color in colors:
            block_pose = self.get_random_pose(env, block_size)
            block_id = env.add_object('block/block.urdf', block_pose, color=utils.COLORS[color])

            # Each block goes to the container.
            self.add_goal(objs=[block_id], matches=np.ones((1, 1)), targ_poses=[container_pose],
                          replace=False, rotations=True, metric='pose', params=None,
                          step_max_reward=1 / len(colors),
                          language_goal=self.lang_template.format(color=color))
