"""GenSim tasks with piles of small blocks swept by a spatula, and with ropes (issue 15).

Each pile is one ``pile`` variable (its ``count`` small blocks start as one
cluster); ``push_pile_into_zone`` puts a pile's blocks into a region by pushes
(``pile_in_zone``: progress is the share of the blocks inside). A task with
such a goal gets the spatula and the push action (:mod:`factask.sim.robots.spatula`).
Piles here are smaller than Ravens' 50 blocks where a task has several, so the
scene stays within the graph model's object limit.

A rope (kind ``rope``) is a chain of linked segments; ``lay_rope_along`` lays
one straight along a line (``rope_along``, Ravens' 2 cm tolerance per segment);
connect-boxes-with-rope lays one from a block to another (its own template).

The templates of these tasks are defined here, beside their kinds, and added to
the library's registry (:data:`factask.library.templates.TEMPLATES`) on import.
"""

from __future__ import annotations

from typing import Any

from factask.graph import (
    AtFixedPose,
    StateVariable,
    SubtaskFactor,
    SubtaskTemplate,
    TaskGraph,
)
from factask.library.builders import assemble, at, region, register, use, var
from factask.library.templates import REGIONS, TEMPLATES, slot
from factask.relations import PileInZone, RopeAlong
from factask.relations.rope import ANCHOR_GAP, SLOT_PITCH
from factask.vocabulary.tolerances import Tolerances
from factask.vocabulary.world import WORKSPACE_Y

#: A Ravens small block: a 1 cm cube.
SMALL_BLOCK = (0.01, 0.01, 0.01)
#: Ravens' zone for piles (12 cm square) and separating-piles' larger one.
ZONE = (0.12, 0.12, 0.001)
BIG_ZONE = (0.15, 0.15, 0.001)
#: Tasks with a pile per colour: the piles start in x PILE_X, within BAND of their
#: band's middle; the zones lie at x ZONE_X.
PILE_X = (0.27, 0.42)
ZONE_X = 0.66
BAND = 0.06

_DEFORMABLE_TEMPLATES = [
    SubtaskTemplate(
        name="push_pile_into_zone",
        description="Push the small blocks of the {objects} into the {zone} with the spatula.",
        slots=[slot("objects", "the piles of small blocks to push", ["pile"], many=True,
                    movable=True),
               slot("zone", "the target region", REGIONS)],
        factors=[SubtaskFactor(
            name="pile_in_zone",
            description="push the blocks of the {objects} into the {zone}",
            goal=PileInZone(objects=["objects"], zone="zone"),
        )],
    ),
]
for _t in _DEFORMABLE_TEMPLATES:
    TEMPLATES.setdefault(_t.name, _t)


def _pile(color: str, count: int, **extra: Any) -> StateVariable:
    return var(f"{color}_pile", "pile", color, SMALL_BLOCK, count=count,
               description=f"a pile of {count} small {color} blocks", **extra)


def _zone(color: str, size: tuple[float, float, float] = ZONE, **extra: Any) -> StateVariable:
    return var(f"{color}_zone", "zone", color, size, description=f"the {color} zone",
               **extra)


def _pile_per_zone(colors: tuple[str, ...], count: int) -> list[TaskGraph]:
    """One pile of ``count`` blocks per colour, each pushed into the zone of its colour.

    Each colour has its own band across the table: its pile starts near the robot,
    its zone lies at the far side of the band, so no push crosses another zone."""
    width = (WORKSPACE_Y[1] - WORKSPACE_Y[0] - 0.2) / len(colors)
    out = []
    for k, c in enumerate(colors):
        y = WORKSPACE_Y[0] + 0.1 + (k + 0.5) * width
        pile = _pile(c, count, initial=region(PILE_X, (y - BAND, y + BAND)))
        zone = _zone(c, initial=at(ZONE_X, y))
        out.append(use("push_pile_into_zone", prefix=c, objects=[pile], zone=zone))
    return out


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
    fragments = _pile_per_zone(colors, 15)
    lines = []
    for frag, c in zip(fragments, colors, strict=True):
        zone = frag.variable(f"{c}_zone")
        assert isinstance(zone.initial, AtFixedPose)
        # The line runs from the pile's side to the zone, along the band.
        lines.append(var(f"{c}_line", "line", c, (0.22, 0.01, 0.001),
                         description=f"the {c} line to the {c} zone",
                         initial=at(ZONE_X - 0.17, zone.initial.y)))
    return assemble(
        "move-piles-along-line",
        "Push three piles of small blocks (red, blue, green) along the lines of their "
        "colours into the zones of their colours with the spatula.",
        fragments,
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


# ------------------------------------------------------------------------ ropes
#: Ravens' rope: 20 beads, 1 cm thick, about 28 cm long.
ROPE_SEGMENTS = 20
ROPE_SEGMENT = (0.014, 0.01, 0.01)
#: Ravens' rope tasks accept a bead within 2 cm of its target.
ROPE_TOLERANCE = Tolerances(xy=0.02)


def _rope(color: str, **extra: Any) -> StateVariable:
    return var(f"{color}_rope", "rope", color, ROPE_SEGMENT, count=ROPE_SEGMENTS,
               description=f"a {color} rope of {ROPE_SEGMENTS} linked segments", **extra)


_ROPE_TEMPLATES = [
    SubtaskTemplate(
        name="lay_rope_along",
        description="Lay the {rope} straight along the {line}.",
        slots=[slot("rope", "the rope", ["rope"], movable=True),
               slot("line", "the line (or region) to lie along", REGIONS)],
        factors=[SubtaskFactor(
            name="rope_along", description="lay the {rope} straight along the {line}",
            goal=RopeAlong(objects=["rope"], along="line", tolerances=ROPE_TOLERANCE),
        )],
    ),
]
for _t in _ROPE_TEMPLATES:
    TEMPLATES.setdefault(_t.name, _t)


@register("align-rope-along-line")
def align_rope_along_line() -> TaskGraph:
    rope = _rope("red")
    line = var("green_line", "line", "green", (0.30, 0.01, 0.001), description="the line")
    return assemble(
        "align-rope-along-line",
        "Align the rope straight along the green line marked on the tabletop.",
        use("lay_rope_along", rope=rope, line=line),
    )


@register("manipulating-two-ropes")
def manipulating_two_ropes() -> TaskGraph:
    fragments = []
    for c, y in (("red", -0.22), ("blue", 0.22)):
        rope = _rope(c, initial=region((0.3, 0.7), (y - 0.2, y + 0.2)))
        line = var(f"{c}_line", "line", c, (0.30, 0.01, 0.001),
                   description=f"the {c} line", initial=at(0.5, y))
        fragments.append(use("lay_rope_along", prefix=c, rope=rope, line=line))
    return assemble(
        "manipulating-two-ropes",
        "Lay the red and the blue rope each straight along the line of its colour.",
        fragments,
    )


#: Ravens' 3-sided square of its rope tasks: side 2 x bead radius x 20 x sqrt(2).
ROPE_SQUARE = (0.283, 0.283, 0.001)


def _on_side(fragment: TaskGraph, side: str) -> TaskGraph:
    """The ``lay_rope_along`` fragment with its run moved to one ``side`` of its region
    (an edge, or the diagonal)."""
    factor = fragment.factors[0]
    factor.goal = factor.goal.model_copy(update={"side": side})
    return fragment


def _square_rope_task(name: str, description: str, side: str) -> TaskGraph:
    rope = _rope("red")
    square = var("green_square", "zone", "green", ROPE_SQUARE,
                 description="the 3-sided square (its outline as a flat zone)")
    return assemble(name, description,
                    _on_side(use("lay_rope_along", rope=rope, line=square), side))


@register("align-rope")
def align_rope() -> TaskGraph:
    return _square_rope_task(
        "align-rope",
        "Align the rope from the front right tip to the back right corner of the 3-sided "
        "square (its ends at the two corners of that side).", "+x")


@register("manipulating-rope")
def manipulating_rope() -> TaskGraph:
    return _square_rope_task(
        "manipulating-rope",
        "Rearrange the rope so that it connects the two end points of the 3-sided square "
        "(the open side).", "+y")


@register("align-rope-cross-zone")
def align_rope_cross_zone() -> TaskGraph:
    rope = _rope("blue")
    zone = var("green_zone", "zone", "green", (0.2, 0.2, 0.001), description="the zone")
    return assemble(
        "align-rope-cross-zone",
        "Align the rope across the diagonal of the green zone marked on the tabletop.",
        _on_side(use("lay_rope_along", rope=rope, line=zone), "diagonal"),
    )


@register("push-piles-into-letter")
def push_piles_into_letter() -> TaskGraph:
    # The letter L on the table, as two bars: the stem across the table at the far
    # side, the foot from the stem's end towards the robot. One pile per bar, each
    # pushed along its own band (+x), so no push crosses the other bar.
    stem_y, foot_y = 0.06, -0.06
    stem = var("stem_zone", "zone", "green", (0.06, 0.2, 0.001), initial=at(0.68, stem_y),
               description="the stem of the letter L")
    foot = var("foot_zone", "zone", "green", (0.14, 0.06, 0.001),
               initial=at(0.58, foot_y), description="the foot of the letter L")
    stem_pile = _pile("red", 10, initial=region(PILE_X, (stem_y + 0.02, stem_y + 0.08)))
    foot_pile = _pile("blue", 10, initial=region(PILE_X, (foot_y - 0.08, foot_y - 0.02)))
    return assemble(
        "push-piles-into-letter",
        "Push the piles of small blocks into the letter L marked on the tabletop: the red "
        "pile into its stem, the blue pile into its foot.",
        use("push_pile_into_zone", prefix="stem", objects=[stem_pile], zone=stem),
        use("push_pile_into_zone", prefix="foot", objects=[foot_pile], zone=foot),
    )


#: A rope from one anchor to another (a block beside each end: GenSim's
#: connect-boxes-with-rope). One task uses it (not registered, see templates.TEMPLATES).
_CONNECT_WITH_ROPE = SubtaskTemplate(
    name="connect_with_rope",
    description="Lay the {rope} straight from the {start} to the {end}.",
    slots=[slot("rope", "the rope", ["rope"], movable=True),
           slot("start", "the anchor at the rope's one end"),
           slot("end", "the anchor at the rope's other end")],
    factors=[SubtaskFactor(
        name="rope_along", description="lay the {rope} from the {start} to the {end}",
        goal=RopeAlong(objects=["rope"], start="start", end="end", tolerances=ROPE_TOLERANCE),
    )],
)

#: A Ravens block (4 cm cube).
BLOCK = (0.04, 0.04, 0.04)


@register("connect-boxes-with-rope")
def connect_boxes_with_rope() -> TaskGraph:
    # Two fixed blocks across the table, as far apart as the rope's run needs: its
    # slots fill the space between their faces, with the anchor gap at each end.
    rope = _rope("yellow")
    apart = BLOCK[0] + 2 * ANCHOR_GAP + ROPE_SEGMENTS * ROPE_SEGMENT[0] * SLOT_PITCH
    red = var("red_block", "block", "red", BLOCK, fixed=True, initial=at(0.5, -apart / 2),
              description="the red block")
    blue = var("blue_block", "block", "blue", BLOCK, fixed=True, initial=at(0.5, apart / 2),
               description="the blue block")
    return assemble(
        "connect-boxes-with-rope",
        "Connect the red and the blue block with the rope: lay it straight from one "
        "block to the other.",
        _CONNECT_WITH_ROPE.instantiate(rope=rope, start=red, end=blue),
    )
