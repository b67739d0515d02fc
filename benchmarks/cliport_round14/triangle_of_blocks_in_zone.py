import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class TriangleOfBlocksInZone(Task):
    """Arrange three blocks in a triangle inside the large zone."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "arrange the blocks in a triangle in the zone"
        self.task_completed_desc = "done arranging the triangle."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        zone_size = (0.2, 0.2, 0)
        zone_pose = self.get_random_pose(env, zone_size)
        zone_urdf = 'zone/zone.urdf'
        env.add_object(zone_urdf, zone_pose, 'fixed')

        block_size = (0.04, 0.04, 0.04)
        blocks = []
        for color in ['red', 'blue', 'green']:
            pose = self.get_random_pose(env, block_size)
            blocks.append(env.add_object('block/block.urdf', pose, color=utils.COLORS[color]))

        r = 0.05
        angles = [0, 2 * np.pi / 3, 4 * np.pi / 3]
        targs = [(utils.apply(zone_pose, (r * np.cos(a), r * np.sin(a), 0.02)), zone_pose[1]) for a in angles]

        self.add_goal(objs=blocks, matches=np.ones((3, 3)), targ_poses=targs, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
