import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlockOnCylinderOnPallet(Task):
    """Stand the cylinder on the pallet and put the block on the cylinder: both
    targets at the pallet's pose, the block's at a height the author guessed. Was
    refused at reset."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "put the cylinder on the pallet and the block on the cylinder"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        pallet_size = (0.12, 0.12, 0.02)
        pallet_pose = self.get_random_pose(env, pallet_size)
        env.add_object('pallet/pallet.urdf', pallet_pose, 'fixed')
        cylinder_template = 'cylinder/cylinder-template.urdf'
        replace = {'DIM': (0.04, 0.04, 0.06), 'HALF': (0.02, 0.02, 0.03)}
        urdf = self.fill_template(cylinder_template, replace)
        cylinder_id = env.add_object(urdf, self.get_random_pose(env, (0.04, 0.04, 0.06)),
                                     color=utils.COLORS['green'])
        block_id = env.add_object('stacking/block.urdf',
                                  self.get_random_pose(env, (0.04, 0.04, 0.04)),
                                  color=utils.COLORS['red'])
        self.add_goal(objs=[cylinder_id], matches=np.ones((1, 1)), targ_poses=[pallet_pose],
                      replace=False, rotations=True, metric='pose', params=None,
                      step_max_reward=1 / 2, language_goal=self.lang_template)
        block_place = utils.apply(pallet_pose, (0, 0, 0.05))
        self.add_goal(objs=[block_id], matches=np.ones((1, 1)),
                      targ_poses=[(block_place, pallet_pose[1])], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 2,
                      language_goal=self.lang_template)
