import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class RandomSizeBoxesInContainer(Task):
    """Pack three boxes of random sizes into a container."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "pack all the boxes into the container"
        self.task_completed_desc = "done packing boxes."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        # Add container.
        container_size = (0.25, 0.25, 0.05)
        container_pose = self.get_random_pose(env, container_size)
        container_urdf = self.fill_template('container/container-template.urdf',
                                            {'DIM': container_size,
                                             'HALF': (container_size[0] / 2, container_size[1] / 2,
                                                      container_size[2] / 2)})
        env.add_object(container_urdf, container_pose, 'fixed')

        # Add boxes of random size.
        boxes = []
        for _ in range(3):
            box_size = self.get_random_size(0.03, 0.06, 0.03, 0.06, 0.03, 0.05)
            box_pose = self.get_random_pose(env, box_size)
            box_urdf = self.fill_template('box/box-template.urdf', {'DIM': box_size})
            boxes.append(env.add_object(box_urdf, box_pose, color=utils.COLORS['orange']))

        self.add_goal(objs=boxes, matches=np.ones((3, 1)), targ_poses=[container_pose], replace=True,
                      rotations=True, metric='zone', params=[(container_pose, container_size)],
                      step_max_reward=1, language_goal=self.lang_template)
