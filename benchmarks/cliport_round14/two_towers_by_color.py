import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class TwoTowersByColor(Task):
    """Build a red tower on the left zone and a blue tower on the right zone, two blocks each."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "build a {color} tower on the {color} zone"
        self.task_completed_desc = "done building towers."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        zone_size = (0.12, 0.12, 0)
        block_size = (0.04, 0.04, 0.04)
        colors = ['red', 'blue']

        for color in colors:
            zone_pose = self.get_random_pose(env, zone_size)
            env.add_object('zone/zone.urdf', zone_pose, 'fixed', color=utils.COLORS[color])

            blocks = []
            for _ in range(2):
                block_pose = self.get_random_pose(env, block_size)
                blocks.append(env.add_object('block/block.urdf', block_pose, color=utils.COLORS[color]))

            targs = [(utils.apply(zone_pose, (0, 0, 0.02)), zone_pose[1]),
                     (utils.apply(zone_pose, (0, 0, 0.06)), zone_pose[1])]
            self.add_goal(objs=blocks, matches=np.ones((2, 2)), targ_poses=targs, replace=False,
                          rotations=True, metric='pose', params=None, step_max_reward=1 / 2,
                          language_goal=self.lang_template.format(color=color))
