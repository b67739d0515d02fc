import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class InsertTwoEllsIntoFixtures(Task):
    """Insert the red and the blue L-shaped blocks into the fixtures of their colour."""

    def __init__(self):
        super().__init__()
        self.max_steps = 4
        self.lang_template = "put the {color} L shape block in the {color} L shape hole"
        self.task_completed_desc = "done with insertion."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        size = (0.1, 0.1, 0.04)
        colors = ['red', 'blue']
        for color in colors:
            fixture_pose = self.get_random_pose(env, size)
            env.add_object('insertion/fixture.urdf', fixture_pose, 'fixed', color=utils.COLORS[color])

            ell_pose = self.get_random_pose(env, size)
            ell_id = env.add_object('insertion/ell.urdf', ell_pose, color=utils.COLORS[color])

            self.add_goal(objs=[ell_id], matches=np.int32([[1]]), targ_poses=[fixture_pose],
                          replace=False, rotations=True, metric='pose', params=None,
                          step_max_reward=1 / 2, symmetries=[2 * np.pi],
                          language_goal=self.lang_template.format(color=color))
