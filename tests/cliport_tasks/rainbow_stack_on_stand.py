import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class RainbowStackOnStand(Task):
    """Stack blocks in rainbow order on the stand, one goal per block, each target
    at the author's own height: the first at the stand's own pose (below its top),
    then a 3 cm step for 4 cm blocks. Was refused at reset (the targets, checked at
    the heights factask corrects them to, intersected)."""

    def __init__(self):
        super().__init__()
        self.max_steps = 12
        self.lang_template = "stack the blocks on the stand in rainbow order"
        self.task_completed_desc = "done stacking."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        stand_size = (0.12, 0.12, 0.02)
        stand_pose = self.get_random_pose(env, stand_size)
        env.add_object('stacking/stand.urdf', stand_pose, 'fixed')
        colors = ['red', 'orange', 'yellow', 'green', 'blue']
        block_size = (0.04, 0.04, 0.04)
        for i, color in enumerate(colors):
            block_pose = self.get_random_pose(env, block_size)
            block_id = env.add_object('stacking/block.urdf', block_pose,
                                      color=utils.COLORS[color])
            place = utils.apply(stand_pose, (0, 0, i * 0.03))
            self.add_goal(objs=[block_id], matches=np.ones((1, 1)),
                          targ_poses=[(place, stand_pose[1])], replace=False,
                          rotations=True, metric='pose', params=None,
                          step_max_reward=1 / len(colors), language_goal=self.lang_template)
