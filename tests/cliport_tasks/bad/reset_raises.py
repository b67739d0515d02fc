"""A task whose reset divides by zero."""

from cliport.tasks.task import Task


class ResetRaises(Task):
    def reset(self, env):
        super().reset(env)
        env.add_object("block/block.urdf", self.get_random_pose(env, (0.04, 0.04, 0.04)))
        n_blocks = 0
        share = 1 / n_blocks
        return share
