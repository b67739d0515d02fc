import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BallsIntoOneBowl(Task):
    """Put all three balls into the green bowl."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.pos_eps = 0.05
        self.lang_template = "put the balls in the green bowl"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        bowl_pose = self.get_random_pose(env, (0.12, 0.12, 0))
        env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed', color=utils.COLORS['green'])
        urdf = self.fill_template('sphere/sphere-template.urdf', {'DIM': (0.04, 0.04, 0.04)})
        balls = [env.add_object(urdf, self.get_random_pose(env, (0.04, 0.04, 0.04)),
                                color=utils.COLORS[c]) for c in ['red', 'yellow', 'blue']]
        self.add_goal(objs=balls, matches=np.ones((3, 1)), targ_poses=[bowl_pose], replace=True,
                      rotations=False, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
