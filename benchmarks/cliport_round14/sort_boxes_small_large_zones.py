import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class SortBoxesSmallLargeZones(Task):
    """Put the small boxes in the blue zone and the large boxes in the red zone."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "put the {size} boxes in the {color} zone"
        self.task_completed_desc = "done sorting boxes by size."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        zone_size = (0.15, 0.15, 0)
        groups = [('small', 'blue', (0.03, 0.03, 0.03)), ('large', 'red', (0.06, 0.06, 0.05))]

        for size_name, zone_color, box_size in groups:
            zone_pose = self.get_random_pose(env, zone_size)
            env.add_object('zone/zone.urdf', zone_pose, 'fixed', color=utils.COLORS[zone_color])

            box_urdf = self.fill_template('box/box-template.urdf', {'DIM': box_size})
            boxes = []
            for _ in range(2):
                pose = self.get_random_pose(env, box_size)
                boxes.append(env.add_object(box_urdf, pose, color=utils.COLORS['white']))

            self.add_goal(objs=boxes, matches=np.ones((2, 1)), targ_poses=[zone_pose], replace=True,
                          rotations=True, metric='zone', params=[(zone_pose, zone_size)],
                          step_max_reward=1 / 2,
                          language_goal=self.lang_template.format(size=size_name, color=zone_color))
