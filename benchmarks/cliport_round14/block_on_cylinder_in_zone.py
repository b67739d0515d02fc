import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlockOnCylinderInZone(Task):
    """Put the cylinder in the zone, then put the block on top of the cylinder."""

    def __init__(self):
        super().__init__()
        self.max_steps = 3
        self.lang_template = "put the cylinder in the zone and the block on top of it"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        zone_size = (0.12, 0.12, 0)
        zone_pose = self.get_random_pose(env, zone_size)
        env.add_object('zone/zone.urdf', zone_pose, 'fixed')

        cylinder_size = (0.06, 0.06, 0.05)
        cylinder_urdf = self.fill_template('cylinder/cylinder-template.urdf',
                                           {'DIM': cylinder_size, 'HALF': np.float32(cylinder_size) / 2})
        cylinder_pose = self.get_random_pose(env, cylinder_size)
        cylinder = env.add_object(cylinder_urdf, cylinder_pose, color=utils.COLORS['purple'])

        block_size = (0.04, 0.04, 0.04)
        block_pose = self.get_random_pose(env, block_size)
        block = env.add_object('block/block.urdf', block_pose, color=utils.COLORS['orange'])

        self.add_goal(objs=[cylinder], matches=np.ones((1, 1)), targ_poses=[zone_pose], replace=False,
                      rotations=False, metric='zone', params=[(zone_pose, zone_size)],
                      step_max_reward=1 / 2, language_goal="put the purple cylinder in the zone")

        block_targ = (utils.apply(zone_pose, (0, 0, 0.07)), zone_pose[1])
        self.add_goal(objs=[block], matches=np.ones((1, 1)), targ_poses=[block_targ], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 2,
                      language_goal="put the orange block on the cylinder")
