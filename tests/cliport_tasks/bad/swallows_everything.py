"""A reset whose loops catch every exception, BaseException included: no stop raised
into it can end it (issue 37, item 1)."""

from cliport.tasks.task import Task


class SwallowsEverything(Task):
    def reset(self, env):
        super().reset(env)
        while True:
            try:
                while True:
                    pass
            except BaseException:  # the habit under test
                pass
