import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class RowSpacedUnderBlockSize(Task):
    """Three blocks in a row the author spaced 3.8 cm for 4 cm blocks (Ravens checks
    within 1 cm: blocks that touch, each a few mm off, meet it)."""

    def __init__(self):
        super().__init__()
        self.max_steps = 8
        self.lang_template = "make a row of blocks"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        base = self.get_random_pose(env, (0.2, 0.06, 0.04))
        blocks = [env.add_object('block/block.urdf', self.get_random_pose(env, (0.04, 0.04, 0.04)),
                                 color=utils.COLORS[c]) for c in ["red", "green", "blue"]]
        targs = [(utils.apply(base, (-0.038 + 0.038 * i, 0, 0.02)), base[1]) for i in range(3)]
        self.add_goal(objs=blocks, matches=np.eye(3), targ_poses=targs, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
