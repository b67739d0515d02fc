import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BoxesQueuedToPalletCentre(Task):
    """Put the red box on the pallet, then the blue box on the pallet: both goals
    target the pallet's centre (GenSim writes one goal per object). Was refused at reset: the
    second target collided with the first."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "put the {color} box on the pallet"
        self.task_completed_desc = "done placing boxes."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        pallet_size = (0.15, 0.15, 0.02)
        pallet_pose = self.get_random_pose(env, pallet_size)
        env.add_object('pallet/pallet.urdf', pallet_pose, 'fixed')
        for color in ['red', 'blue']:
            box_size = (0.05, 0.05, 0.05)
            box_pose = self.get_random_pose(env, box_size)
            box_id = env.add_object('box/box-template.urdf', box_pose,
                                    color=utils.COLORS[color])
            self.add_goal(objs=[box_id], matches=np.ones((1, 1)), targ_poses=[pallet_pose],
                          replace=False, rotations=True, metric='pose', params=None,
                          step_max_reward=1 / 2,
                          language_goal=self.lang_template.format(color=color))
