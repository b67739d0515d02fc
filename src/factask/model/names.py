"""Identifier rules for variables, factors, templates and tasks."""

from __future__ import annotations

from typing import Annotated

from pydantic import AfterValidator, StringConstraints

#: Separator between a variable's name and an instance index (``blocks__2``).
INSTANCE_SEPARATOR = "__"

#: Pattern of variable, factor, slot and template names: snake_case identifiers.
#: A double underscore is reserved (it separates a variable from an instance index).
NAME_PATTERN = r"^[a-z][a-z0-9_]{0,63}$"
#: Pattern of task names: kebab-case as in GenSim's task list (snake_case accepted).
TASK_NAME_PATTERN = r"^[a-z0-9][a-z0-9_-]{0,99}$"



def _no_double_underscore(value: str) -> str:
    if INSTANCE_SEPARATOR in value:
        raise ValueError(f"name {value!r} contains '__', which is reserved for instance "
                         "names (blocks__2); use single underscores")
    return value


Name = Annotated[
    str, StringConstraints(pattern=NAME_PATTERN), AfterValidator(_no_double_underscore)
]
TaskName = Annotated[str, StringConstraints(pattern=TASK_NAME_PATTERN)]


def instance_names(variable: str, count: int) -> list[str]:
    """Names of the objects a variable stands for: itself, or ``name__i`` if count > 1."""
    if count == 1:
        return [variable]
    return [f"{variable}{INSTANCE_SEPARATOR}{i}" for i in range(count)]
