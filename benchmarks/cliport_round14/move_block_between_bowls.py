import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class MoveBlockBetweenBowls(Task):
    """The green block starts in the gray bowl; move it into the blue bowl."""

    def __init__(self):
        super().__init__()
        self.max_steps = 2
        self.lang_template = "move the green block from the gray bowl to the blue bowl"
        self.task_completed_desc = "done moving the block."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        bowl_size = (0.12, 0.12, 0)
        start_bowl_pose = self.get_random_pose(env, bowl_size)
        env.add_object('bowl/bowl.urdf', start_bowl_pose, 'fixed', color=utils.COLORS['gray'])
        goal_bowl_pose = self.get_random_pose(env, bowl_size)
        env.add_object('bowl/bowl.urdf', goal_bowl_pose, 'fixed', color=utils.COLORS['blue'])

        # Block starts inside the first bowl.
        block_pose = (utils.apply(start_bowl_pose, (0, 0, 0.03)), start_bowl_pose[1])
        block_id = env.add_object('block/block.urdf', block_pose, color=utils.COLORS['green'])

        self.add_goal(objs=[block_id], matches=np.ones((1, 1)), targ_poses=[goal_bowl_pose], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
