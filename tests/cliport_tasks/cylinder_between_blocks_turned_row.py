import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class MixedHeightRotatedRow(Task):
    """A row of a block, a tall cylinder and a block, the row turned about 45 degrees."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "make a row: block, cylinder, block"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        row_pose = self.get_random_pose(env, (0.2, 0.06, 0.1))
        theta = np.pi / 4 + np.random.uniform(-0.1, 0.1)
        row_pose = (row_pose[0], utils.eulerXYZ_to_quatXYZW((0, 0, theta)))
        block = (0.04, 0.04, 0.04)
        b1 = env.add_object('block/block.urdf', self.get_random_pose(env, block),
                            color=utils.COLORS['red'])
        b2 = env.add_object('block/block.urdf', self.get_random_pose(env, block),
                            color=utils.COLORS['red'])
        csize = (0.04, 0.04, 0.1)
        curdf = self.fill_template('cylinder/cylinder-template.urdf',
                                   {'DIM': csize, 'HALF': (0.02, 0.02, 0.05)})
        cyl = env.add_object(curdf, self.get_random_pose(env, csize), color=utils.COLORS['yellow'])
        ends = [(utils.apply(row_pose, (dx, 0, 0.02)), row_pose[1]) for dx in (-0.05, 0.05)]
        self.add_goal(objs=[b1, b2], matches=np.ones((2, 2)), targ_poses=ends,
                      replace=False, rotations=True, metric='pose', params=None,
                      step_max_reward=2 / 3,
                      language_goal="put the red blocks at the ends of the row")
        # The cylinder's author z is its centre (5 cm): higher than the blocks' targets,
        # but it stands on the table between them.
        middle = (utils.apply(row_pose, (0, 0, 0.05)), row_pose[1])
        self.add_goal(objs=[cyl], matches=np.ones((1, 1)), targ_poses=[middle],
                      replace=False, rotations=False, metric='pose', params=None,
                      step_max_reward=1 / 3, language_goal="stand the cylinder in the middle")
