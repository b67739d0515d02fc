"""A task whose error message looks like Rich markup ("[/tmp/a]")."""

from cliport.tasks.task import Task


class MarkupError(Task):
    def reset(self, env):
        super().reset(env)
        raise ValueError("asset folder [/tmp/a] is missing [bold]")
