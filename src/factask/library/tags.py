"""Tags of library tasks, and the subtask-reuse figure.

Most tags are read off the graph, so they cannot drift from what a task does:
its family (declared at registration), how many movable objects it has, which
relations its goals use, whether it is sequenced, has milestones, distractors or
objects that start stacked or inside, whether it moves a receptacle, where it
comes from (Ravens/CLIPort, GenSim or factask's own) and whether its tallest
structure needs the arm's reach.
Authors add tags the graph cannot tell with ``register(..., tags=[...])``.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from functools import cache
from importlib import resources

from factask.graph import TaskGraph
from factask.library.builders import EXTRA_TAGS, FAMILIES
from factask.library.templates import TEMPLATES
from factask.vocabulary.kinds import kind_spec

#: A structure whose top is at least this high above the table (m) counts as
#: needing the arm's reach: an arm must lift over it and place at that height
#: (four 4 cm blocks, or a three-box column on a pallet).
REACH_HEIGHT = 0.16


@cache
def task_origins() -> Mapping[str, str]:
    """Task name -> origin in the shipped 192-task list (``ravens_cliport_original``
    or ``gensim_generated``)."""
    path = resources.files("factask") / "data" / "gensim_tasks.json"
    return {t["name"]: t.get("origin", "") for t in json.loads(path.read_text())}


def _origin_tag(name: str) -> str:
    origin = task_origins().get(name)
    if origin is None:
        return "origin:factask"
    return "origin:ravens" if origin.startswith("ravens") else "origin:gensim"


def structure_height(graph: TaskGraph) -> float:
    """Height (m) of the top of the tallest structure the goals build.

    Each goal that rests objects on something (``stack``, ``on``, ``row ... on``)
    makes each moved object's top its support's top plus its own height; a
    variable with several instances in a column counts once per instance.
    """
    height = {v.name: v.extents[2] for v in graph.variables}
    count = {v.name: v.count for v in graph.variables}
    support: dict[str, list[str]] = {}
    for f in graph.factors:
        g = f.goal
        kind = g.type
        if kind == "stack":
            below = getattr(g, "base", None)
            for obj in g.objects:
                support.setdefault(obj, []).extend([below] if below else [])
                below = obj
        elif kind == "on":
            for obj in g.objects:
                support.setdefault(obj, []).append(g.support)  # type: ignore[attr-defined]
        elif kind == "row" and getattr(g, "on", None):
            for obj in g.objects:
                support.setdefault(obj, []).extend(g.anchor_names("on"))
    stacked = {name for f in graph.factors if f.goal.type == "stack" for name in f.goal.objects}

    @cache
    def top(name: str, depth: int = 0) -> float:
        own = height[name] * (count[name] if name in stacked else 1)
        below = [top(s, depth + 1) for s in support.get(name, []) if depth < 32]
        return own + max(below, default=0.0)

    movers = [v.name for v in graph.variables if not v.is_fixed]
    return max((top(n) for n in movers if n in support), default=0.0)


def graph_tags(graph: TaskGraph) -> list[str]:
    """Tags read off a graph alone (no registry): objects, relations, order, starts."""
    tags = [f"objects:{graph.movable_object_count()}"]
    tags += [f"relation:{r}" for r in dict.fromkeys(f.goal.type for f in graph.factors)]
    if any(f.after for f in graph.factors):
        tags.append("sequenced")
    if graph.milestones():
        tags.append("milestones")
    moved = {n for f in graph.factors for n in f.scope_names}
    if any(not v.is_fixed and v.name not in moved for v in graph.variables):
        tags.append("distractors")
    starts = {v.initial.type for v in graph.variables}
    if "on" in starts:
        tags.append("starts-stacked")
    if "inside" in starts:
        tags.append("starts-inside")
    kinds = {v.name: v.kind for v in graph.variables}
    if any(kind_spec(kinds[o]).receptacle for f in graph.factors for o in f.goal.objects
           if o in kinds):
        tags.append("moves-receptacle")  # a bowl or container carried by its rim
    if structure_height(graph) >= REACH_HEIGHT - 1e-9:
        tags.append("needs-arm-reach")
    return tags


def task_tags(name: str, graph: TaskGraph) -> tuple[str, ...]:
    """Every tag of library task ``name`` (whose graph is ``graph``), family first."""
    family = FAMILIES.get(name)
    tags = [f"family:{family}"] if family else []
    tags += graph_tags(graph)
    tags.append(_origin_tag(name))
    tags += EXTRA_TAGS.get(name, ())
    return tuple(dict.fromkeys(tags))


def matches_tags(tags: Iterable[str], wanted: Iterable[str]) -> bool:
    """True if every wanted tag is among ``tags``. A wanted tag without a colon
    also matches the value part (``stacking`` matches ``family:stacking``)."""
    have = set(tags)
    values = {t.split(":", 1)[1] for t in have if ":" in t}
    return all(w in have or w in values for w in wanted)


@dataclass(frozen=True)
class ReuseStats:
    """How much of the library is built from shared templates.

    Attributes:
        tasks: Number of tasks.
        factors: Factors over every task.
        shared: Factors instantiated from a library template that two or more tasks use.
        per_template: Template -> (tasks using it, factors built from it).
    """

    tasks: int
    factors: int
    shared: int
    per_template: Mapping[str, tuple[int, int]]

    @property
    def reuse(self) -> float:
        """Shared factors / all factors (0 when there are none)."""
        return self.shared / self.factors if self.factors else 0.0


def reuse_stats(graphs: Mapping[str, TaskGraph]) -> ReuseStats:
    """The subtask-reuse figure of ``graphs`` (task name -> graph)."""
    users: dict[str, set[str]] = {t: set() for t in TEMPLATES}
    built: dict[str, int] = dict.fromkeys(TEMPLATES, 0)
    total = 0
    for name, g in graphs.items():
        for f in g.factors:
            total += 1
            if f.template in users:
                users[f.template].add(name)
                built[f.template] += 1
    shared = sum(built[t] for t, u in users.items() if len(u) >= 2)
    per = {t: (len(users[t]), built[t]) for t in TEMPLATES}
    return ReuseStats(tasks=len(graphs), factors=total, shared=shared, per_template=per)
