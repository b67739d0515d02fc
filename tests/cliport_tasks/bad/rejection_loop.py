"""A GenSim-style rejection loop whose test never passes (blocks 2 m apart on a
1 m table), its draw wrapped in a bare ``except:`` that retries on any error."""

import numpy as np
from cliport.tasks.task import Task


class RejectionLoop(Task):
    def reset(self, env):
        super().reset(env)
        poses = []
        while len(poses) < 3:
            try:
                pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            except:  # noqa: E722 -- the habit under test
                continue
            if all(np.linalg.norm(np.array(pose[0][:2]) - np.array(q[0][:2])) > 2.0
                   for q in poses):
                poses.append(pose)
        blocks = [env.add_object("block/block.urdf", pose) for pose in poses]
        self.add_goal(objs=blocks, matches=np.ones((3, 3)), targ_poses=poses, replace=False,
                      rotations=True, metric="pose", params=None, step_max_reward=1)
