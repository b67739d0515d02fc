"""Library tasks with articulated furniture: cabinets whose drawers slide open and shut.

A cabinet stands fixed on the table with its drawers stacked in it (level 0 at
the bottom); each drawer is a variable of its own that starts ``in_cabinet``
(:mod:`factask.scene.cabinet`). The robot slides a drawer by holding its handle
from above (:mod:`factask.sim.robots.slide_pull`); a block put inside an open
drawer rides in it when the drawer is shut.
"""

from __future__ import annotations

from factask.graph import InCabinet, StateVariable, TaskGraph
from factask.library.builders import assemble, register, start_inside, use, var
from factask.library.conventions import BLOCK, BOWL, ZONE
from factask.vocabulary.kinds import drawer_size

#: A cabinet of three drawers (4.6 cm deep inside each) and one of two, whose drawers
#: (7 cm inside) take a 4 cm block and still shut over it.
THREE_DRAWERS = (0.22, 0.30, 0.24)
TWO_DRAWERS = (0.22, 0.30, 0.20)
#: Names of the drawers by level, bottom first, for a cabinet of two or three.
LEVEL_NAMES = {2: ("bottom", "top"), 3: ("bottom", "middle", "top")}


def cabinet(size: tuple[float, float, float], opened: dict[str, float] | None = None,
            color: str = "brown") -> tuple[StateVariable, dict[str, StateVariable]]:
    """A cabinet variable and its drawers (``<level>_drawer``), each sized for it.

    Args:
        size: The cabinet's size.
        opened: Drawer level name -> how far it starts pulled out (a fraction).
        color: Their colour.

    Returns:
        The cabinet and its drawers by level name.
    """
    names = LEVEL_NAMES[3 if size == THREE_DRAWERS else 2]
    box = var("cabinet", "cabinet", color, size)
    drawers = {
        level: var(f"{level}_drawer", "drawer", color, drawer_size(size, len(names)),
                   description=f"the {level} drawer of the cabinet",
                   initial=InCabinet(cabinet="cabinet", level=k,
                                     opening=(opened or {}).get(level, 0.0)))
        for k, level in enumerate(names)}
    return box, drawers


@register("open-drawer")
def open_drawer() -> TaskGraph:
    box, drawers = cabinet(THREE_DRAWERS)
    return assemble(
        "open-drawer",
        "Open the middle drawer of the cabinet.",
        use("open_drawer", drawer=drawers["middle"]),
        extra=[box, drawers["bottom"], drawers["top"]],
    )


@register("close-drawer")
def close_drawer() -> TaskGraph:
    box, drawers = cabinet(THREE_DRAWERS, opened={"middle": 1.0})
    return assemble(
        "close-drawer",
        "Close the middle drawer of the cabinet.",
        use("close_drawer", drawer=drawers["middle"]),
        extra=[box, drawers["bottom"], drawers["top"]],
    )


@register("open-drawer-and-put-block-inside")
def open_drawer_and_put_block_inside() -> TaskGraph:
    box, drawers = cabinet(TWO_DRAWERS)
    block = var("red_block", "block", "red", BLOCK)
    opened = use("open_drawer", drawer=drawers["top"])
    return assemble(
        "open-drawer-and-put-block-inside",
        "Open the top drawer of the cabinet and put the red block inside it.",
        opened,
        use("put_in_container", objects=block, container=drawers["top"]),
        extra=[box, drawers["bottom"]],
    )


@register("put-block-in-drawer-and-close-it")
def put_block_in_drawer_and_close_it() -> TaskGraph:
    box, drawers = cabinet(TWO_DRAWERS)
    block = var("red_block", "block", "red", BLOCK)
    opened = use("open_drawer", drawer=drawers["top"], milestone=True)
    put = use("put_in_container", objects=block, container=drawers["top"])
    return assemble(
        "put-block-in-drawer-and-close-it",
        "Open the top drawer of the cabinet, put the red block inside it and close it.",
        opened, put,
        use("close_drawer", drawer=drawers["top"], after=[put]),
        extra=[box, drawers["bottom"]],
    )


@register("open-top-drawer")
def open_top_drawer() -> TaskGraph:
    box, drawers = cabinet(THREE_DRAWERS)
    return assemble(
        "open-top-drawer",
        "Open the top drawer of the cabinet.",
        use("open_drawer", drawer=drawers["top"]),
        extra=[box, drawers["bottom"], drawers["middle"]],
    )


@register("open-bottom-drawer")
def open_bottom_drawer() -> TaskGraph:
    # Two drawers, as first written: the bottom one of three (7 cm up, under 24 cm of
    # cabinet) the arm reaches only leaning its tool (tests/test_drawers.py has it).
    box, drawers = cabinet(TWO_DRAWERS)
    return assemble(
        "open-bottom-drawer",
        "Open the bottom drawer of the cabinet.",
        use("open_drawer", drawer=drawers["bottom"]),
        extra=[box, drawers["top"]],
    )


@register("close-top-drawer")
def close_top_drawer() -> TaskGraph:
    box, drawers = cabinet(THREE_DRAWERS, opened={"top": 1.0})
    return assemble(
        "close-top-drawer",
        "Close the top drawer of the cabinet.",
        use("close_drawer", drawer=drawers["top"]),
        extra=[box, drawers["bottom"], drawers["middle"]],
    )


@register("open-two-drawers")
def open_two_drawers() -> TaskGraph:
    # The lower drawer first: a drawer pulled out above a shut one covers its handle.
    box, drawers = cabinet(TWO_DRAWERS)
    bottom = use("open_drawer", drawer=drawers["bottom"])
    return assemble(
        "open-two-drawers",
        "Open both drawers of the cabinet, the bottom one first.",
        bottom,
        use("open_drawer", drawer=drawers["top"], after=[bottom]),
        extra=[box],
    )


@register("put-two-blocks-in-open-drawer")
def put_two_blocks_in_open_drawer() -> TaskGraph:
    box, drawers = cabinet(TWO_DRAWERS, opened={"top": 1.0})
    blocks = [var(f"{c}_block", "block", c, BLOCK) for c in ("red", "blue")]
    return assemble(
        "put-two-blocks-in-open-drawer",
        "Put the red block and the blue block inside the open top drawer of the cabinet.",
        use("put_in_container", objects=blocks, container=drawers["top"]),
        extra=[box, drawers["bottom"]],
    )


@register("open-drawer-and-take-block-out")
def open_drawer_and_take_block_out() -> TaskGraph:
    box, drawers = cabinet(TWO_DRAWERS, opened={"top": 0.5})
    block = var("red_block", "block", "red", BLOCK, initial=start_inside(drawers["top"]))
    zone = var("green_zone", "zone", "green", ZONE)
    opened = use("open_drawer", drawer=drawers["top"])
    return assemble(
        "open-drawer-and-take-block-out",
        "Pull the half-open top drawer of the cabinet all the way open, take the red "
        "block out of it and place it in the green zone.",
        opened,
        use("place_in_zone", objects=block, zone=zone, after=[opened]),
        extra=[box, drawers["bottom"]],
    )


@register("take-block-out-of-shut-drawer")
def take_block_out_of_shut_drawer() -> TaskGraph:
    # The block starts in the drawer with the drawer shut: hidden until it is opened.
    box, drawers = cabinet(TWO_DRAWERS)
    block = var("red_block", "block", "red", BLOCK, initial=start_inside(drawers["top"]))
    zone = var("green_zone", "zone", "green", ZONE)
    opened = use("open_drawer", drawer=drawers["top"])
    return assemble(
        "take-block-out-of-shut-drawer",
        "Open the top drawer of the cabinet, take out the red block that lies in it and "
        "place it in the green zone.",
        opened,
        use("place_in_zone", objects=block, zone=zone, after=[opened]),
        extra=[box, drawers["bottom"]],
    )


@register("take-block-out-of-drawer-to-zone")
def take_block_out_of_drawer_to_zone() -> TaskGraph:
    box, drawers = cabinet(TWO_DRAWERS, opened={"top": 1.0})
    block = var("red_block", "block", "red", BLOCK, initial=start_inside(drawers["top"]))
    zone = var("green_zone", "zone", "green", ZONE)
    return assemble(
        "take-block-out-of-drawer-to-zone",
        "Take the red block out of the open top drawer of the cabinet and place it in "
        "the green zone.",
        use("place_in_zone", objects=block, zone=zone),
        extra=[box, *drawers.values()],
    )


@register("put-bowl-on-cabinet-and-close-drawer")
def put_bowl_on_cabinet_and_close_drawer() -> TaskGraph:
    box, drawers = cabinet(TWO_DRAWERS, opened={"bottom": 1.0})
    bowl = var("blue_bowl", "bowl", "blue", BOWL, fixed=False)
    on = use("place_on_top", objects=bowl, support=box)
    return assemble(
        "put-bowl-on-cabinet-and-close-drawer",
        "Put the blue bowl on top of the cabinet and then close its open bottom drawer.",
        on,
        use("close_drawer", drawer=drawers["bottom"], after=[on]),
        extra=[drawers["top"]],
    )
