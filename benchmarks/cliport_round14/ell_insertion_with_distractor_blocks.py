import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class EllInsertionWithDistractorBlocks(Task):
    """Insert the L-shaped block into its fixture; some blocks lie around as distractors."""

    def __init__(self):
        super().__init__()
        self.max_steps = 3
        self.lang_template = "put the L shape block in the L shape hole"
        self.task_completed_desc = "done with insertion."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        size = (0.1, 0.1, 0.04)
        fixture_pose = self.get_random_pose(env, size)
        env.add_object('insertion/fixture.urdf', fixture_pose, 'fixed')

        ell_pose = self.get_random_pose(env, size)
        ell_id = env.add_object('insertion/ell.urdf', ell_pose)

        # Distractor blocks.
        block_size = (0.04, 0.04, 0.04)
        for color in ['green', 'yellow', 'purple']:
            env.add_object('block/block.urdf', self.get_random_pose(env, block_size),
                           color=utils.COLORS[color])

        self.add_goal(objs=[ell_id], matches=np.int32([[1]]), targ_poses=[fixture_pose], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      symmetries=[2 * np.pi], language_goal=self.lang_template)
