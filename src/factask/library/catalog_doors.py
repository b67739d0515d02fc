"""Library tasks with hinged doors: a microwave opened, shut, a bowl (or a mug's
stand-in) put inside; and a drawer that starts open, a bowl put in it, shut.

A microwave stands fixed on the table, open at its -x side behind its door (and at
the top, for the top-down cups); the door is a variable of its own that starts
``in_cabinet`` of it (:mod:`factask.scene.microwave`). The robot swings the door by
holding its handle tab from above and moving along the arc about the hinge
(:mod:`factask.sim.robots.door_swing`). A goal inside the microwave comes after
the door's ``open`` and before its ``closed`` (:mod:`factask.graph.order`), with no
``after`` written.
"""

from __future__ import annotations

from factask.graph import InCabinet, StateVariable, TaskGraph
from factask.library.builders import assemble, register, use, var
from factask.library.catalog_articulated import TWO_DRAWERS, cabinet
from factask.library.conventions import BOWL
from factask.vocabulary.kinds import door_size, kind_spec

#: The microwave of these tasks: the kind's default (a 12 cm bowl fits inside with
#: a centimetre to spare along x).
MICROWAVE = kind_spec("microwave").default_size


#: A mug's stand-in: an upright cylinder the cup takes by its top.
MUG = (0.05, 0.05, 0.07)


def microwave(opening: float = 0.0, color: str = "gray",
              name: str = "microwave") -> tuple[StateVariable, StateVariable]:
    """A microwave variable and its door (``<name>_door``), the door sized for it.

    Args:
        opening: How far the door starts swung out (a fraction of its range).
        color: Their colour.
        name: The microwave variable's name.

    Returns:
        The microwave and its door.
    """
    box = var(name, "microwave", color, MICROWAVE,
              description=f"the {name.replace('_', ' ')}")
    door = var(f"{name}_door", "door", color, door_size(MICROWAVE),
               description=f"the door of the {name.replace('_', ' ')}",
               initial=InCabinet(cabinet=name, opening=opening))
    return box, door


def _bowl() -> StateVariable:
    return var("blue_bowl", "bowl", "blue", BOWL, fixed=False)


@register("open-microwave", family="articulated")
def open_microwave() -> TaskGraph:
    box, door = microwave()
    return assemble(
        "open-microwave",
        "Open the door of the microwave.",
        use("open_door", door=door),
        extra=[box],
    )


@register("close-microwave", family="articulated")
def close_microwave() -> TaskGraph:
    box, door = microwave(opening=1.0)
    return assemble(
        "close-microwave",
        "Close the open door of the microwave.",
        use("close_door", door=door),
        extra=[box],
    )


@register("open-microwave-and-put-bowl-inside", family="articulated")
def open_microwave_and_put_bowl_inside() -> TaskGraph:
    box, door = microwave()
    return assemble(
        "open-microwave-and-put-bowl-inside",
        "Open the door of the microwave and put the blue bowl inside it.",
        use("open_door", door=door),
        use("put_in_container", objects=_bowl(), container=box),
    )


@register("put-bowl-in-microwave-and-close-it", family="articulated")
def put_bowl_in_microwave_and_close_it() -> TaskGraph:
    # The door is opened first (a milestone: the close moves it again); the bowl
    # goes in after the open and before the close by the order's own rules.
    box, door = microwave()
    return assemble(
        "put-bowl-in-microwave-and-close-it",
        "Open the door of the microwave, put the blue bowl inside it and close the door.",
        use("open_door", door=door, milestone=True),
        use("put_in_container", objects=_bowl(), container=box),
        use("close_door", door=door),
    )


@register("put-bowl-in-open-microwave-and-close-it", family="articulated")
def put_bowl_in_open_microwave_and_close_it() -> TaskGraph:
    box, door = microwave(opening=1.0)
    return assemble(
        "put-bowl-in-open-microwave-and-close-it",
        "Put the blue bowl inside the microwave, whose door is open, and close the door.",
        use("put_in_container", objects=_bowl(), container=box),
        use("close_door", door=door),
    )


@register("put-mug-in-white-microwave-and-close-it", family="articulated")
def put_mug_in_white_microwave_and_close_it() -> TaskGraph:
    box, door = microwave(color="white", name="white_microwave")
    mug = var("red_mug", "cylinder", "red", MUG, description="the red mug (a cylinder)")
    return assemble(
        "put-mug-in-white-microwave-and-close-it",
        "Open the white microwave, put the red mug inside it and close its door.",
        use("open_door", door=door, milestone=True),
        use("put_in_container", objects=mug, container=box),
        use("close_door", door=door),
    )


@register("put-bowl-in-open-drawer-and-close-it", family="articulated")
def put_bowl_in_open_drawer_and_close_it() -> TaskGraph:
    # The drawer starts open: the put comes before the close without an 'after'
    # (a goal inside a drawer waits for its open, never for its close).
    box, drawers = cabinet(TWO_DRAWERS, opened={"top": 1.0})
    return assemble(
        "put-bowl-in-open-drawer-and-close-it",
        "Put the blue bowl inside the open top drawer of the cabinet and close it.",
        use("put_in_container", objects=_bowl(), container=drawers["top"]),
        use("close_drawer", drawer=drawers["top"]),
        extra=[box, drawers["bottom"]],
    )
