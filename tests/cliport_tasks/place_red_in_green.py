"""Ravens-style: put the red blocks in the green zone (goals appended directly)."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class PlaceRedInGreen(Task):
    """Put the red blocks in the green zone."""

    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "put the red blocks in the green zone"
        self.task_completed_desc = "done placing blocks in the zone."

    def reset(self, env):
        super().reset(env)
        zone_size = (0.12, 0.12, 0)
        zone_pose = ((0.6, 0.25, 0.0), (0, 0, 0, 1))
        env.add_object("zone/zone.urdf", zone_pose, "fixed", color="green")
        blocks = []
        for _ in range(2):
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            blocks.append((env.add_object("block/block.urdf", pose, color=utils.COLORS["red"]),
                           (np.pi / 2, None)))
        self.goals.append((blocks, np.ones((2, 1)), [zone_pose], True, False, "zone",
                           [(zone_pose, zone_size)], 1))
        self.lang_goals.append(self.lang_template)
