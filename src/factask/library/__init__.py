"""The library: reusable subtask templates and top-level tasks built from them.

Depends on the graph model only (no MuJoCo, no LLM).
"""

from factask.library.tasks import (
    TASKS,
    TaskInfo,
    UnknownTaskError,
    get_task,
    list_tasks,
    task_info,
    task_names,
    templates_used,
)
from factask.library.templates import TEMPLATES, get_template, match_pairs, template_names

__all__ = [
    "TASKS", "TEMPLATES", "TaskInfo", "UnknownTaskError", "get_task", "get_template",
    "list_tasks", "match_pairs", "task_info", "task_names", "template_names", "templates_used",
]
