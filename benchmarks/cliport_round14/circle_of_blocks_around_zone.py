import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class CircleOfBlocksAroundZone(Task):
    """Arrange six blocks in a circle around the zone."""

    def __init__(self):
        super().__init__()
        self.max_steps = 8
        self.lang_template = "arrange the blocks in a circle around the zone"
        self.task_completed_desc = "done arranging the circle."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        circle_size = (0.3, 0.3, 0)
        zone_pose = self.get_random_pose(env, circle_size)
        env.add_object('zone/zone.urdf', zone_pose, 'fixed')

        n_blocks = 6
        radius = 0.11
        block_size = (0.04, 0.04, 0.04)
        colors = ['red', 'orange', 'yellow', 'green', 'blue', 'purple']

        blocks = []
        targs = []
        for i in range(n_blocks):
            pose = self.get_random_pose(env, block_size)
            blocks.append(env.add_object('block/block.urdf', pose, color=utils.COLORS[colors[i]]))
            angle = 2 * np.pi * i / n_blocks
            targs.append((utils.apply(zone_pose, (radius * np.cos(angle), radius * np.sin(angle), 0.02)),
                          zone_pose[1]))

        self.add_goal(objs=blocks, matches=np.ones((n_blocks, n_blocks)), targ_poses=targs, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
