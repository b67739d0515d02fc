"""An LLM-style bead chain written out by hand: sphere beads linked through frames on
both sides (+h on the parent, -h on the child), listed last bead first in the goal, with
targets along two sides of an L and identity matches (one end first only)."""

import numpy as np
import pybullet as p
from cliport.tasks import primitives
from cliport.tasks.task import Task
from cliport.utils import utils


class BeadChainLShape(Task):
    """Bend the yellow bead chain into an L."""

    def __init__(self):
        super().__init__()
        self.max_steps = 20
        self.pos_eps = 0.02
        self.primitive = primitives.PickPlace(height=0.02, speed=0.001)
        self.lang_template = "bend the yellow bead chain into an L around the corner"

    def reset(self, env):
        super().reset(env)
        n, r, pitch = 16, 0.006, 0.015
        corner_pose = self.get_random_pose(env, (0.2, 0.2, 0.01))
        env.add_object("corner/corner-template.urdf", corner_pose, "fixed")
        corner = np.float32(corner_pose[0])
        start, _ = self.get_random_pose(env, (0.1, 0.1, 0.1))
        shape = p.createCollisionShape(p.GEOM_SPHERE, radius=r)
        look = p.createVisualShape(p.GEOM_SPHERE, radius=r,
                                   rgbaColor=utils.COLORS["yellow"] + [1])
        beads = []
        for i in range(n):
            pos = (start[0], start[1], r + i * pitch)
            beads.append(p.createMultiBody(baseMass=0.05, baseCollisionShapeIndex=shape,
                                           baseVisualShapeIndex=look, basePosition=pos))
            if i:
                p.createConstraint(parentBodyUniqueId=beads[i - 1], parentLinkIndex=-1,
                                   childBodyUniqueId=beads[i], childLinkIndex=-1,
                                   jointType=p.JOINT_POINT2POINT, jointAxis=(0, 0, 0),
                                   parentFramePosition=(0, 0, pitch / 2),
                                   childFramePosition=(0, 0, -pitch / 2))
        # Bead i's target: 8 along +x from the corner, then 8 along +y.
        targets = []
        for i in range(n):
            k = i - 7.5
            off = (0.5 * pitch - (8 - i) * pitch, 0.0) if i < 8 else (0.0, (k - 0.0) * pitch)
            targets.append(((corner[0] + off[0], corner[1] + off[1], 0.006), (0, 0, 0, 1)))
        objs = [(b, (0, None)) for b in reversed(beads)]
        targs = list(reversed(targets))
        self.add_goal(objs=objs, matches=np.eye(n), targ_poses=targs, replace=False,
                      rotations=False, metric="pose", params=None, step_max_reward=1,
                      language_goal=self.lang_template)
