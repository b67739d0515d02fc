"""Targets turned with PyBullet's axis-angle maths: ``p.getQuaternionFromAxisAngle``,
``p.rotateVector`` and ``p.getAxisAngleFromQuaternion`` (pure maths, as
``getQuaternionFromEuler``). Before, the stand-in refused them as unsupported calls
and the import failed.
"""

import numpy as np
import pybullet as p
from cliport.tasks.task import Task
from cliport.utils import utils


class AxisAngleTargets(Task):
    """Place three blocks around the bowl, each turned to face it."""

    def __init__(self):
        super().__init__()
        self.max_steps = 8
        self.lang_template = "place the blocks around the bowl facing it"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        bowl_pose = self.get_random_pose(env, (0.3, 0.3, 0))
        env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed')
        blocks, targs = [], []
        for k, c in enumerate(['red', 'green', 'blue']):
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            blocks.append(env.add_object('block/block.urdf', pose, color=utils.COLORS[c]))
            turn = p.getQuaternionFromAxisAngle([0, 0, 1], 2 * np.pi * k / 3)
            offset = p.rotateVector(turn, [0.1, 0, 0])
            pos = (bowl_pose[0][0] + offset[0], bowl_pose[0][1] + offset[1], 0.02)
            targs.append((pos, turn))
        _, angle = p.getAxisAngleFromQuaternion(targs[1][1])
        assert abs(angle - 2 * np.pi / 3) < 1e-6
        self.add_goal(objs=blocks, matches=np.eye(3), targ_poses=targs, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
