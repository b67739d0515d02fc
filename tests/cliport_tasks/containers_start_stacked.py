"""Containers that start stacked, each on the rim of the one below (as wide as it, so
not inside it): factask cannot rest an object on a rim, so each starts at a random free
spot (was: the second container placed inside the first, refused at reset). Each is
then unstacked to a spot of its own and gets a block of its colour. Written here in
the style of GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class ContainerBlockSorting(Task):
    """Unstack the containers, then put each block into the container of its colour."""

    def __init__(self):
        super().__init__()
        self.max_steps = 12
        self.lang_template = "put the {} block in the {} container"
        self.task_completed_desc = "done sorting."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        names = ['red', 'blue', 'green']
        size = (0.1, 0.1, 0.04)
        base_pose = self.get_random_pose(env, size)
        containers = []
        for i, name in enumerate(names):
            urdf = self.fill_template('container/container-template.urdf',
                                      {'DIM': size, 'HALF': (0.05, 0.05, 0.02)})
            pose = (utils.apply(base_pose, (0, 0, i * size[2])), base_pose[1])
            containers.append(env.add_object(urdf, pose, color=utils.COLORS[name]))
        blocks = []
        for name in names:
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            blocks.append(env.add_object('block/block.urdf', pose, color=utils.COLORS[name]))
        spots = [self.get_random_pose(env, size) for _ in names]
        for i in reversed(range(3)):
            self.add_goal(objs=[containers[i]], matches=np.ones((1, 1)), targ_poses=[spots[i]],
                          replace=False, rotations=False, metric='pose', params=None,
                          step_max_reward=1 / 6,
                          language_goal=f"move the {names[i]} container onto the table")
        for i in range(3):
            self.add_goal(objs=[blocks[i]], matches=np.ones((1, 1)), targ_poses=[spots[i]],
                          replace=False, rotations=False, metric='pose', params=None,
                          step_max_reward=1 / 6,
                          language_goal=self.lang_template.format(names[i], names[i]))
