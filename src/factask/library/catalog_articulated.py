"""Library tasks with articulated furniture: cabinets whose drawers slide open and shut.

A cabinet stands fixed on the table with its drawers stacked in it (level 0 at
the bottom); each drawer is a variable of its own that starts ``in_cabinet``
(:mod:`factask.scene.cabinet`). The robot slides a drawer by holding its handle
from above (:mod:`factask.sim.robots.slide_pull`); a block put inside an open
drawer rides in it when the drawer is shut.
"""

from __future__ import annotations

from factask.graph import InCabinet, StateVariable, TaskGraph
from factask.library.builders import assemble, register, use, var
from factask.library.conventions import BLOCK
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
