import numpy as np
from cliport.tasks.task import Task
from cliport.utils import utils

N_BLOCKS = 5
RADIUS = 0.1


def ring_poses(center_pose, n, radius):
    """Poses on a ring around center, each turned to face outwards."""
    poses = []
    for i in range(n):
        theta = 2 * np.pi * i / n
        pos = utils.apply(center_pose, (radius * np.cos(theta), radius * np.sin(theta), 0.02))
        rot = utils.eulerXYZ_to_quatXYZW((0, 0, theta))
        poses.append((pos, rot))
    return poses


class CircleOfBlocksAroundBowl(Task):
    """Place five blocks in a ring around the bowl."""

    def __init__(self):
        super().__init__()
        self.max_steps = N_BLOCKS + 2
        self.lang_template = "arrange the blocks in a circle around the bowl"
        self.task_completed_desc = "done arranging."
        self.additional_reset()

    def reset(self, env):
        super().reset(env)
        bowl_pose = self.get_random_pose(env, (0.34, 0.34, 0))
        env.add_object('bowl/bowl.urdf', bowl_pose, 'fixed')
        colors, _ = utils.get_colors(self.mode, n_colors=N_BLOCKS)
        blocks = []
        for i in range(N_BLOCKS):
            pose = self.get_random_pose(env, (0.04, 0.04, 0.04))
            blocks.append(env.add_object('stacking/block.urdf', pose, color=colors[i]))
        targs = ring_poses(bowl_pose, N_BLOCKS, RADIUS)
        self.add_goal(objs=blocks, matches=np.ones((N_BLOCKS, N_BLOCKS)), targ_poses=targs,
                      replace=False, rotations=False, metric='pose', params=None, step_max_reward=1,
                      language_goal=self.lang_template)
