import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlocksInMatchingZones(Task):
    """Move each block into the zone that has the same colour."""

    def __init__(self):
        super().__init__()
        self.max_steps = 3
        self.lang_template = "move the {color} block into the {color} zone"
        self.task_completed_desc = "done placing blocks in zones."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        colors = ['green', 'purple', 'orange']
        zone_size = (0.12, 0.12, 0)
        zone_poses = []
        for color in colors:
            zone_pose = self.get_random_pose(env, zone_size)
            env.add_object('zone/zone.urdf', zone_pose, 'fixed', color=utils.COLORS[color])
            zone_poses.append(zone_pose)

        block_size = (0.04, 0.04, 0.04)
        for color, zone_pose in zip(colors, zone_poses):
            block_pose = self.get_random_pose(env, block_size)
            block_id = env.add_object('block/block.urdf', block_pose, color=utils.COLORS[color])
            self.add_goal(objs=[block_id], matches=np.ones((1, 1)), targ_poses=[zone_pose],
                          replace=False, rotations=True, metric='zone',
                          params=[(zone_pose, zone_size)], step_max_reward=1 / 3,
                          language_goal=self.lang_template.format(color=color))
