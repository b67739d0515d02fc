"""GenSim tasks with piles of small blocks swept by a spatula (issue 15).

Each pile is one ``pile`` variable (its ``count`` small blocks start as one
cluster); ``push_pile_into_zone`` puts a pile's blocks into a region by pushes
(``pile_in_zone``: progress is the share of the blocks inside). A task with
such a goal gets the spatula and the push action (:mod:`factask.sim.push`).
Piles here are smaller than Ravens' 50 blocks where a task has several, so the
scene stays within the graph model's object limit.

The templates of these tasks are defined here, beside their kinds, and added to
the library's registry (:data:`factask.library.templates.TEMPLATES`) on import.
"""

from __future__ import annotations

from factask.library.builders import assemble, register, use, var
from factask.library.templates import REGIONS, TEMPLATES
from factask.model import StateVariable, SubtaskFactor, SubtaskTemplate, TaskGraph, TemplateSlot
from factask.relations import PileInZone

#: A Ravens small block: a 1 cm cube.
SMALL_BLOCK = (0.01, 0.01, 0.01)
#: Ravens' zone for piles (12 cm square) and separating-piles' larger one.
ZONE = (0.12, 0.12, 0.001)
BIG_ZONE = (0.15, 0.15, 0.001)
#: A marked line from a pile to its zone.
LINE = (0.30, 0.01, 0.001)

_DEFORMABLE_TEMPLATES = [
    SubtaskTemplate(
        name="push_pile_into_zone",
        description="Push the small blocks of the {objects} into the {zone} with the spatula.",
        slots=[TemplateSlot(name="objects", description="the piles of small blocks to push",
                            kinds=["pile"], many=True, movable=True),
               TemplateSlot(name="zone", description="the target region",
                            kinds=REGIONS)],  # type: ignore[arg-type]
        factors=[SubtaskFactor(
            name="pile_in_zone",
            description="push the blocks of the {objects} into the {zone}",
            goal=PileInZone(objects=["objects"], zone="zone"),
        )],
    ),
]
for _t in _DEFORMABLE_TEMPLATES:
    TEMPLATES.setdefault(_t.name, _t)


def _pile(color: str, count: int) -> StateVariable:
    return var(f"{color}_pile", "pile", color, SMALL_BLOCK, count=count,
               description=f"a pile of {count} small {color} blocks")


def _zone(color: str, size: tuple[float, float, float] = ZONE) -> StateVariable:
    return var(f"{color}_zone", "zone", color, size, description=f"the {color} zone")


def _pile_per_zone(colors: tuple[str, ...], count: int) -> list[TaskGraph]:
    """One pile of ``count`` blocks per colour, each pushed into the zone of its colour."""
    return [use("push_pile_into_zone", prefix=c, objects=[_pile(c, count)], zone=_zone(c))
            for c in colors]


@register("sweeping-piles")
def sweeping_piles() -> TaskGraph:
    pile = _pile("red", 50)
    zone = _zone("green")
    return assemble(
        "sweeping-piles",
        "Push the pile of small blocks into the green zone marked on the tabletop.",
        use("push_pile_into_zone", objects=[pile], zone=zone),
    )


@register("separating-piles")
def separating_piles() -> TaskGraph:
    pile = _pile("yellow", 50)
    target = _zone("green", BIG_ZONE)
    distractor = _zone("red", BIG_ZONE)
    return assemble(
        "separating-piles",
        "Sweep the pile of yellow blocks into the green zone; the red zone is a distractor.",
        use("push_pile_into_zone", objects=[pile], zone=target),
        extra=[distractor],
    )


@register("mix-piles")
def mix_piles() -> TaskGraph:
    reds, blues = _pile("red", 10), _pile("blue", 10)
    zone = _zone("green", BIG_ZONE)
    return assemble(
        "mix-piles",
        "Two separate piles of ten blocks, red and blue: push both into the green zone.",
        use("push_pile_into_zone", prefix="red", objects=[reds], zone=zone),
        use("push_pile_into_zone", prefix="blue", objects=[blues], zone=zone),
    )


@register("move-piles-along-line")
def move_piles_along_line() -> TaskGraph:
    colors = ("red", "blue", "green")
    lines = [var(f"{c}_line", "line", c, LINE, description=f"the {c} line to the {c} zone")
             for c in colors]
    return assemble(
        "move-piles-along-line",
        "Push three piles of small blocks (red, blue, green) into the zones of their "
        "colours with the spatula.",
        _pile_per_zone(colors, 15),
        extra=lines,
    )


@register("sweep-and-sort-blocks")
def sweep_and_sort_blocks() -> TaskGraph:
    return assemble(
        "sweep-and-sort-blocks",
        "Sweep the piles of small red, blue, green and yellow blocks into the zones of "
        "their colours.",
        _pile_per_zone(("red", "blue", "green", "yellow"), 12),
    )
