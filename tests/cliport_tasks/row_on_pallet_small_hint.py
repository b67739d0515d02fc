"""A row of blocks on a pallet placed with a smaller size than factask's pallet asset
(a 2 cm hint for a 3.75 cm pallet, so its recorded centre sinks it into the table),
targets given as offsets in the pallet's frame with ``utils.apply``. Written here
in the style of GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class RowOnPalletSmallHint(Task):
    """Place blocks in a row on the pallet, left to right."""

    def __init__(self):
        super().__init__()
        self.max_steps = 8
        self.lang_template = "put the {color} block on the pallet, next in the row"
        self.task_completed_desc = "done building the row."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        pallet_size = (0.3, 0.15, 0.02)
        pallet_pose = self.get_random_pose(env, pallet_size)
        env.add_object("pallet/pallet.urdf", pallet_pose, "fixed")

        colors = ["red", "yellow", "blue"]
        block_size = (0.04, 0.04, 0.04)
        blocks = []
        for color in colors:
            pose = self.get_random_pose(env, block_size)
            blocks.append(env.add_object("stacking/block.urdf", pose,
                                         color=utils.COLORS[color]))

        # On the pallet's top as the author sized it: 2 cm + half a block.
        offsets = [(-0.08 + 0.08 * i, 0, 0.03) for i in range(3)]
        targets = [(utils.apply(pallet_pose, o), pallet_pose[1]) for o in offsets]
        for i, block in enumerate(blocks):
            self.add_goal(objs=[block], matches=np.ones((1, 1)), targ_poses=[targets[i]],
                          replace=False, rotations=True, metric="pose", params=None,
                          step_max_reward=1 / 3,
                          language_goal=self.lang_template.format(color=colors[i]))
