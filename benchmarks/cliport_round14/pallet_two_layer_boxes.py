import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class PalletTwoLayerBoxes(Task):
    """Palletize six boxes: four in the bottom layer, then two on top."""

    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "stack the boxes on the pallet in two layers"
        self.task_completed_desc = "done palletizing."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        pallet_pose = ((0.5, 0.25, 0.02), utils.eulerXYZ_to_quatXYZW((0, 0, 0)))
        env.add_object('pallet/pallet.urdf', pallet_pose, 'fixed')

        box_size = (0.06, 0.06, 0.05)
        box_urdf = self.fill_template('box/box-template.urdf', {'DIM': box_size})
        boxes = []
        for _ in range(6):
            pose = self.get_random_pose(env, box_size)
            boxes.append(env.add_object(box_urdf, pose, color=utils.COLORS['brown']))

        bottom = [(-0.035, -0.035, 0.045), (-0.035, 0.035, 0.045), (0.035, -0.035, 0.045), (0.035, 0.035, 0.045)]
        top = [(0, -0.035, 0.095), (0, 0.035, 0.095)]
        bottom_targs = [(utils.apply(pallet_pose, o), pallet_pose[1]) for o in bottom]
        top_targs = [(utils.apply(pallet_pose, o), pallet_pose[1]) for o in top]

        self.add_goal(objs=boxes[:4], matches=np.ones((4, 4)), targ_poses=bottom_targs, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=2 / 3,
                      language_goal="place four boxes on the pallet as the bottom layer")
        self.add_goal(objs=boxes[4:], matches=np.ones((2, 2)), targ_poses=top_targs, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1 / 3,
                      language_goal="place the remaining boxes on top")
