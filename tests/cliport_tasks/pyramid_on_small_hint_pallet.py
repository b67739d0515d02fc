"""A pyramid (three, two, one) on a pallet placed with a 1 cm size hint
(factask's pallet is 3.75 cm tall, so it starts on the table and the author's
targets on it must follow it up, every layer with them). Written here in the
style of GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class PyramidOnSmallHintPallet(Task):
    """Build a three-two-one pyramid of blocks on the pallet."""

    def __init__(self):
        super().__init__()
        self.max_steps = 12
        self.lang_template = "build a pyramid on the pallet"
        self.task_completed_desc = "done building the pyramid."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        pallet_size = (0.18, 0.18, 0.01)
        pallet_pose = self.get_random_pose(env, pallet_size)
        env.add_object('pallet/pallet.urdf', pallet_pose, 'fixed')
        colors = [utils.COLORS[c] for c in ['red', 'red', 'red', 'green', 'green', 'blue']]
        blocks = []
        for color in colors:
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            blocks.append(env.add_object('block/block.urdf', pose, color=color))
        place_pos = [(0, -0.05, 0.03), (0, 0, 0.03), (0, 0.05, 0.03),
                     (0, -0.025, 0.08), (0, 0.025, 0.08), (0, 0, 0.13)]
        targs = [(utils.apply(pallet_pose, i), pallet_pose[1]) for i in place_pos]
        self.add_goal(objs=blocks[:3], matches=np.ones((3, 3)), targ_poses=targs[:3], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 2,
                      language_goal="put the red blocks in a row on the pallet")
        self.add_goal(objs=blocks[3:5], matches=np.ones((2, 2)), targ_poses=targs[3:5],
                      replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 3,
                      language_goal="put the green blocks on the red blocks")
        self.add_goal(objs=blocks[5:], matches=np.ones((1, 1)), targ_poses=targs[5:], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 6,
                      language_goal="put the blue block on top")
