"""The registry of top-level library tasks.

Every task is a builder that declares variables, instantiates templates from
:mod:`factask.library.templates` and composes them (see
:mod:`factask.library.builders`). Names follow GenSim's task list where a task
matches one of its entries.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable
from dataclasses import dataclass, field

from factask.graph import FactaskError, TaskGraph

# Importing the catalogue modules registers their builders.
from factask.library import (  # noqa: F401
    catalog_arranging,
    catalog_articulated,
    catalog_deformable,
    catalog_doors,
    catalog_gensim_insertion,
    catalog_gensim_layers,
    catalog_gensim_lines,
    catalog_gensim_matching,
    catalog_gensim_packing,
    catalog_gensim_receptacles,
    catalog_gensim_sorting,
    catalog_gensim_stacking,
    catalog_placing,
    catalog_shelves,
    catalog_stacking,
    catalog_structures,
    catalog_switches,
)
from factask.library.builders import BUILDERS
from factask.library.tags import graph_tags, task_tags

#: Task name -> builder returning a fresh, validated graph.
#: By name as a reader sorts (case-insensitive): the 192 list spells one name with a
#: capital (``Four-corner-pyramid-challenge``), which a plain sort put first.
TASKS: dict[str, Callable[[], TaskGraph]] = dict(
    sorted(BUILDERS.items(), key=lambda item: (item[0].casefold(), item[0])))


class UnknownTaskError(FactaskError, KeyError):
    """A task name that the library does not have."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.suggestions = close_task_names(name)
        hint = f"; did you mean {', '.join(self.suggestions)}?" if self.suggestions else ""
        super().__init__(f"unknown library task {name!r}{hint} (see `factask list`)")

    def __str__(self) -> str:  # KeyError would quote the message
        return str(self.args[0])


@dataclass(frozen=True)
class TaskInfo:
    """Summary of one library task (for listings)."""

    name: str
    description: str
    n_variables: int
    n_factors: int
    templates: tuple[str, ...] = field(default_factory=tuple)
    n_movable: int = 0
    tags: tuple[str, ...] = field(default_factory=tuple)

    def to_dict(self) -> dict[str, object]:
        return {
            "name": self.name,
            "description": self.description,
            "n_variables": self.n_variables,
            "n_factors": self.n_factors,
            "n_movable": self.n_movable,
            "templates": list(self.templates),
            "tags": list(self.tags),
        }


def task_names() -> list[str]:
    """Names of every library task, sorted."""
    return list(TASKS)


def close_task_names(name: str, n: int = 5) -> list[str]:
    """Library task names close to ``name`` (for "did you mean")."""
    return difflib.get_close_matches(name, TASKS, n=n, cutoff=0.5)


def get_task(name: str) -> TaskGraph:
    """A fresh, validated graph of library task ``name``.

    Raises:
        UnknownTaskError: no such task (the message suggests close names).
    """
    try:
        builder = TASKS[name]
    except KeyError:
        raise UnknownTaskError(name) from None
    return builder().ensure_valid()


def templates_used(graph: TaskGraph) -> tuple[str, ...]:
    """Templates the graph's factors came from, in first-use order."""
    return tuple(dict.fromkeys(f.template for f in graph.factors if f.template))


def task_info(graph: TaskGraph) -> TaskInfo:
    """The :class:`TaskInfo` of a graph."""
    return TaskInfo(
        name=graph.name,
        description=graph.description,
        n_variables=len(graph.variables),
        n_factors=len(graph.factors),
        templates=templates_used(graph),
        n_movable=graph.movable_object_count(),
        tags=task_tags(graph.name, graph) if graph.name in TASKS else graph_tags(graph),
    )


def list_tasks() -> list[TaskInfo]:
    """A :class:`TaskInfo` for every library task, sorted by name."""
    return [task_info(get_task(n)) for n in TASKS]
