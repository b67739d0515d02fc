"""Ravens' stack-block-pyramid: six blocks on a stand, three layers, loops + utils.apply."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class StackBlockPyramid(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 12
        self.lang_template = "make the {row} row of the pyramid"

    def reset(self, env):
        super().reset(env)
        base_size = (0.05, 0.15, 0.005)
        base_pose = ((0.5, 0.1, 0.0025), utils.eulerXYZ_to_quatXYZW((0, 0, 0)))
        env.add_object("stacking/stand.urdf", base_pose, "fixed")
        colors = ["purple", "blue", "green", "yellow", "orange", "red"]
        blocks = []
        for color in colors:
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            blocks.append(env.add_object("stacking/block.urdf", pose, color=utils.COLORS[color]))
        place_pos = [(0, -0.05, 0.03), (0, 0, 0.03), (0, 0.05, 0.03),
                     (0, -0.025, 0.08), (0, 0.025, 0.08), (0, 0, 0.13)]
        targs = [(utils.apply(base_pose, i), base_pose[1]) for i in place_pos]
        rows = [("bottom", blocks[:3], targs[:3], 1 / 2),
                ("middle", blocks[3:5], targs[3:5], 1 / 3),
                ("top", blocks[5:], targs[5:], 1 / 6)]
        for row, objs, row_targs, reward in rows:
            self.add_goal(objs=objs, matches=np.ones((len(objs), len(objs))), targ_poses=row_targs,
                          replace=False, rotations=True, metric="pose", params=None,
                          step_max_reward=reward, symmetries=[np.pi / 2] * len(objs),
                          language_goal=self.lang_template.format(row=row))
        assert base_size[2] > 0
