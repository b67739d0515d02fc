"""Ravens-style kitting: shapes from get_kitting_shapes into a kit (make_kitting_objects)."""

import os

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class AssemblingKits(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "put all the shapes in the kit"

    def reset(self, env):
        super().reset(env)
        kit_pose = ((0.5, 0.0, 0.0025), (0, 0, 0, 1))
        env.add_object("kitting/kit.urdf", kit_pose, "fixed")
        n_objects = 3
        obj_shapes = self.get_kitting_shapes(n_objects)
        colors, _ = utils.get_colors(self.mode, n_objects)
        targets = []
        for i in range(n_objects):
            pos = utils.apply(kit_pose, (-0.08 + 0.08 * i, 0.0, 0.0))
            targ = ((pos[0], pos[1], 0.01), (0, 0, 0, 1))
            fname = os.path.join(self.assets_root, "kitting", f"{obj_shapes[i]:02d}.obj")
            urdf = self.fill_template("kitting/object-template-nocollision.urdf",
                                      {"FNAME": (fname,), "SCALE": [0.003, 0.003, 0.0001],
                                       "COLOR": (0.2, 0.2, 0.2)})
            env.add_object(urdf, targ, "fixed")
            targets.append(targ)
        objects, matches = self.make_kitting_objects(env, targets, obj_shapes, n_objects, colors)
        self.add_goal(objs=objects, matches=np.int32(matches), targ_poses=targets, replace=False,
                      rotations=True, metric="pose", params=None, step_max_reward=1,
                      language_goal=self.lang_template)
