"""Blocks (not ells) inserted into insertion fixtures by ONE goal whose matches are
the identity: each target lies in another fixture, so the goal stays in world
coordinates (no one fixture's frame). Nothing named the fixtures, so they had the
ell hollow, which a block cannot enter: each block came to rest tilted on the
hollow's edge. Written here in the style of GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlocksIntoFixturesOneGoal(Task):
    """Put every block into the fixture of its color."""

    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "put each block into the fixture of the same color"
        self.task_completed_desc = "done inserting blocks."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        colors = ['red', 'blue', 'green']
        fixture_poses = []
        for i, color in enumerate(colors):
            pose = ((0.45, -0.2 + 0.15 * i, 0.02), (0, 0, 0, 1))
            env.add_object('insertion/fixture.urdf', pose, 'fixed', color=utils.COLORS[color])
            fixture_poses.append(pose)
        block_size = (0.04, 0.04, 0.04)
        blocks = [env.add_object('block/block.urdf', self.get_random_pose(env, block_size),
                                 color=utils.COLORS[color]) for color in colors]
        self.add_goal(objs=blocks, matches=np.eye(3), targ_poses=fixture_poses, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
