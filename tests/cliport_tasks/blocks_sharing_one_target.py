import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BlocksSharingOneTarget(Task):
    """Put all three blocks on the red zone (one target, replace=True)."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "put the blocks on the red zone"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        zone_pose = self.get_random_pose(env, (0.12, 0.12, 0))
        env.add_object('zone/zone.urdf', zone_pose, 'fixed', color=utils.COLORS['red'])
        blocks = [env.add_object('block/block.urdf', self.get_random_pose(env, (0.04, 0.04, 0.04)),
                                 color=utils.COLORS['blue']) for _ in range(3)]
        self.add_goal(objs=blocks, matches=np.ones((3, 1)), targ_poses=[zone_pose], replace=True,
                      rotations=False, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
