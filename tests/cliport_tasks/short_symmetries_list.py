import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class SymmetriesListShort(Task):
    """Put three boxes in a row; the LLM passed one symmetry for three objects."""

    def __init__(self):
        super().__init__()
        self.max_steps = 6
        self.lang_template = "line up the boxes"
        self.task_completed_desc = "done."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        size = (0.06, 0.04, 0.04)
        urdf = self.fill_template('box/box-template.urdf', {'DIM': size})
        boxes = [env.add_object(urdf, self.get_random_pose(env, size),
                                color=utils.COLORS['orange']) for _ in range(3)]
        row = self.get_random_pose(env, (0.24, 0.06, 0.04))
        targs = [(utils.apply(row, (0, dy, 0.02)), row[1]) for dy in (-0.06, 0, 0.06)]
        # GenSim zips objs with symmetries: this goal is over the first box only.
        self.add_goal(objs=boxes, matches=np.ones((3, 3)), targ_poses=targs, replace=False,
                      rotations=True, metric='pose', params=None, step_max_reward=1,
                      symmetries=[np.pi], language_goal=self.lang_template)
