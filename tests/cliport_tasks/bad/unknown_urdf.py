"""A task using an asset factask has no mapping for."""

from cliport.tasks.task import Task


class UnknownUrdf(Task):
    def reset(self, env):
        super().reset(env)
        env.add_object("teapot/teapot.urdf", ((0.5, 0.0, 0.05), (0, 0, 0, 1)))
