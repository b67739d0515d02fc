import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class TowerInZoneWithPrint(Task):
    """Stack three blocks into a tower in the middle of the zone."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "stack the blocks into a tower in the zone"
        self.task_completed_desc = "done stacking the tower."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        zone_size = (0.12, 0.12, 0)
        zone_pose = self.get_random_pose(env, zone_size)
        env.add_object('zone/zone.urdf', zone_pose, 'fixed')
        print("zone pose:", zone_pose)

        block_size = (0.04, 0.04, 0.04)
        blocks = []
        for color in ['blue', 'red', 'green']:
            block_pose = self.get_random_pose(env, block_size)
            blocks.append(env.add_object('block/block.urdf', block_pose, color=utils.COLORS[color]))
        print("blocks:", blocks)

        targs = []
        for i in range(3):
            targs.append((utils.apply(zone_pose, (0, 0, 0.02 + i * 0.04)), zone_pose[1]))

        self.add_goal(objs=blocks, matches=np.ones((3, 3)), targ_poses=targs, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
