"""Run GenSim/CLIPort ``Task`` classes unchanged and import them as factask graphs.

A task file written against CLIPort's API (``from cliport.tasks.task import Task``,
``from cliport.utils import utils``, ``import pybullet as p``) is executed with
factask's stand-ins for those modules; its ``reset(env)`` runs against a
recording environment, and the objects and goals it set up become a
:class:`~factask.graph.taskgraph.TaskGraph`. **Task files are code and are
executed**: import only files you trust (the batch command isolates each file in
a child process with a time limit). See docs/compat.md.
"""

from importlib import resources
from pathlib import Path

from factask.compat.cliport.errors import CliportImportError, Unsupported
from factask.compat.cliport.loader import (
    ImportResult,
    cliport_aliases,
    import_cliport,
    load_task_class,
)
from factask.compat.cliport.scoring import RavensGoal, RavensScore, ravens_reward


def example_tasks_dir() -> Path:
    """The CLIPort original task files shipped with factask (Apache-2.0, unchanged;
    ``factask/data/cliport_tasks``): 18 files, 39 task classes to import and run."""
    return Path(str(resources.files("factask") / "data" / "cliport_tasks"))


__all__ = [
    "CliportImportError", "ImportResult", "RavensGoal", "RavensScore", "Unsupported",
    "cliport_aliases", "example_tasks_dir", "import_cliport", "load_task_class",
    "ravens_reward",
]
