"""A container is moved into a zone, then a box is put "in the container" with its
target at the zone's centre (z 0): the box rests on the moved container's floor, not on
its rim (the target was read as 8.5 cm high and every episode failed)."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class ContainerToZoneThenBox(Task):
    """Move the container into the green zone, then put the box inside the container."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "put the box in the container on the green zone"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        zone_size = (0.2, 0.2, 0)
        zone_pose = self.get_random_pose(env, zone_size)
        env.add_object('zone/zone.urdf', zone_pose, 'fixed', color=utils.COLORS['green'])

        container_size = (0.12, 0.12, 0.06)
        container_template = 'container/container-template.urdf'
        half = np.float32(container_size) / 2
        replace = {'DIM': container_size, 'HALF': half}
        container_urdf = self.fill_template(container_template, replace)
        container_pose = self.get_random_pose(env, container_size)
        container_id = env.add_object(container_urdf, container_pose)

        box_size = (0.05, 0.05, 0.05)
        box_urdf = self.fill_template('box/box-template.urdf', {'DIM': box_size})
        box_pose = self.get_random_pose(env, box_size)
        box_id = env.add_object(box_urdf, box_pose, color=utils.COLORS['blue'])

        self.add_goal(objs=[container_id], matches=np.ones((1, 1)), targ_poses=[zone_pose],
                      replace=False, rotations=True, metric='zone',
                      params=[(zone_pose, zone_size)], step_max_reward=1 / 2,
                      language_goal="move the container into the green zone")
        self.add_goal(objs=[box_id], matches=np.ones((1, 1)), targ_poses=[zone_pose],
                      replace=False, rotations=True, metric='pose', params=None,
                      step_max_reward=1 / 2, language_goal="put the box in the container")
