"""A task with a rope (deformable): unsupported."""

from cliport.tasks.task import Task


class RopeTask(Task):
    def reset(self, env):
        super().reset(env)
        self.make_ropes(env, corners=((0.4, 0.0, 0.0), (0.6, 0.0, 0.0)))
