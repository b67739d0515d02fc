"""Four ell fixtures an author put 10 cm apart in a row (Ravens' fixture frame is
0.10 x 0.105): factask's fixtures must not reach into each other's hollows."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class FixturesTenCmApart(Task):
    """Insert each ell into the fixture of its colour, left to right."""

    def __init__(self):
        super().__init__()
        self.max_steps = 20
        self.lang_template = "put the {color} L shape block in the L shape hole"
        self.task_completed_desc = "done with insertion."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        colors = ['red', 'blue', 'green', 'yellow']
        fixture_poses = []
        for i, color in enumerate(colors):
            pose = ((0.35 + 0.1 * i, -0.25, 0.02), utils.eulerXYZ_to_quatXYZW((0, 0, np.pi / 2)))
            env.add_object('insertion/fixture.urdf', pose, 'fixed', color=utils.COLORS[color])
            fixture_poses.append(pose)
        ells = [env.add_object('insertion/ell.urdf', self.get_random_pose(env, (0.04, 0.04, 0.04)),
                               color=utils.COLORS[c]) for c in colors]
        for i, ell in enumerate(ells):
            self.add_goal(objs=[ell], matches=np.int32([[1]]), targ_poses=[fixture_poses[i]],
                          replace=False, rotations=True, metric='pose', params=None,
                          step_max_reward=1 / len(ells),
                          language_goal=self.lang_template.format(color=colors[i]))
