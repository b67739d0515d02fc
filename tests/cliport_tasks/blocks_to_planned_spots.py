"""Ravens-style: a packing plan — each block has its own spot in the zone — and the
goal is appended to ``self.goals`` directly, with Ravens' ``(object_points, zones)``."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlocksToPlannedSpots(Task):
    """Put the two blocks on their planned spots in the zone."""

    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "put the blocks in the zone"
        self.task_completed_desc = "done."

    def reset(self, env):
        super().reset(env)
        zone_size = (0.12, 0.12, 0)
        zone_pose = ((0.55, 0.2, 0.0), (0, 0, 0, 1))
        env.add_object("zone/zone.urdf", zone_pose, "fixed", color="green")
        blocks, spots, points = [], [], {}
        for k, color in enumerate(("red", "blue")):
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            block = env.add_object("block/block.urdf", pose, color=utils.COLORS[color])
            blocks.append((block, (np.pi / 2, None)))
            points[block] = np.zeros((3, 1))
            spots.append(((0.525 + 0.05 * k, 0.2, 0.02), (0, 0, 0, 1)))
        self.goals.append((blocks, np.eye(2), spots, False, True, "zone",
                           (points, [(zone_pose, zone_size)]), 1))
        self.lang_goals.append(self.lang_template)
