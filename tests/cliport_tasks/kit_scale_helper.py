"""A task file that sizes its objects with GenSim's `utils.map_kit_scale` (a kit
shape's mesh scale / 10): was refused ('cliport.utils.utils.map_kit_scale is not
provided'). Written in the style of GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class KitScaleHelper(Task):
    """Put two boxes, sized from a kit scale, on the pallet."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "put the boxes on the pallet"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        pallet_size = (0.15, 0.15, 0.02)
        pallet_pose = self.get_random_pose(env, pallet_size)
        env.add_object('pallet/pallet.urdf', pallet_pose, 'fixed')
        scale = utils.map_kit_scale((0.4, 0.4, 0.4))  # (0.04, 0.04, 0.04)
        urdf = self.fill_template('box/box-template.urdf', {'DIM': scale})
        boxes, targets = [], []
        for i, color in enumerate(['red', 'blue']):
            boxes.append(env.add_object(urdf, self.get_random_pose(env, scale),
                                        color=utils.COLORS[color]))
            targets.append((utils.apply(pallet_pose, (0, (i - 0.5) * 0.06, 0.03)),
                            pallet_pose[1]))
        self.add_goal(objs=boxes, matches=np.ones((2, 2)), targ_poses=targets,
                      replace=False, rotations=True, metric='pose', params=None,
                      step_max_reward=1, language_goal=self.lang_template)
