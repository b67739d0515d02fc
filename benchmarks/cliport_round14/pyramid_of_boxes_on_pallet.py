import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class PyramidOfBoxesOnPallet(Task):
    """Build a three-layer pyramid of six boxes on the pallet."""

    def __init__(self):
        super().__init__()
        self.max_steps = 12
        self.lang_template = "build the {layer} layer of the box pyramid on the pallet"
        self.task_completed_desc = "done building the pyramid."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        # Add pallet.
        pallet_size = (0.3, 0.25, 0.0375)
        pallet_pose = self.get_random_pose(env, pallet_size)
        env.add_object('pallet/pallet.urdf', pallet_pose, 'fixed')

        # Add boxes.
        box_size = (0.05, 0.05, 0.05)
        box_urdf = self.fill_template('box/box-template.urdf', {'DIM': box_size})
        boxes = []
        for _ in range(6):
            box_pose = self.get_random_pose(env, box_size)
            boxes.append(env.add_object(box_urdf, box_pose, color=utils.COLORS['brown']))

        # Pyramid positions relative to the pallet.
        place_pos = [(0, -0.055, 0.06), (0, 0, 0.06), (0, 0.055, 0.06),
                     (0, -0.0275, 0.11), (0, 0.0275, 0.11),
                     (0, 0, 0.16)]
        targs = [(utils.apply(pallet_pose, i), pallet_pose[1]) for i in place_pos]

        # Bottom layer.
        self.add_goal(objs=boxes[:3], matches=np.ones((3, 3)), targ_poses=targs[:3], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 2,
                      language_goal=self.lang_template.format(layer='bottom'))
        # Middle layer.
        self.add_goal(objs=boxes[3:5], matches=np.ones((2, 2)), targ_poses=targs[3:5], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 3,
                      language_goal=self.lang_template.format(layer='middle'))
        # Top layer.
        self.add_goal(objs=boxes[5:], matches=np.ones((1, 1)), targ_poses=targs[5:], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 6,
                      language_goal=self.lang_template.format(layer='top'))
