import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class CylindersIntoMatchingBowls(Task):
    """Place each cylinder into the bowl of the same colour; one extra bowl is a distractor."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "put the {color} cylinder in the {color} bowl"
        self.task_completed_desc = "done placing cylinders in bowls."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)

        colors = ['red', 'green', 'blue']
        bowl_size = (0.12, 0.12, 0)
        cylinder_size = (0.04, 0.04, 0.04)
        cylinder_urdf = self.fill_template('cylinder/cylinder-template.urdf',
                                           {'DIM': cylinder_size, 'HALF': np.float32(cylinder_size) / 2})

        bowl_poses = []
        for color in colors:
            bowl_pose = self.get_random_pose(env, bowl_size)
            env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed', color=utils.COLORS[color])
            bowl_poses.append(bowl_pose)

        # Distractor bowl.
        env.add_object('bowl/bowl.urdf', self.get_random_pose(env, bowl_size), 'fixed',
                       color=utils.COLORS['yellow'])

        cylinders = []
        for color in colors:
            pose = self.get_random_pose(env, cylinder_size)
            cylinders.append(env.add_object(cylinder_urdf, pose, color=utils.COLORS[color]))

        for i in range(len(colors)):
            self.add_goal(objs=[cylinders[i]], matches=np.ones((1, 1)), targ_poses=[bowl_poses[i]],
                          replace=False, rotations=False, metric='pose', params=None,
                          step_max_reward=1 / 3, language_goal=self.lang_template.format(color=colors[i]))
