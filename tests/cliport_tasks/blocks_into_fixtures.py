"""Blocks (not ells) inserted into insertion fixtures, one goal per block, the
fixtures in a row turned 90 degrees. The goals' targets are the fixtures' poses
in world coordinates: the fixtures were given the ell hollow (nothing named
them), which a block cannot enter; each block came to rest tilted on the hollow's
edge. Written here in the style of GenSim's generated tasks."""

import numpy as np
import pybullet as p
from cliport.tasks.task import Task
from cliport.utils import utils


class BlocksIntoFixtures(Task):
    """Insert each colored block into the fixture of the same color."""

    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "insert the {color} block into the {color} fixture"
        self.task_completed_desc = "done inserting blocks."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        colors = ['red', 'blue', 'green']
        fixture_poses = []
        for i, color in enumerate(colors):
            pose = ((0.4 + 0.13 * i, 0.3, 0.02), p.getQuaternionFromEuler((0, 0, np.pi / 2)))
            env.add_object('insertion/fixture.urdf', pose, 'fixed', color=utils.COLORS[color])
            fixture_poses.append(pose)
        block_size = (0.04, 0.04, 0.04)
        blocks = [env.add_object('block/block.urdf', self.get_random_pose(env, block_size),
                                 color=utils.COLORS[color]) for color in colors]
        for i, color in enumerate(colors):
            self.add_goal(objs=[blocks[i]], matches=np.ones((1, 1)), targ_poses=[fixture_poses[i]],
                          replace=False, rotations=True, metric='pose', params=None,
                          step_max_reward=1 / 3,
                          language_goal=self.lang_template.format(color=color))
