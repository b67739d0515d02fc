import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class SortSixBlocksIntoThreeZones(Task):
    """Sort six blocks into three zones by color, two per zone."""

    def __init__(self):
        super().__init__()
        self.max_steps = 12
        self.lang_template = "put the {color} blocks in the {color} zone"
        self.task_completed_desc = "done sorting."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        color_names = ['red', 'green', 'blue']
        zone_size = (0.12, 0.12, 0)
        zone_poses = []
        for c in color_names:
            zp = self.get_random_pose(env, zone_size)
            env.add_object('zone/zone.urdf', zp, 'fixed', color=utils.COLORS[c])
            zone_poses.append(zp)
        blocks, block_colors = [], []
        for c in color_names:
            for _ in range(2):
                pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
                blocks.append(env.add_object('stacking/block.urdf', pose, color=utils.COLORS[c]))
                block_colors.append(c)
        matches = np.zeros((6, 3))
        for i, c in enumerate(block_colors):
            matches[i, color_names.index(c)] = 1
        self.add_goal(objs=blocks, matches=matches, targ_poses=zone_poses, replace=True,
                      rotations=False, metric='zone', params=[(zp, zone_size) for zp in zone_poses],
                      step_max_reward=1, language_goal="sort the blocks into the zones by color")
