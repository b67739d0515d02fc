import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class RedThenBlueBlockIntoBowl(Task):
    """First put the red block in the bowl, then put the blue block in the zone."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "first put the red block in the bowl, then put the blue block in the zone"
        self.task_completed_desc = "done with the sequence."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        bowl_size = (0.12, 0.12, 0)
        bowl_pose = self.get_random_pose(env, bowl_size)
        env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed')

        zone_size = (0.12, 0.12, 0)
        zone_pose = self.get_random_pose(env, zone_size)
        env.add_object('zone/zone.urdf', zone_pose, 'fixed')

        block_size = (0.04, 0.04, 0.04)
        red_pose = self.get_random_pose(env, block_size)
        red_block = env.add_object('block/block.urdf', red_pose, color=utils.COLORS['red'])
        blue_pose = self.get_random_pose(env, block_size)
        blue_block = env.add_object('block/block.urdf', blue_pose, color=utils.COLORS['blue'])

        # Step 1: red block in bowl.
        self.add_goal(objs=[red_block], matches=np.ones((1, 1)), targ_poses=[bowl_pose], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 2,
                      language_goal="put the red block in the bowl")
        # Step 2: blue block in zone.
        self.add_goal(objs=[blue_block], matches=np.ones((1, 1)), targ_poses=[zone_pose], replace=False,
                      rotations=True, metric='zone', params=[(zone_pose, zone_size)],
                      step_max_reward=1 / 2, language_goal="put the blue block in the zone")
