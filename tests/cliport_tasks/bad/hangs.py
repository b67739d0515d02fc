"""A task whose reset never returns (for the batch time limit)."""

from cliport.tasks.task import Task


class Hangs(Task):
    def reset(self, env):
        super().reset(env)
        while True:
            pass
