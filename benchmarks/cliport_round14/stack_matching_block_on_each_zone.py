import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class StackMatchingBlockOnEachZone(Task):
    """On each coloured zone, stack two blocks of the zone's colour."""

    def __init__(self):
        super().__init__()
        self.max_steps = 8
        self.lang_template = "stack the {color} blocks on the {color} zone"
        self.task_completed_desc = "done stacking blocks on zones."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        colors, _ = utils.get_colors(mode=self.mode, n_colors=3)
        color_names = ['first', 'second', 'third']
        zone_size = (0.1, 0.1, 0)
        block_size = (0.04, 0.04, 0.04)

        zone_poses = []
        for i in range(3):
            zone_pose = self.get_random_pose(env, zone_size)
            env.add_object('zone/zone.urdf', zone_pose, 'fixed', color=colors[i])
            zone_poses.append(zone_pose)

        for i in range(3):
            blocks = []
            for _ in range(2):
                block_pose = self.get_random_pose(env, block_size)
                blocks.append(env.add_object('block/block.urdf', block_pose, color=colors[i]))
            bottom = (utils.apply(zone_poses[i], (0, 0, 0.02)), zone_poses[i][1])
            top = (utils.apply(zone_poses[i], (0, 0, 0.06)), zone_poses[i][1])
            self.add_goal(objs=blocks, matches=np.ones((2, 2)), targ_poses=[bottom, top], replace=False,
                          rotations=True, metric='pose', params=None, step_max_reward=1 / 3,
                          language_goal=self.lang_template.format(color=color_names[i]))
