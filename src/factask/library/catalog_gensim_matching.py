"""GenSim tasks that match objects to targets of their colour on the table: zones,
stands, pallets, corner markers, and objects on top of other objects.

Each task pairs objects with targets through
:func:`~factask.library.templates.match_pairs` over one template
(``place_in_zone``, ``place_on_top``, ``palletize_layer``, ``align_to_corner``).
"""

from __future__ import annotations

from factask.graph import StateVariable, TaskGraph
from factask.library.builders import (
    assemble,
    at,
    barrier,
    colored,
    region,
    register,
    start_inside,
    start_on,
    use,
    var,
)
from factask.library.conventions import BALL, BLOCK, CORNER, CYLINDER, FOUR, NEAR, THREE, ZONE
from factask.library.templates import match_pairs

#: A squat cylinder wide enough to carry a block on its top.
PEDESTAL = (0.05, 0.05, 0.04)
#: A ball needs a wider top: released by the arm it may roll a centimetre or two.
BALL_PEDESTAL = (0.08, 0.08, 0.04)
STAND = (0.07, 0.07, 0.005)
SMALL_PALLET = (0.12, 0.12, 0.02)
#: Four spots (top left, top right, bottom left, bottom right as seen from the robot).
SQUARE = ((0.65, 0.22), (0.65, -0.22), (0.40, 0.22), (0.40, -0.22))
ROW4 = ((0.64, 0.3), (0.64, 0.1), (0.64, -0.1), (0.64, -0.3))


def _match(name: str, description: str, template: str, objects: list[StateVariable],
           targets: list[StateVariable], *, sequential: bool = False,
           extra: list[StateVariable] | None = None) -> TaskGraph:
    """Colour matching: each object onto/into the target at the same index."""
    return assemble(name, description,
                    match_pairs(template, list(zip(objects, targets, strict=True)),
                                sequential=sequential),
                    extra=extra or [])


# ------------------------------------------------------------------------ zones
@register("colored-cylinder-zone-sorting", family="sorting")
def colored_cylinder_zone_sorting() -> TaskGraph:
    return _match("colored-cylinder-zone-sorting",
                  "Pick up each of the red, blue and green cylinders and place it in the zone "
                  "of the same colour.", "place_in_zone",
                  colored("cylinder", THREE, CYLINDER), colored("zone", THREE, ZONE))


@register("align-cylinder-in-zone", family="placing")
def align_cylinder_in_zone() -> TaskGraph:
    zones = colored("zone", ("green", "yellow"), ZONE)
    return _match("align-cylinder-in-zone",
                  "Place the red cylinder in the green zone and the blue cylinder in the "
                  "yellow zone, leaving the other coloured zones as they are.", "place_in_zone",
                  colored("cylinder", ("red", "blue"), CYLINDER), zones,
                  extra=colored("zone", ("red", "blue"), ZONE,
                                description="a distractor zone"))


@register("align-balls-in-colored-zones", family="sorting")
def align_balls_in_colored_zones() -> TaskGraph:
    colors = ("red", "blue", "green", "yellow", "orange", "purple")
    # The zones stand in a straight line, so the balls end up in one.
    zones = [var(f"{c}_zone", "zone", c, (0.11, 0.11, 0.001), initial=at(0.58, 0.3 - 0.12 * k))
             for k, c in enumerate(colors)]
    return _match("align-balls-in-colored-zones",
                  "Pick up each of six balls and place it in the zone of the same colour; the "
                  "zones run in a straight line, so the balls end up in one.", "place_in_zone",
                  colored("ball", colors, BALL, initial=NEAR), zones)


@register("color-coordinated-cylinder-alignment", family="sorting")
def color_coordinated_cylinder_alignment() -> TaskGraph:
    colors = ("red", "green", "blue", "yellow", "orange")
    zones = [var(f"{c}_zone", "zone", c, (0.10, 0.10, 0.001), initial=at(0.64, 0.36 - 0.18 * k))
             for k, c in enumerate(colors)]
    # GenSim starts each cylinder in a zone of another colour; factask's layout keeps
    # objects off markers at reset, so they start in a strip in front of the zones
    # (as insertion-in-color-sequenced-zones does; see docs/library.md).
    return _match("color-coordinated-cylinder-alignment",
                  "Move each of five cylinders into the zone of its own colour; the zones "
                  "run in a row.", "place_in_zone",
                  colored("cylinder", colors, CYLINDER, initial=NEAR), zones)


def _zones_beyond_barrier(name: str, description: str, kind: str,
                          size: tuple[float, ...]) -> TaskGraph:
    zones = [var(f"{c}_zone", "zone", c, ZONE, initial=at(*xy))
             for c, xy in zip(FOUR, ROW4, strict=True)]
    return _match(name, description, "place_in_zone",
                  colored(kind, FOUR, size, initial=NEAR), zones, extra=barrier(0.52))


@register("ball-sorting-with-blocks-barrier", family="sorting", tags=("barrier",))
def ball_sorting_with_blocks_barrier() -> TaskGraph:
    return _zones_beyond_barrier("ball-sorting-with-blocks-barrier",
                                 "Pick up each ball and place it in the zone of the same "
                                 "colour, reaching over the barrier without knocking it.",
                                 "ball", BALL)


@register("align-cylinders-in-zones", family="sorting", tags=("barrier",))
def align_cylinders_in_zones() -> TaskGraph:
    return _zones_beyond_barrier("align-cylinders-in-zones",
                                 "Place each of four cylinders in the zone of its colour; a "
                                 "low barrier lies between the cylinders and the zones.",
                                 "cylinder", CYLINDER)


@register("color-sequenced-sphere-placement", family="sorting")
def color_sequenced_sphere_placement() -> TaskGraph:
    # GenSim's coloured squares are flat square markers: factask zones.
    squares = [var(f"{c}_square", "zone", c, ZONE, description=f"the {c} square marker")
               for c in FOUR]
    spheres = [var(f"{c}_sphere", "ball", c, BALL) for c in FOUR]
    return _match("color-sequenced-sphere-placement",
                  "Place each sphere in the centre of the square of the same colour, in the "
                  "order red, blue, green, yellow.", "place_in_zone", spheres, squares,
                  sequential=True)


@register("align-cylinders-in-square", family="placing")
def align_cylinders_in_square() -> TaskGraph:
    zones = [var(f"{c}_zone", "zone", c, (0.08, 0.08, 0.001), initial=at(*xy))
             for c, xy in zip(FOUR, SQUARE, strict=True)]
    return _match("align-cylinders-in-square",
                  "Place four cylinders on the corners of a square, each in the corner zone "
                  "of its colour: red top left, blue top right, green bottom left, yellow "
                  "bottom right.", "place_in_zone",
                  colored("cylinder", FOUR, CYLINDER, initial=region((0.45, 0.6), (-0.12, 0.12))),
                  zones)


# ----------------------------------------------------------------------- stands
@register("sphere-align-stand", family="sorting")
def sphere_align_stand() -> TaskGraph:
    colors = ("red", "blue", "green", "yellow", "orange")
    return _match("sphere-align-stand",
                  "Pick up each of five spheres and place it on the stand of the same colour.",
                  "place_on_top", [var(f"{c}_sphere", "ball", c, BALL) for c in colors],
                  colored("stand", colors, STAND))


@register("color-coordinated-cylinder-stand-stack", family="sorting")
def color_coordinated_cylinder_stand_stack() -> TaskGraph:
    return _match("color-coordinated-cylinder-stand-stack",
                  "Pick up each of the red, blue and green cylinders and place it on top of "
                  "the stand of the same colour.", "place_on_top",
                  colored("cylinder", THREE, CYLINDER), colored("stand", THREE, STAND))


@register("cylinder-stand-alignment", family="sorting")
def cylinder_stand_alignment() -> TaskGraph:
    return _match("cylinder-stand-alignment",
                  "Place four coloured cylinders on the four stands of matching colour, which "
                  "stand in a random order, in the order red, blue, green, yellow.",
                  "place_on_top", colored("cylinder", FOUR, CYLINDER),
                  colored("stand", FOUR, STAND), sequential=True)


@register("color-coordinated-cylinder-stand-assembly", family="sorting")
def color_coordinated_cylinder_stand_assembly() -> TaskGraph:
    return _match("color-coordinated-cylinder-stand-assembly",
                  "Pick up each of four cylinders and place it on top of the stand of the "
                  "same colour, forming four cylinder-and-stand pairs.", "place_on_top",
                  colored("cylinder", FOUR, CYLINDER), colored("stand", FOUR, STAND))


# ---------------------------------------------------------------------- pallets
@register("sorting-blocks-into-pallets", family="pallets")
def sorting_blocks_into_pallets() -> TaskGraph:
    pallets = [var(f"{c}_pallet", "pallet", c, SMALL_PALLET, initial=at(*xy))
               for c, xy in zip(FOUR, ROW4, strict=True)]
    return _match("sorting-blocks-into-pallets",
                  "Pick up blocks of four colours and place each on the pallet of the same "
                  "colour; the pallets stand in a row.", "palletize_layer",
                  colored("block", FOUR, BLOCK, initial=NEAR), pallets)


@register("color-coordinated-block-insertion-in-pallets", family="pallets")
def color_coordinated_block_insertion_in_pallets() -> TaskGraph:
    return _match("color-coordinated-block-insertion-in-pallets",
                  "Pick up each coloured block and place it on the pallet of the same colour "
                  "in the order red, blue, green, yellow.", "palletize_layer",
                  colored("block", FOUR, BLOCK), colored("pallet", FOUR, SMALL_PALLET),
                  sequential=True)


# ------------------------------------------------------------- on other objects
def _on_pedestals(name: str, description: str, kind: str, size: tuple[float, ...],
                  colors: tuple[str, ...] = FOUR, sequential: bool = False,
                  extra: list[StateVariable] | None = None,
                  pedestals: list[StateVariable] | None = None) -> TaskGraph:
    """Each object on top of the squat cylinder of its colour."""
    top = BALL_PEDESTAL if kind in ("ball", "sphere") else PEDESTAL
    peds = pedestals or colored("cylinder", colors, top)
    objs = [var(f"{c}_{kind}", "ball" if kind == "sphere" else kind, c, size) for c in colors]
    return _match(name, description, "place_on_top", objs, peds, sequential=sequential,
                  extra=extra)


@register("color-coordinated-sphere-and-cylinder-assembly", family="sorting")
def color_coordinated_sphere_and_cylinder_assembly() -> TaskGraph:
    return _on_pedestals("color-coordinated-sphere-and-cylinder-assembly",
                         "Pick up each of four spheres and place it on top of the cylinder "
                         "of the same colour, forming four sphere-and-cylinder pairs.",
                         "sphere", BALL)


@register("color-coordinated-cylinder-ball-match", family="sorting")
def color_coordinated_cylinder_ball_match() -> TaskGraph:
    return _on_pedestals("color-coordinated-cylinder-ball-match",
                         "Pick up each ball and place it on top of the cylinder of the same "
                         "colour without the ball rolling off.", "ball", BALL)


@register("cylinder-ring-stack", family="sorting")
def cylinder_ring_stack() -> TaskGraph:
    return _on_pedestals("cylinder-ring-stack",
                         "Pick up each of four blocks and stack it on top of the cylinder of "
                         "the same colour.", "block", BLOCK)


@register("block-on-cylinder-on-pallet", family="sorting", tags=("starts-on-pallet",))
def block_on_cylinder_on_pallet() -> TaskGraph:
    pallet = var("pallet", "pallet", "brown", (0.30, 0.25, 0.0375), description="the pallet",
                 initial=at(0.55, 0.0))
    peds = colored("cylinder", FOUR, PEDESTAL, initial=start_on(pallet))
    return _on_pedestals("block-on-cylinder-on-pallet",
                         "Pick up each block and place it on the cylinder of the same colour; "
                         "the cylinders stand on a pallet.", "block", BLOCK,
                         pedestals=peds, extra=[pallet])


@register("ball-on-box-on-container", family="sorting", tags=("starts-inside",))
def ball_on_box_on_container() -> TaskGraph:
    box = var("container", "container", "brown", (0.24, 0.24, 0.05),
              description="the container the boxes stand in", initial=at(0.55, 0.0))
    boxes = colored("box", THREE, (0.05, 0.05, 0.06), initial=start_inside(box))
    return _on_pedestals("ball-on-box-on-container",
                         "Pick up each ball and place it on the box of the same colour; the "
                         "boxes stand inside a container.", "ball", BALL, colors=THREE,
                         pedestals=boxes, extra=[box])


@register("code-blue-on-red-cylinder", family="placing")
def code_blue_on_red_cylinder() -> TaskGraph:
    return assemble(
        "code-blue-on-red-cylinder", "Place the blue box on top of the red cylinder.",
        use("place_on_top", objects=var("blue_box", "box", "blue", (0.05, 0.05, 0.04)),
            support=var("red_cylinder", "cylinder", "red", (0.06, 0.06, 0.05))))


# ---------------------------------------------------------------------- corners
def _corners(colors: tuple[str, ...], spots: tuple[tuple[float, float], ...] = SQUARE
             ) -> list[StateVariable]:
    return [var(f"{c}_corner", "corner", c, CORNER, initial=at(*xy))
            for c, xy in zip(colors, spots, strict=True)]


@register("align-cylinder-in-corner", family="corners")
def align_cylinder_in_corner() -> TaskGraph:
    return assemble(
        "align-cylinder-in-corner",
        "Align the blue cylinder to the L-shaped corner marker on the tabletop.",
        use("align_to_corner", objects=var("blue_cylinder", "cylinder", "blue", CYLINDER),
            corner=var("corner", "corner", "green", CORNER,
                       description="the L-shaped corner marker")))


@register("cylinder-corner-insert", family="corners")
def cylinder_corner_insert() -> TaskGraph:
    return _match("cylinder-corner-insert",
                  "Place each of four coloured cylinders into the corner marked in its colour.",
                  "align_to_corner", colored("cylinder", FOUR, CYLINDER), _corners(FOUR))


@register("corner-sort-cylinders", family="corners")
def corner_sort_cylinders() -> TaskGraph:
    return _match("corner-sort-cylinders",
                  "Pick up cylinders of four colours and place each into the corner marked in "
                  "its colour; each corner takes one cylinder.", "align_to_corner",
                  colored("cylinder", FOUR, CYLINDER), _corners(FOUR))


@register("color-coordinated-corner-placement", family="corners")
def color_coordinated_corner_placement() -> TaskGraph:
    return _match("color-coordinated-corner-placement",
                  "Pick up each cylinder and place it into the corner of the same colour, in "
                  "the order red, blue, green, yellow.", "align_to_corner",
                  colored("cylinder", FOUR, CYLINDER), _corners(FOUR), sequential=True)


@register("colored-balls-sorting-in-corner", family="corners", tags=("starts-mismatched",))
def colored_balls_sorting_in_corner() -> TaskGraph:
    # Each ball starts beside the corner of the next colour (not on its vertex, so
    # the corner it belongs in is free for its own ball).
    balls = [var(f"{c}_ball", "ball", c, BALL,
                 initial=at(SQUARE[(k + 1) % 4][0] + 0.06, SQUARE[(k + 1) % 4][1] + 0.06))
             for k, c in enumerate(FOUR)]
    return _match("colored-balls-sorting-in-corner",
                  "Each ball starts at a corner of another colour; move each into the corner "
                  "of its own colour in the order red, blue, green, yellow.",
                  "align_to_corner", balls, _corners(FOUR), sequential=True)


@register("color-cued-ball-corner-sorting", family="corners", tags=("barrier",))
def color_cued_ball_corner_sorting() -> TaskGraph:
    # The rectangular zone in the middle of the table, fenced by two low bars (GenSim's
    # small blocks) that the balls must be carried around or over.
    middle = var("middle_zone", "zone", "gray", (0.14, 0.14, 0.001), initial=at(0.52, 0.0),
                 description="the fenced zone in the middle of the table")
    fence = [var(f"fence_{k}", "box", "gray", (0.14, 0.02, 0.02), fixed=True,
                 initial=at(0.52, y, 0.0), description="a low bar fencing the middle zone")
             for k, y in enumerate((0.08, -0.08))]
    return _match("color-cued-ball-corner-sorting",
                  "Pick up each ball and place it precisely in the corner of the same colour, "
                  "without touching the low bars that fence the zone in the middle.",
                  "align_to_corner", colored("ball", FOUR, BALL), _corners(FOUR),
                  extra=[middle, *fence])


@register("color-matching-blocks-to-corner-and-zone", family="corners", tags=("milestones",))
def color_matching_blocks_to_corner_and_zone() -> TaskGraph:
    blocks = colored("block", FOUR, BLOCK)
    corners = _corners(FOUR, ((0.65, 0.3), (0.65, 0.1), (0.65, -0.1), (0.65, -0.3)))
    zones = [var(f"{c}_zone", "zone", c, (0.10, 0.10, 0.001), initial=at(0.38, y))
             for c, y in zip(FOUR, (0.3, 0.1, -0.1, -0.3), strict=True)]
    first = [use("align_to_corner", objects=b, corner=c, milestone=True)
             for b, c in zip(blocks, corners, strict=True)]
    then = [use("place_in_zone", objects=b, zone=z, after=[f])
            for b, z, f in zip(blocks, zones, first, strict=True)]
    return assemble("color-matching-blocks-to-corner-and-zone",
                    "Pick each block and place it on the corner of its colour, then move it "
                    "on to the zone of the same colour.", first, then)
