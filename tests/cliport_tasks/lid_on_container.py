import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class BoxLidOnContainer(Task):
    """Cover a small container with a flat box as a lid (too wide to go in)."""

    def __init__(self):
        super().__init__()
        self.max_steps = 3
        self.lang_template = "put the lid on the container"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        csize = (0.1, 0.1, 0.05)
        cpose = self.get_random_pose(env, csize)
        urdf = self.fill_template('container/container-template.urdf',
                                  {'DIM': csize, 'HALF': (0.05, 0.05, 0.025)})
        env.add_object(urdf, cpose, 'fixed')
        lid_size = (0.12, 0.12, 0.01)
        lid = env.add_object(self.fill_template('box/box-template.urdf', {'DIM': lid_size}),
                             self.get_random_pose(env, lid_size), color=utils.COLORS['red'])
        targ = ((cpose[0][0], cpose[0][1], csize[2] + lid_size[2] / 2), cpose[1])
        self.add_goal(objs=[lid], matches=np.ones((1, 1)), targ_poses=[targ], replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      symmetries=[np.pi / 2], language_goal=self.lang_template)
