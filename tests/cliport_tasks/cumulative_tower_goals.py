"""A tower whose every goal lists all the blocks placed so far, each at the same target
as before (goal k: blocks[:k] -> targets[:k]): a block listed again stays where an
earlier goal put it (was refused at reset: its slot 'collides with' itself). Written
here in the style of GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class CumulativeBlockTower(Task):
    """Build a three-block tower on a stand; each goal checks the whole tower so far."""

    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "build a tower: {}"
        self.task_completed_desc = "done building."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        base_pose = self.get_random_pose(env, (0.05, 0.15, 0.005))
        env.add_object('stacking/stand.urdf', base_pose, 'fixed')
        names = ['red', 'green', 'blue']
        blocks = []
        for name in names:
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            blocks.append(env.add_object('stacking/block.urdf', pose, color=utils.COLORS[name]))
        targs = [(utils.apply(base_pose, (0, 0, 0.025 + 0.04 * i)), base_pose[1]) for i in range(3)]
        for k in range(1, 4):
            text = self.lang_template.format(f"place the {names[k - 1]} block")
            self.add_goal(objs=blocks[:k], matches=np.eye(k), targ_poses=targs[:k], replace=False,
                          rotations=True, metric='pose', params=None, step_max_reward=1 / 3,
                          symmetries=[np.pi / 2] * k,
                          language_goal=text)
