"""Library tasks with a stepped shelf: a block put on its top level, a bowl on its
lower level, a block moved from one level to another, two blocks on two levels, a
block taken off a level into a zone.

A shelf stands fixed on the table; its levels rise from its -x side (nearest the
robot) towards its back panel, each level's top open to the sky, so a top-down
suction cup reaches every one (:mod:`factask.scene.shelf`). Each level is a
variable of its own (kind ``shelf_level``) that starts ``in_cabinet`` of the shelf
with its level; ``on`` a level is plain ``on`` a support.
"""

from __future__ import annotations

from factask.graph import InCabinet, StateVariable, TaskGraph
from factask.library.builders import assemble, register, start_on, use, var
from factask.library.conventions import BOWL, ZONE
from factask.vocabulary.kinds import kind_spec, shelf_level_size

#: The shelf of these tasks: the kind's default (two levels 14.5 cm deep, 32 cm
#: wide: a 12 cm bowl stands on either).
SHELF = kind_spec("shelf").default_size
#: Names of the levels by level, the lowest first, for a shelf of two.
LEVEL_NAMES = ("lower", "upper")
#: The library's family of furniture that does not move (shelves).
FAMILY = "furniture"


def shelf(color: str = "brown") -> tuple[StateVariable, dict[str, StateVariable]]:
    """A shelf variable and its two levels (``<level>_level``), each sized for it.

    Args:
        color: Their colour.

    Returns:
        The shelf and its levels by name (``lower``, ``upper``).
    """
    box = var("shelf", "shelf", color, SHELF, description="the shelf")
    levels = {
        name: var(f"{name}_level", "shelf_level", color,
                  shelf_level_size(SHELF, len(LEVEL_NAMES), k),
                  description=f"the {name} level of the shelf",
                  initial=InCabinet(cabinet="shelf", level=k))
        for k, name in enumerate(LEVEL_NAMES)}
    return box, levels


@register("put-block-on-upper-shelf-level", family=FAMILY)
def put_block_on_upper_shelf_level() -> TaskGraph:
    box, levels = shelf()
    block = var("red_block", "block", "red")
    return assemble(
        "put-block-on-upper-shelf-level",
        "Put the red block on the upper level of the shelf.",
        use("place_on_top", objects=block, support=levels["upper"]),
        extra=[box, levels["lower"]],
    )


@register("put-bowl-on-lower-shelf-level", family=FAMILY)
def put_bowl_on_lower_shelf_level() -> TaskGraph:
    box, levels = shelf()
    bowl = var("blue_bowl", "bowl", "blue", BOWL, fixed=False)
    return assemble(
        "put-bowl-on-lower-shelf-level",
        "Put the blue bowl on the lower level of the shelf.",
        use("place_on_top", objects=bowl, support=levels["lower"]),
        extra=[box, levels["upper"]],
    )


@register("move-block-up-a-shelf-level", family=FAMILY)
def move_block_up_a_shelf_level() -> TaskGraph:
    box, levels = shelf()
    block = var("green_block", "block", "green", initial=start_on(levels["lower"]),
                description="the green block, on the lower level of the shelf")
    return assemble(
        "move-block-up-a-shelf-level",
        "Move the green block from the lower level of the shelf to the upper level.",
        use("place_on_top", objects=block, support=levels["upper"]),
        extra=[box, levels["lower"]],
    )


@register("put-blocks-on-two-shelf-levels", family=FAMILY)
def put_blocks_on_two_shelf_levels() -> TaskGraph:
    box, levels = shelf()
    red = var("red_block", "block", "red")
    blue = var("blue_block", "block", "blue")
    return assemble(
        "put-blocks-on-two-shelf-levels",
        "Put the red block on the lower level of the shelf and the blue block on the "
        "upper level.",
        use("place_on_top", prefix="lower", objects=red, support=levels["lower"]),
        use("place_on_top", prefix="upper", objects=blue, support=levels["upper"]),
        extra=[box],
    )


@register("put-three-blocks-on-upper-shelf-level", family=FAMILY)
def put_three_blocks_on_upper_shelf_level() -> TaskGraph:
    box, levels = shelf()
    blocks = var("yellow_blocks", "block", "yellow", count=3)
    return assemble(
        "put-three-blocks-on-upper-shelf-level",
        "Put the three yellow blocks side by side on the upper level of the shelf.",
        use("place_on_top", objects=blocks, support=levels["upper"]),
        extra=[box, levels["lower"]],
    )


@register("take-block-off-shelf-into-zone", family=FAMILY)
def take_block_off_shelf_into_zone() -> TaskGraph:
    box, levels = shelf()
    block = var("blue_block", "block", "blue", initial=start_on(levels["upper"]),
                description="the blue block, on the upper level of the shelf")
    zone = var("green_zone", "zone", "green", ZONE)
    return assemble(
        "take-block-off-shelf-into-zone",
        "Take the blue block off the upper level of the shelf and put it in the green zone.",
        use("place_in_zone", objects=block, zone=zone),
        extra=[box, *levels.values()],
    )
