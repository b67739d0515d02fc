"""A bowl put on a pallet's centre (at the pallet's pose, raised by the pallet's
size hint) and a ball to put in it. The pallet's centre lies inside the bowl's
footprint too: it was taken as starting inside the bowl (a 30 cm pallet in a 12 cm
bowl: no reset), and the ball's target, measured from the bowl as the author
placed it (factask's pallet is taller than the 2 cm hint), lay inside the bowl's
walls. Written here in the style of GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BallInBowlOnPallet(Task):
    """Pick up the red ball and place it into the bowl that sits on the pallet."""

    def __init__(self):
        super().__init__()
        self.max_steps = 5
        self.lang_template = "put the red ball in the elevated bowl"
        self.task_completed_desc = "done placing ball."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        pallet_size = (0.15, 0.15, 0.02)
        pallet_pose = self.get_random_pose(env, pallet_size)
        env.add_object('pallet/pallet.urdf', pallet_pose, 'fixed')

        bowl_pose = (utils.apply(pallet_pose, (0, 0, pallet_size[2])), pallet_pose[1])
        env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed', color=utils.COLORS['green'])

        ball_size = (0.04, 0.04, 0.04)
        ball_urdf = self.fill_template('ball/ball-template.urdf', {'DIM': ball_size})
        ball = env.add_object(ball_urdf, self.get_random_pose(env, ball_size),
                              color=utils.COLORS['red'])
        self.add_goal(objs=[ball], matches=np.ones((1, 1)), targ_poses=[bowl_pose],
                      replace=False, rotations=False, metric='pose', params=None,
                      step_max_reward=1, language_goal=self.lang_template)
