"""Insert an ell into a fixture the task places in the air, tilted in roll and pitch
(BlockInsertionSixDof's fixture): the target is the fixture's own pose."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class TiltedFixture(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 3
        self.pos_eps = 0.02
        self.lang_template = "put the l shape block in the l shape hole"

    def reset(self, env):
        super().reset(env)
        size = (0.1, 0.1, 0.04)
        block = env.add_object("insertion/ell.urdf", self.get_random_pose(env, size))
        pos, _ = self.get_random_pose(env, size)
        rot = utils.eulerXYZ_to_quatXYZW((0.4, -0.3, 1.2))
        fixture_pose = ((pos[0], pos[1], 0.02 + 0.08), rot)
        env.add_object("insertion/fixture.urdf", fixture_pose, "fixed")
        self.goals.append(([(block, (2 * np.pi, None))], np.int32([[1]]), [fixture_pose],
                           False, True, "pose", None, 1))
        self.lang_goals.append(self.lang_template)
