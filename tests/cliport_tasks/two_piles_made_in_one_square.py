"""GenSim's mix-piles: two ``make_piles`` calls of different colours, each pile pushed
into the same zone by a goal of its own.

``make_piles`` spawns every pile in the same 20 x 20 cm square, the blocks of both
mixed; factask's piles are separate clusters, so the second starts at a random free
spot (warning). Before, both clusters were pinned at one centre and every reset
failed ("no free spot for the pile").
"""

import numpy as np
from cliport.tasks import primitives
from cliport.tasks.grippers import Spatula
from cliport.tasks.task import Task
from cliport.utils import utils


class TwoPilesMadeInOneSquare(Task):
    """Push the red pile and the blue pile into the zone."""

    def __init__(self):
        super().__init__()
        self.max_steps = 20
        self.num_blocks = 10
        self.lang_template = "push the piles of blocks into the zone"
        self.task_completed_desc = "done mixing piles."
        self.ee = Spatula
        self.primitive = primitives.push
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        zone_size = (0.15, 0.15, 0)
        zone_pose = self.get_random_pose(env, zone_size)
        env.add_object('zone/zone.urdf', zone_pose, 'fixed')

        piles1 = self.make_piles(env, block_color=utils.COLORS['red'])
        piles2 = self.make_piles(env, block_color=utils.COLORS['blue'])

        for piles in (piles1, piles2):
            self.add_goal(objs=piles, matches=np.ones((len(piles), 1)), targ_poses=[zone_pose],
                          replace=True, rotations=False, metric='zone',
                          params=[(zone_pose, zone_size)], step_max_reward=0.5,
                          language_goal=self.lang_template)
