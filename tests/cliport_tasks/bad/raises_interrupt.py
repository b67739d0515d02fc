"""A reset that raises KeyboardInterrupt itself (issue 37, item 4)."""

from cliport.tasks.task import Task


class RaisesInterrupt(Task):
    def reset(self, env):
        super().reset(env)
        raise KeyboardInterrupt
