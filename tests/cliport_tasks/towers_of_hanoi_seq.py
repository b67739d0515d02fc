"""Ravens' towers-of-hanoi-seq: the same disks move several times (goals in a loop)."""

import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils


class TowersOfHanoiSeq(Task):
    def __init__(self):
        super().__init__()
        self.max_steps = 14
        self.lang_template = "move the {obj} ring to the {loc}"

    def reset(self, env):
        super().reset(env)
        base_pose = ((0.5, 0.0, 0.005), (0, 0, 0, 1))
        env.add_object("hanoi/stand.urdf", base_pose, "fixed")
        rod_pos = ((0, -0.12, 0.03), (0, 0, 0.03), (0, 0.12, 0.03))
        rod_names = ("lighter brown side", "middle of the stand", "darker brown side")
        n_disks = 3
        disks = []
        disk_names = ["green", "blue", "red"]
        for i in range(n_disks):
            pos = utils.apply(base_pose, rod_pos[0])
            z = 0.015 * (n_disks - i - 2)
            pos = (pos[0], pos[1], pos[2] + z)
            disks.append(env.add_object(f"hanoi/disk{i}.urdf", (pos, base_pose[1]),
                                        color=disk_names[i]))
        steps = utils.solve_hanoi_all(n_disks)
        for disk_idx, _, to_rod in steps:
            targ = utils.apply(base_pose, rod_pos[to_rod])
            targ = ((targ[0], targ[1], 0.015 + 0.01 * (n_disks - disk_idx)), (0, 0, 0, 1))
            self.add_goal(objs=[disks[disk_idx]], matches=np.int32([[1]]), targ_poses=[targ],
                          replace=False, rotations=True, metric="pose", params=None,
                          step_max_reward=1 / len(steps),
                          language_goal=self.lang_template.format(obj=disk_names[disk_idx],
                                                                  loc=rod_names[to_rod]))
