import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlockInZoneThenBallInBowl(Task):
    """Put the yellow block in the zone, then the red ball in the bowl."""

    def __init__(self):
        super().__init__()
        self.max_steps = 3
        self.lang_template = "put the block in the zone and then the ball in the bowl"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        zone_size = (0.12, 0.12, 0)
        zone_pose = self.get_random_pose(env, zone_size)
        env.add_object('zone/zone.urdf', zone_pose, 'fixed')

        bowl_size = (0.12, 0.12, 0)
        bowl_pose = self.get_random_pose(env, bowl_size)
        env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed')

        block_size = (0.04, 0.04, 0.04)
        block = env.add_object('block/block.urdf', self.get_random_pose(env, block_size),
                               color=utils.COLORS['yellow'])

        ball_size = (0.04, 0.04, 0.04)
        ball_urdf = self.fill_template('ball/ball-template.urdf', {'DIM': ball_size})
        ball = env.add_object(ball_urdf, self.get_random_pose(env, ball_size), color=utils.COLORS['red'])

        self.add_goal(objs=[block], matches=np.ones((1, 1)), targ_poses=[zone_pose], replace=False,
                      rotations=True, metric='zone', params=[(zone_pose, zone_size)],
                      step_max_reward=1 / 2, language_goal="put the yellow block in the zone")
        self.add_goal(objs=[ball], matches=np.ones((1, 1)), targ_poses=[bowl_pose], replace=False,
                      rotations=False, metric='pose', params=None, step_max_reward=1 / 2,
                      language_goal="put the red ball in the bowl")
