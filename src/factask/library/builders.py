"""A tiny vocabulary for writing library tasks as data.

A task builder declares its variables with :func:`var`, instantiates library
templates with :func:`use` (or :func:`factask.library.templates.match_pairs`) and
joins the fragments with :func:`assemble`. Nothing here is task specific: every
task goes through the same three steps, so tasks stay data built from templates.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from typing import Any

from factask.graph import AtFixedPose, InRegion, StartInside, StartOn, StateVariable, TaskGraph
from factask.graph import compose as _compose
from factask.library.templates import get_template
from factask.vocabulary.errors import InvalidValueError

#: Task name -> builder (filled by :func:`register`, read by ``factask.library.tasks``).
BUILDERS: dict[str, Callable[[], TaskGraph]] = {}
#: Task name -> its family (what kind of task it is: stacking, placing, sorting, ...).
FAMILIES: dict[str, str] = {}
#: Task name -> tags the author gave beyond those read off the graph (see
#: :func:`factask.library.tags.task_tags`).
EXTRA_TAGS: dict[str, tuple[str, ...]] = {}


def register(name: str, *, family: str | None = None, tags: Sequence[str] = ()
             ) -> Callable[[Callable[[], TaskGraph]], Callable[[], TaskGraph]]:
    """Decorator: record ``builder`` as the library task ``name`` (kebab-case).

    ``family`` defaults to the catalogue module's topic (``catalog_stacking`` ->
    ``stacking``); ``tags`` adds tags that the graph cannot tell (e.g. ``barrier``).
    """

    def deco(builder: Callable[[], TaskGraph]) -> Callable[[], TaskGraph]:
        if name in BUILDERS:
            raise InvalidValueError(f"library task {name!r} is registered twice")
        BUILDERS[name] = builder
        module = builder.__module__.rsplit(".", 1)[-1]
        FAMILIES[name] = family or module.removeprefix("catalog_").removeprefix("gensim_")
        EXTRA_TAGS[name] = tuple(tags)
        return builder

    return deco


def var(name: str, kind: str, color: str = "gray", size: Sequence[float] | None = None,
        count: int = 1, description: str = "", **extra: Any) -> StateVariable:
    """A state variable; ``description`` defaults to "<count> <colour> <kind>(s)"."""
    if not description:
        plural = "s" if count > 1 else ""
        description = f"{count} {color} {kind}{plural}" if count > 1 else f"the {color} {kind}"
    return StateVariable(name=name, kind=kind, color=color, count=count,  # type: ignore[arg-type]
                         size=tuple(size) if size is not None else None,  # type: ignore[arg-type]
                         description=description, **extra)


def at(x: float, y: float, yaw_deg: float = 0.0) -> AtFixedPose:
    """Initial placement at a fixed table spot."""
    return AtFixedPose(x=x, y=y, yaw_deg=yaw_deg)


def region(x: tuple[float, float], y: tuple[float, float]) -> InRegion:
    """Initial placement somewhere inside an x/y box of the table."""
    return InRegion(x=x, y=y)


def start_on(support: StateVariable) -> StartOn:
    """Initial placement on top of another variable."""
    return StartOn(support=support.name)


def start_inside(container: StateVariable) -> StartInside:
    """Initial placement inside a receptacle variable."""
    return StartInside(container=container.name)


def use(template: str, *, prefix: str | None = None, after: Iterable[TaskGraph | str] = (),
        milestone: bool | None = None,
        **bindings: StateVariable | Sequence[StateVariable]) -> TaskGraph:
    """Instantiate library template ``template`` with ``bindings``.

    ``after`` takes fragments (all their factors) or factor names that this
    instance must come after: an explicit order beyond what anchoring implies.
    ``milestone=True`` makes the instance's factors milestones (they count once
    achieved, in order).
    """
    names: list[str] = []
    for item in after:
        names.extend(item.factor_names() if isinstance(item, TaskGraph) else [item])
    return get_template(template).instantiate(prefix=prefix, after=names, milestone=milestone,
                                              **bindings)


def assemble(name: str, description: str, *fragments: TaskGraph | Sequence[TaskGraph],
             extra: Sequence[StateVariable] = ()) -> TaskGraph:
    """Compose fragments (and distractor/fixed variables in ``extra``) into a
    validated task graph."""
    flat: list[TaskGraph] = []
    for f in fragments:
        flat.extend([f] if isinstance(f, TaskGraph) else list(f))
    if extra:
        flat.append(TaskGraph(name=name, variables=list(extra)))
    return _compose(*flat, name=name, description=description).ensure_valid()


def colored(kind: str, colors: Sequence[str], size: Sequence[float] | None = None,
            suffix: str | None = None, **extra: Any) -> list[StateVariable]:
    """One variable per colour, named ``<colour>_<suffix or kind>`` (sorting tasks
    pair these up with :func:`factask.library.templates.match_pairs`)."""
    return [var(f"{c}_{suffix or kind}", kind, c, size, **extra) for c in colors]


def barrier(x: float, span: float = 0.8, color: str = "gray") -> list[StateVariable]:
    """Fixed low bars (2 cm wide and high) across the table at depth ``x``, together
    ``span`` long and centred on y = 0: GenSim's "line of small blocks" that the
    robot must carry objects over without knocking it. Segments stay under 30 cm
    (the library's largest fixed object)."""
    n = max(1, math.ceil(span / 0.30 - 1e-9))
    length = span / n
    return [var(f"barrier_{k + 1}", "box", color, (length, 0.02, 0.02), fixed=True,
                initial=at(x, -span / 2 + (k + 0.5) * length, 90.0),
                description="a fixed low barrier the robot must reach over")
            for k in range(n)]
