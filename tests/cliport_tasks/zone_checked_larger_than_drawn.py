import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BoxesBySizeZones(Task):
    """Big boxes go in the left zone, small boxes in the right zone."""

    def __init__(self):
        super().__init__()
        self.max_steps = 12
        self.lang_template = "put the {size} boxes in the {side} zone"
        self.task_completed_desc = "done sorting boxes."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        zone_size = (0.15, 0.15, 0)
        zones = []
        for color in ['yellow', 'orange']:
            zone_pose = self.get_random_pose(env, zone_size)
            env.add_object('zone/zone.urdf', zone_pose, 'fixed', color=utils.COLORS[color])
            zones.append(zone_pose)
        big, small = [], []
        for _ in range(2):
            size = self.get_random_size(0.06, 0.07, 0.06, 0.07, 0.05, 0.06)
            urdf = self.fill_template('box/box-template.urdf', {'DIM': size})
            pose = self.get_random_pose(env, size)
            big.append(env.add_object(urdf, pose, color=utils.COLORS['blue']))
        for _ in range(2):
            size = self.get_random_size(0.03, 0.04, 0.03, 0.04, 0.03, 0.04)
            urdf = self.fill_template('box/box-template.urdf', {'DIM': size})
            pose = self.get_random_pose(env, size)
            small.append(env.add_object(urdf, pose, color=utils.COLORS['red']))
        self.add_goal(objs=big, matches=np.ones((2, 1)), targ_poses=[zones[0]], replace=True,
                      rotations=False, metric='zone', params=[(zones[0], zone_size)],
                      step_max_reward=1 / 2,
                      language_goal=self.lang_template.format(size='big', side='yellow'))
        self.add_goal(objs=small, matches=np.ones((2, 1)), targ_poses=[zones[1]], replace=True,
                      rotations=False, metric='zone', params=[(zones[1], zone_size)],
                      step_max_reward=1 / 2,
                      language_goal=self.lang_template.format(size='small', side='orange'))
