"""The library of reusable subtask templates.

Each template is a small, checkable subtask over *slots* (placeholders for task
variables). Top-level tasks bind the slots to their own variables with
``TEMPLATES[name].instantiate(...)`` and join the fragments with
:func:`factask.graph.compose`. Factor descriptions use ``{slot}`` placeholders,
so an instance reads as a language goal ("put the red block in the green bowl").

Templates never compute target poses: every goal is a relation that the solver
turns into poses at reset.
"""

from __future__ import annotations

from collections.abc import Sequence

from factask.graph import (
    Aligned,
    AtPose,
    Circle,
    Closed,
    CompositionError,
    Inside,
    InZone,
    On,
    Open,
    Row,
    Stack,
    StateVariable,
    SubtaskFactor,
    SubtaskTemplate,
    SwitchedOff,
    SwitchedOn,
    TargetPose,
    TaskGraph,
    TemplateSlot,
)

# Kinds a suction gripper can pick and that stay where they are put; a free bowl or
# container is taken by its rim (factask.sim.oracle.pick_points).
MOVABLE_RECEPTACLES = ["bowl", "container"]
PICKABLE = ["block", "box", "cylinder", "ball", "log", "ell", *MOVABLE_RECEPTACLES]
# Kinds that can carry something on their flat top (columns, layers, decks).
STACKABLE = ["block", "box", "cylinder"]
# Kinds usable as the footprint of an ``in_zone`` goal.
REGIONS = ["zone", "pallet", "kit", "stand", "line", "bowl", "container", "fixture"]
# Kinds one can put things inside.
RECEPTACLES = ["container", "bowl", "fixture", "drawer", "microwave"]
# Kinds a column may stand on (``stack`` base: support or region; a corner marker
# holds a column of ells, an ell carries an equal ell).
BASES = ["pallet", "stand", "kit", "zone", "container", "block", "box", "cylinder", "corner",
         "ell"]
# Kinds objects may rest on (``on`` support: support or receptacle; a cabinet's top).
SUPPORTS = ["block", "box", "cylinder", "pallet", "stand", "kit", "container", "bowl",
            "cabinet", "stove", "shelf_level"]

#: Centre distance of a bridge's two pillars (m): with 4 cm pillars the gap is
#: 4 cm, so a deck at least 12 cm long spans it with 2 cm resting on each pillar.
BRIDGE_PILLAR_SPACING = 0.08


def slot(name: str, description: str, kinds: list[str] | None = None, *,
         many: bool = False, movable: bool | None = None) -> TemplateSlot:
    """A template slot (the catalogs' task-local templates use it too)."""
    return TemplateSlot(name=name, description=description, kinds=kinds,  # type: ignore[arg-type]
                        many=many, movable=movable)


def _objects(description: str = "the objects to move", kinds: list[str] | None = None,
             name: str = "objects") -> TemplateSlot:
    return slot(name, description, kinds or PICKABLE, many=True, movable=True)


#: The layer a pyramid or wall layer rests on: a row made of one variable's instances,
#: or of several variables (a layer of mixed colours).
_BELOW = slot("below", "the layer underneath, a row: one variable or several (mixed "
               "colours)", STACKABLE, many=True)

_TEMPLATE_LIST: list[SubtaskTemplate] = [
    SubtaskTemplate(
        name="place_in_zone",
        description="Place the {objects} inside the {zone}.",
        slots=[_objects(), slot("zone", "the target region", REGIONS)],
        factors=[SubtaskFactor(
            name="in_zone",
            description="place the {objects} inside the {zone}",
            goal=InZone(objects=["objects"], zone="zone"),
        )],
    ),
    SubtaskTemplate(
        name="put_in_container",
        description="Put the {objects} into the {container}.",
        slots=[_objects(), slot("container", "the receptacle", RECEPTACLES)],
        factors=[SubtaskFactor(
            name="put_in",
            description="put the {objects} into the {container}",
            goal=Inside(objects=["objects"], container="container"),
        )],
    ),
    SubtaskTemplate(
        name="open_drawer",
        description="Open the {drawer}.",
        slots=[slot("drawer", "the drawer to pull open", ["drawer"])],
        factors=[SubtaskFactor(
            name="open",
            description="pull the {drawer} open",
            goal=Open(objects=["drawer"]),
        )],
    ),
    SubtaskTemplate(
        name="close_drawer",
        description="Close the {drawer}.",
        slots=[slot("drawer", "the drawer to push shut", ["drawer"])],
        factors=[SubtaskFactor(
            name="close",
            description="push the {drawer} shut",
            goal=Closed(objects=["drawer"]),
        )],
    ),
    SubtaskTemplate(
        name="switch_on",
        description="Switch on the {switch}.",
        slots=[slot("switch", "the switch to press down", ["switch"])],
        factors=[SubtaskFactor(
            name="switch_on",
            description="press the {switch} down",
            goal=SwitchedOn(objects=["switch"]),
        )],
    ),
    SubtaskTemplate(
        name="switch_off",
        description="Switch off the {switch}.",
        slots=[slot("switch", "the switch to pull back up", ["switch"])],
        factors=[SubtaskFactor(
            name="switch_off",
            description="pull the {switch} back up",
            goal=SwitchedOff(objects=["switch"]),
        )],
    ),
    SubtaskTemplate(
        name="open_door",
        description="Open the {door}.",
        slots=[slot("door", "the door to swing open", ["door"])],
        factors=[SubtaskFactor(
            name="open",
            description="swing the {door} open",
            goal=Open(objects=["door"]),
        )],
    ),
    SubtaskTemplate(
        name="close_door",
        description="Close the {door}.",
        slots=[slot("door", "the door to swing shut", ["door"])],
        factors=[SubtaskFactor(
            name="close",
            description="swing the {door} shut",
            goal=Closed(objects=["door"]),
        )],
    ),
    SubtaskTemplate(
        name="stack_column",
        description="Stack the {layers} into one column on the table, first at the bottom.",
        slots=[_objects("the column's layers, bottom first", STACKABLE, "layers")],
        factors=[SubtaskFactor(
            name="stack",
            description="stack the {layers} into a column on the table, bottom to top",
            goal=Stack(objects=["layers"]),
        )],
    ),
    SubtaskTemplate(
        name="stack_on_base",
        description="Stack the {layers} into one column on the {base}, first at the bottom.",
        slots=[_objects("the column's layers, bottom first", [*STACKABLE, "ell"], "layers"),
               slot("base", "what the column stands on", BASES)],
        factors=[SubtaskFactor(
            name="stack_on",
            description="stack the {layers} on the {base}, bottom to top",
            goal=Stack(objects=["layers"], base="base"),
        )],
    ),
    SubtaskTemplate(
        name="build_row",
        description="Place the {objects} side by side in a straight row on the table.",
        slots=[_objects("the row's objects, in order")],
        factors=[SubtaskFactor(
            name="row",
            description="line up the {objects} side by side in a straight row",
            goal=Row(objects=["objects"]),
        )],
    ),
    SubtaskTemplate(
        name="place_on_top",
        description="Put the {objects} on top of the {support}.",
        slots=[_objects(), slot("support", "what the objects rest on", SUPPORTS)],
        factors=[SubtaskFactor(
            name="on_top",
            description="put the {objects} on top of the {support}",
            goal=On(objects=["objects"], support="support"),
        )],
    ),
    SubtaskTemplate(
        name="bridge",
        description="Build a bridge: two {pillars} apart, the {deck} resting across both.",
        slots=[slot("pillars", "one variable with two instances: the bridge's pillars",
                     STACKABLE, movable=True),
               slot("deck", "the bar or log laid across the pillars (>= 12 cm long)",
                     ["box", "block", "log"], movable=True)],
        factors=[
            SubtaskFactor(
                name="pillars",
                description="stand the two {pillars} upright in a row with a gap between them",
                goal=Row(objects=["pillars"], spacing=BRIDGE_PILLAR_SPACING),
            ),
            SubtaskFactor(
                name="deck",
                description="lay the {deck} across the two {pillars}",
                goal=On(objects=["deck"], support="pillars"),
                initial_setup="the two {pillars} stand in a row with a gap between them",
            ),
        ],
    ),
    SubtaskTemplate(
        name="pyramid_layer",
        description="Lay the {layer} as a row on the {below}, each bridging two neighbours.",
        slots=[_objects("the layer's objects (one fewer than below)", STACKABLE, "layer"),
               _BELOW],
        factors=[SubtaskFactor(
            name="pyramid_layer",
            description="lay the {layer} on the {below}, each bridging two neighbours",
            goal=Row(objects=["layer"], on=["below"]),
            initial_setup="the {below} stand side by side in a row",
        )],
    ),
    SubtaskTemplate(
        name="layer_on_row",
        description="Lay the {layer} on the {below}, one on each (a wall or pallet layer).",
        slots=[_objects("the layer's objects (as many as below)", STACKABLE, "layer"),
               _BELOW],
        factors=[SubtaskFactor(
            name="layer_on",
            description="lay the {layer} on the {below}, one on each",
            goal=Row(objects=["layer"], on=["below"]),
            initial_setup="the {below} stand side by side in a row",
        )],
    ),
    SubtaskTemplate(
        name="insert_into_fixture",
        description="Insert the {objects} into the {fixture}, matching its position and yaw.",
        slots=[_objects("the piece to insert", ["ell", "block", "box", "cylinder", "log"]),
               slot("fixture", "the fixture whose hollow matches the piece", ["fixture"])],
        factors=[SubtaskFactor(
            name="insert",
            description="insert the {objects} into the {fixture}",
            goal=Aligned(objects=["objects"], reference="fixture", mode="center"),
        )],
    ),
    SubtaskTemplate(
        name="align_to_corner",
        description="Align a corner of the {objects} with the {corner} marker.",
        slots=[_objects("the object to align",
                        ["box", "block", "cylinder", "ball", *MOVABLE_RECEPTACLES]),
               slot("corner", "the L-shaped corner marker", ["corner"])],
        factors=[SubtaskFactor(
            name="corner",
            description="align a corner of the {objects} with the {corner}",
            goal=Aligned(objects=["objects"], reference="corner", mode="corner"),
        )],
    ),
    SubtaskTemplate(
        name="palletize_layer",
        description="Set the {objects} side by side on the {pallet}.",
        slots=[_objects("the objects of the layer", STACKABLE),
               slot("pallet", "the pallet", ["pallet"])],
        factors=[SubtaskFactor(
            name="palletize",
            description="set the {objects} side by side on the {pallet}",
            goal=On(objects=["objects"], support="pallet"),
        )],
    ),
    SubtaskTemplate(
        name="arrange_circle",
        description="Arrange the {objects} evenly on a circle on the table.",
        slots=[_objects()],
        factors=[SubtaskFactor(
            name="circle",
            description="arrange the {objects} evenly on a circle",
            goal=Circle(objects=["objects"]),
        )],
    ),
    SubtaskTemplate(
        name="arrange_circle_around",
        description="Arrange the {objects} evenly on a circle around the {center}.",
        slots=[_objects(),
               slot("center", "what the circle goes around",
                     ["zone", "pallet", "kit", "stand", "bowl", "container", "block", "box",
                      "cylinder"])],
        factors=[SubtaskFactor(
            name="circle_around",
            description="arrange the {objects} evenly on a circle around the {center}",
            goal=Circle(objects=["objects"], center="center"),
        )],
    ),
    SubtaskTemplate(
        name="align_along_line",
        description="Line up the {objects} in a row lying on the {line}.",
        slots=[_objects("the row's objects, in order"),
               slot("line", "the line, zone, stand, pallet or container the row lies on; a "
                     "corner marker (along its arm, from the vertex); or two variables the "
                     "row runs between (from the first)",
                     ["line", "zone", "stand", "pallet", "container", "corner"], many=True)],
        factors=[SubtaskFactor(
            name="along",
            description="line up the {objects} in a row along the {line}",
            goal=Row(objects=["objects"], along=["line"]),
        )],
    ),
]

#: Where ``to_line_end`` puts an object: 12 cm along a line from its centre (the
#: far end of a 30 cm line, the object's centre 3 cm inside the end).
LINE_END = 0.12
#: Half the side of the square that ``square_around`` lays out (centres 9 cm apart:
#: 4 cm blocks with 5 cm between them, clear of a 4 cm block at the centre).
SQUARE_HALF = 0.045

_TEMPLATE_LIST += [
    SubtaskTemplate(
        name="to_line_end",
        description="Move the {objects} to the far end of the {line}.",
        slots=[_objects("the object to move along the line"),
               slot("line", "the line whose end is the goal (30 cm long)", ["line"])],
        factors=[SubtaskFactor(
            name="line_end",
            description="move the {objects} to the far end of the {line}",
            goal=AtPose(objects=["objects"], frame="line", check_yaw=False,
                        poses=[TargetPose(x=LINE_END, y=0.0)]),
        )],
    ),
    SubtaskTemplate(
        name="square_around",
        description="Place the {objects} on the four corners of a square centred on the "
                    "{center}: first top left, then top right, bottom left, bottom right.",
        slots=[_objects("four objects: top left, top right, bottom left, bottom right"),
               slot("center", "what the square is centred on (it rests on it if it is "
                     "a support, e.g. a pallet)",
                     ["pallet", "zone", "kit", "stand", "block", "box", "cylinder"])],
        factors=[SubtaskFactor(
            name="square",
            description="place the {objects} on the corners of a square centred on the "
                        "{center}",
            goal=AtPose(objects=["objects"], frame="center", check_yaw=False,
                        poses=[TargetPose(x=x, y=y) for x, y in
                               ((SQUARE_HALF, SQUARE_HALF), (SQUARE_HALF, -SQUARE_HALF),
                                (-SQUARE_HALF, SQUARE_HALF), (-SQUARE_HALF, -SQUARE_HALF))],
                        matches=[[int(i == j) for j in range(4)] for i in range(4)]),
        )],
    ),
]

#: Template name -> template. Every template here is used by >= 2 library tasks.
TEMPLATES: dict[str, SubtaskTemplate] = {t.name: t for t in _TEMPLATE_LIST}


def template_names() -> list[str]:
    """Names of the library's templates, in registry order."""
    return list(TEMPLATES)


def get_template(name: str) -> SubtaskTemplate:
    """The template called ``name``.

    Raises:
        CompositionError: no such template; the message lists the valid names.
    """
    try:
        return TEMPLATES[name]
    except KeyError:
        raise CompositionError(
            f"unknown subtask template {name!r}; templates: {', '.join(TEMPLATES)}"
        ) from None


def match_pairs(
    template: str | SubtaskTemplate,
    pairs: Sequence[tuple[StateVariable, StateVariable]],
    *,
    object_slot: str = "objects",
    target_slot: str | None = None,
    sequential: bool = False,
) -> list[TaskGraph]:
    """Instantiate a two-slot template once per (objects, target) pair.

    This is how sorting by colour is written: ``put_in_container`` for the red
    block and the red bowl, again for the blue pair, and so on.

    Args:
        template: The template (or its name); it must have exactly two slots.
        pairs: (variable bound to ``object_slot``, variable bound to the other slot).
        object_slot: The slot that receives the moved variable.
        target_slot: The other slot (default: the template's remaining slot).
        sequential: Order the instances: each comes after the previous one.

    Returns:
        One fragment per pair, ready for :func:`factask.graph.compose`.
    """
    tpl = get_template(template) if isinstance(template, str) else template
    others = [s.name for s in tpl.slots if s.name != object_slot]
    if target_slot is None:
        if len(others) != 1:
            raise CompositionError(
                f"template {tpl.name!r} has slots {[s.name for s in tpl.slots]}; "
                "match_pairs needs exactly two (or pass target_slot)"
            )
        target_slot = others[0]
    fragments: list[TaskGraph] = []
    for obj, target in pairs:
        after = fragments[-1].factor_names() if sequential and fragments else []
        fragments.append(tpl.instantiate(after=after, **{object_slot: obj, target_slot: target}))
    return fragments
