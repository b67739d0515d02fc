"""A reset that ends its process with exit status 0 and no result (issue 37, item 3)."""

import os

from cliport.tasks.task import Task


class ExitsProcess(Task):
    def reset(self, env):
        super().reset(env)
        os._exit(0)
