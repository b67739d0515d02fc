"""Blocks sorted into containers of their colour, two containers per colour: each
block's goal lists both containers of its colour as targets (a choice), one goal
per block. Written here in the style of GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlocksIntoEitherContainer(Task):
    """Sort blocks into the containers of the matching colour."""

    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "put the {color} block in a {color} container"
        self.task_completed_desc = "done sorting blocks into containers."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        container_size = (0.12, 0.12, 0.12)
        urdf = self.fill_template("container/container-template.urdf",
                                  {"DIM": container_size,
                                   "HALF": np.float32(container_size) / 2})
        colors = ["red", "blue"]
        container_poses = []
        for color in colors:
            for _ in range(2):
                pose = self.get_random_pose(env, container_size)
                env.add_object(urdf, pose, "fixed", color=utils.COLORS[color])
                container_poses.append(pose)

        block_size = (0.04, 0.04, 0.04)
        blocks = []
        for color in colors:
            for _ in range(2):
                pose = self.get_random_pose(env, block_size)
                blocks.append(env.add_object("block/block.urdf", pose,
                                             color=utils.COLORS[color]))

        # Each block: either container of its colour (the targets' z is the
        # containers' centre height, which Ravens ignores).
        for i, block in enumerate(blocks):
            targets = container_poses[i // 2 * 2:(i // 2 + 1) * 2]
            self.add_goal(objs=[block], matches=np.ones((1, 2)), targ_poses=targets,
                          replace=False, rotations=True, metric="pose", params=None,
                          step_max_reward=1 / len(blocks),
                          language_goal=self.lang_template.format(color=colors[i // 2]))
