import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class AlternatingColorTower(Task):
    """Build a tower of four blocks alternating red and white, on a green zone."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "build a tower alternating red and white blocks on the zone"
        self.task_completed_desc = "done building the tower."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        zone_size = (0.12, 0.12, 0)
        zone_pose = self.get_random_pose(env, zone_size)
        env.add_object('zone/zone.urdf', zone_pose, 'fixed', color=utils.COLORS['green'])

        block_size = (0.04, 0.04, 0.04)
        colors = ['red', 'white', 'red', 'white']
        blocks = []
        for color in colors:
            block_pose = self.get_random_pose(env, block_size)
            blocks.append(env.add_object('stacking/block.urdf', block_pose, color=utils.COLORS[color]))

        # Tower positions (each block goes on top of the previous one).
        for i in range(len(blocks)):
            targ_pose = (utils.apply(zone_pose, (0, 0, 0.02 + 0.045 * i)), zone_pose[1])
            self.add_goal(objs=[blocks[i]], matches=np.ones((1, 1)), targ_poses=[targ_pose],
                          replace=False, rotations=True, metric='pose', params=None,
                          step_max_reward=1 / 4,
                          language_goal=f"place the {colors[i]} block on level {i + 1} of the tower")
