"""Two layers of flat boxes in a container: the upper layer's targets stand on
the lower boxes, which rest on the container's 1 cm floor (a target z that
ignored the floor put the upper layer 1 cm into the lower one). Written here in
the style of GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BoxesTwoLayersContainer(Task):
    """Pack four flat boxes into the container in two layers of two."""

    def __init__(self):
        super().__init__()
        self.max_steps = 8
        self.lang_template = "pack the boxes into the container"
        self.task_completed_desc = "done packing."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        container_size = (0.2, 0.12, 0.1)
        container_pose = self.get_random_pose(env, container_size)
        urdf = self.fill_template('container/container-template.urdf',
                                  {'DIM': container_size, 'HALF': np.float32(container_size) / 2})
        env.add_object(urdf, container_pose, 'fixed')
        box_size = (0.08, 0.08, 0.03)
        box_urdf = self.fill_template('box/box-template.urdf', {'DIM': box_size})
        boxes = []
        for color in ['red', 'red', 'blue', 'blue']:
            pose = self.get_random_pose(env, box_size)
            boxes.append(env.add_object(box_urdf, pose, color=utils.COLORS[color]))
        targs = []
        for layer in range(2):
            for side in (-0.045, 0.045):
                pos = utils.apply(container_pose, (side, 0, 0.015 + 0.03 * layer))
                targs.append((pos, container_pose[1]))
        self.add_goal(objs=boxes[:2], matches=np.ones((2, 2)), targ_poses=targs[:2], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=0.5,
                      language_goal="put the red boxes at the bottom of the container")
        self.add_goal(objs=boxes[2:], matches=np.ones((2, 2)), targ_poses=targs[2:], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=0.5,
                      language_goal="put the blue boxes on top of the red boxes")
