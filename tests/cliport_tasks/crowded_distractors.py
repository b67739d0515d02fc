"""Two red blocks into a brown box among twenty grey distractor blocks drawn with
``get_random_pose`` in a loop: the distractors start where the seed's draw put
them, some closer to each other than the gap factask's own sampling keeps.
Written here in the style of GenSim's generated tasks."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class CrowdedDistractors(Task):
    """Put the red blocks in the brown box."""

    def __init__(self):
        super().__init__()
        self.max_steps = 10
        self.lang_template = "put the red blocks in the brown box"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        box_size = self.get_random_size(0.15, 0.2, 0.15, 0.2, 0.05, 0.05)
        box_pose = self.get_random_pose(env, box_size)
        half = (box_size[0] / 2, box_size[1] / 2, box_size[2] / 2)
        container = self.fill_template("container/container-template.urdf",
                                       {"DIM": box_size, "HALF": half})
        env.add_object(container, box_pose, "fixed", color=utils.COLORS["brown"])
        reds = []
        for _ in range(2):
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            reds.append(env.add_object("stacking/block.urdf", pose, color=utils.COLORS["red"]))
        n = 0
        while n < 20:
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            if pose[0] is None:
                continue
            env.add_object("stacking/block.urdf", pose, color=utils.COLORS["gray"])
            n += 1
        self.add_goal(objs=reds, matches=np.ones((2, 1)), targ_poses=[box_pose], replace=True,
                      rotations=False, metric="zone", params=[(box_pose, box_size)],
                      step_max_reward=1, language_goal=self.lang_template)
