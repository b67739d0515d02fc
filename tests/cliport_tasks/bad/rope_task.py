"""A rope closed into a ring (its last bead linked to its first): unsupported."""

import pybullet as p
from cliport.tasks.task import Task


class RopeTask(Task):
    def reset(self, env):
        super().reset(env)
        objs, targs, matches = self.make_ropes(env, corners=((0.4, 0.0, 0.0), (0.6, 0.0, 0.0)))
        p.createConstraint(objs[-1][0], -1, objs[0][0], -1, p.JOINT_POINT2POINT, (0, 0, 0),
                           (0, 0, 0.01), (0, 0, 0))
        self.add_goal(objs=objs, matches=matches, targ_poses=targs, replace=False,
                      rotations=False, metric="pose", params=None, step_max_reward=1,
                      language_goal="lay the ring along the line")
