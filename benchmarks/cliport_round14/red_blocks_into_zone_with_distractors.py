import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class RedBlocksIntoZoneWithDistractors(Task):
    """Put only the red blocks into the zone; leave the other blocks where they are."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "put all the red blocks in the zone"
        self.task_completed_desc = "done moving red blocks."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        zone_size = (0.15, 0.15, 0)
        zone_pose = self.get_random_pose(env, zone_size)
        env.add_object('zone/zone.urdf', zone_pose, 'fixed')

        block_size = (0.04, 0.04, 0.04)
        red_blocks = []
        for _ in range(3):
            block_pose = self.get_random_pose(env, block_size)
            red_blocks.append(env.add_object('block/block.urdf', block_pose, color=utils.COLORS['red']))

        # Distractors.
        distractor_colors = ['blue', 'green', 'yellow']
        for color in distractor_colors:
            block_pose = self.get_random_pose(env, block_size)
            env.add_object('block/block.urdf', block_pose, color=utils.COLORS[color])

        self.add_goal(objs=red_blocks, matches=np.ones((3, 1)), targ_poses=[zone_pose], replace=True,
                      rotations=True, metric='zone', params=[(zone_pose, zone_size)],
                      step_max_reward=1, language_goal=self.lang_template)
