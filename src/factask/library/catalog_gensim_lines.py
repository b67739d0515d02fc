"""GenSim tasks about lines and squares: objects along lines, to a line's far end,
on the corners of a square, in rows of zones.

Lines are flat markers 30 cm long lying along their own x axis; ``to_line_end``
targets 12 cm along that axis, so an object that starts beside one end goes to
the other.
"""

from __future__ import annotations

from factask.graph import StateVariable, SubtaskFactor, SubtaskTemplate, TaskGraph
from factask.library.builders import (
    assemble,
    at,
    colored,
    region,
    register,
    start_on,
    use,
    var,
)
from factask.library.conventions import BALL, BLOCK, CORNER, CYLINDER, FIVE, FOUR, LINE, NEAR
from factask.library.templates import match_pairs, slot
from factask.relations import AtPose, TargetPose
from factask.scene.objects import corner_arm_width

PALLET = (0.20, 0.20, 0.0375)
#: A pallet with room for four slot frames side by side.
WIDE_PALLET = (0.26, 0.26, 0.0375)


def _lines(colors: tuple[str, ...], x: float = 0.52, step: float = 0.18
           ) -> list[StateVariable]:
    """Parallel lines (along x), left (+y) to right, one per colour."""
    first = step * (len(colors) - 1) / 2
    return [var(f"{c}_line", "line", c, LINE, initial=at(x, first - k * step))
            for k, c in enumerate(colors)]


def _beside_line_starts(kind: str, colors: tuple[str, ...], size: tuple[float, ...],
                        lines: list[StateVariable]) -> list[StateVariable]:
    """One object per line, starting beside its near end (off the marker: the layout
    keeps objects off markers at reset)."""
    out = []
    for c, line in zip(colors, lines, strict=True):
        pose = line.initial
        out.append(var(f"{c}_{kind}", kind, c, size,
                       initial=at(pose.x - 0.12, pose.y - 0.05)))  # type: ignore[union-attr]
    return out


def _to_line_ends(name: str, description: str, colors: tuple[str, ...],
                  sequential: bool) -> TaskGraph:
    lines = _lines(colors)
    blocks = _beside_line_starts("block", colors, BLOCK, lines)
    return assemble(name, description,
                    match_pairs("to_line_end", list(zip(blocks, lines, strict=True)),
                                sequential=sequential))


@register("guided-block-path", family="lines")
def guided_block_path() -> TaskGraph:
    return _to_line_ends("guided-block-path",
                         "Move each of four blocks from the start of the line of its colour to "
                         "the line's far end.", FOUR, sequential=False)


@register("color-coordinated-line-blocks", family="lines")
def color_coordinated_line_blocks() -> TaskGraph:
    return _to_line_ends("color-coordinated-line-blocks",
                         "Each of five blocks lies at one end of the line of its colour; move "
                         "each to the other end, in the order red, blue, green, yellow, "
                         "orange.", FIVE, sequential=True)


@register("place-blue-on-line-ends", family="lines")
def place_blue_on_line_ends() -> TaskGraph:
    lines = [var(f"green_line_{k}", "line", "green", LINE, initial=at(0.55, y))
             for k, y in ((1, 0.2), (2, -0.2))]
    boxes = [var(f"blue_box_{k}", "box", "blue", (0.05, 0.05, 0.05)) for k in (1, 2)]
    return assemble("place-blue-on-line-ends",
                    "Pick up each blue box and place it at the end of a green line.",
                    match_pairs("to_line_end", list(zip(boxes, lines, strict=True))))


@register("align-blocks-on-line", family="lines")
def align_blocks_on_line() -> TaskGraph:
    lines = _lines(FOUR, x=0.55, step=0.2)
    blocks = colored("block", FOUR, BLOCK)
    return assemble("align-blocks-on-line",
                    "Pick up each of four blocks and align it along the line of the same "
                    "colour, in the order red, blue, green, yellow.",
                    match_pairs("align_along_line", list(zip(blocks, lines, strict=True)),
                                sequential=True))


@register("cylinder-line-placement", family="lines")
def cylinder_line_placement() -> TaskGraph:
    colors = ("red", "blue", "green", "yellow", "orange", "purple")
    line = var("green_line", "line", "green", (0.34, 0.01, 0.001), description="the green line")
    return assemble("cylinder-line-placement",
                    "Place six cylinders on top of the green line in the order red, blue, "
                    "green, yellow, orange, purple.",
                    use("align_along_line", objects=colored("cylinder", colors,
                                                            (0.04, 0.04, 0.05)), line=line))


@register("color-sorted-block-race", family="sorting")
def color_sorted_block_race() -> TaskGraph:
    pairs = []
    for color, x in (("blue", 0.68), ("red", 0.58)):
        # The blocks start at the near end of the table, the zones run in a line at the far end.
        blocks = [var(f"{color}_block_{k + 1}", "block", color, BLOCK,
                      initial=region((0.27, 0.4), (-0.4, 0.4))) for k in range(3)]
        zones = [var(f"{color}_zone_{k + 1}", "zone", color, (0.07, 0.07, 0.001),
                     initial=at(x, 0.15 - 0.15 * k)) for k in range(3)]
        pairs += list(zip(blocks, zones, strict=True))
    return assemble("color-sorted-block-race",
                    "Carry three blue and three red blocks from the near end of the table to "
                    "the two lines of three small zones of their colour at the far end, one "
                    "block per zone.", match_pairs("place_in_zone", pairs))


@register("color-matching-block-in-pallet", family="pallets")
def color_matching_block_in_pallet() -> TaskGraph:
    pallet = var("pallet", "pallet", "brown", PALLET, description="the pallet")
    return assemble("color-matching-block-in-pallet",
                    "Arrange four blocks on the pallet in a square: red top left, blue top "
                    "right, green bottom left, yellow bottom right.",
                    use("square_around", objects=colored("block", FOUR, BLOCK), center=pallet))


@register("palette-color-match", family="pallets")
def palette_color_match() -> TaskGraph:
    pallet = var("pallet", "pallet", "brown", WIDE_PALLET, description="the pallet")
    order = ("blue", "yellow", "green", "red")
    # The slots are low open frames standing on the pallet (a zone cannot lie on top
    # of a pallet in factask's layout).
    slots = {c: var(f"{c}_slot", "fixture", c, (0.07, 0.07, 0.02), initial=start_on(pallet),
                    description=f"the {c} slot on the pallet") for c in order}
    balls = {c: var(f"{c}_ball", "ball", c, BALL) for c in order}
    return assemble("palette-color-match",
                    "Place each ball in the slot of its colour on the pallet, in the order "
                    "blue, yellow, green, red.",
                    match_pairs("put_in_container", [(balls[c], slots[c]) for c in order],
                                sequential=True), extra=[pallet])


@register("construct-corner-building", family="structures")
def construct_corner_building() -> TaskGraph:
    site = var("site_zone", "zone", "gray", (0.08, 0.08, 0.001), initial=at(0.55, 0.0),
               description="where the building's centre goes")
    red, green, blue, orange, yellow = colored("block", ("red", "green", "blue", "orange",
                                                         "yellow"), BLOCK)
    centre = use("place_in_zone", objects=red, zone=site)
    # Clockwise from the top left: green, blue, orange (bottom right), yellow (bottom
    # left); the template lists top left, top right, bottom left, bottom right.
    return assemble("construct-corner-building",
                    "Put the red block at the centre, then the green, blue, orange and yellow "
                    "blocks clockwise on the corners of a square around it.",
                    centre, use("square_around", objects=[green, blue, yellow, orange],
                                center=red, after=[centre]))


@register("align-cylinders-box", family="lines")
def align_cylinders_box() -> TaskGraph:
    box = var("box", "container", "brown", (0.20, 0.10, 0.08), description="the open box")
    return assemble("align-cylinders-box",
                    "Stand three cylinders upright in a row inside the box: red on the left, "
                    "green in the middle, blue on the right.",
                    use("align_along_line", objects=colored("cylinder", ("red", "green", "blue"),
                                                            (0.04, 0.04, 0.06)), line=box))


#: A corner marker whose arm a row of four blocks fits along (19 cm from the vertex).
LONG_CORNER = (0.22, 0.22, 0.001)


@register("color-coded-blocks-on-corner", family="corners")
def color_coded_blocks_on_corner() -> TaskGraph:
    corner = var("corner", "corner", "gray", LONG_CORNER, description="the corner structure")
    return assemble("color-coded-blocks-on-corner",
                    "Line up the red, blue, green and yellow blocks in a straight row along "
                    "the corner, red at the corner's vertex and yellow at the far end.",
                    use("align_along_line", objects=colored("block", FOUR, BLOCK), line=corner))


@register("put-blocks-between-zones", family="lines")
def put_blocks_between_zones() -> TaskGraph:
    zones = [var(f"{side}_zone", "zone", "gray", (0.12, 0.12, 0.001),
                 initial=region((0.45, 0.6), ys), description=f"the {side} zone")
             for side, ys in (("left", (0.22, 0.3)), ("right", (-0.3, -0.22)))]
    return assemble("put-blocks-between-zones",
                    "Arrange the red, blue, green and yellow blocks in a row between the two "
                    "zones, red nearest the left zone.",
                    use("align_along_line", objects=colored("block", FOUR, BLOCK, initial=NEAR),
                        line=zones))


def _square_edges(colors: tuple[str, ...], x: float = 0.5, y: float = 0.0,
                  side: float = 0.30) -> list[StateVariable]:
    """A square outline of four line markers, one colour per edge: far (+x), left
    (+y), near (-x), right (-y)."""
    h = (side - LINE[1]) / 2
    spots = ((x + h, y, 90.0), (x, y + h, 0.0), (x - h, y, 90.0), (x, y - h, 0.0))
    return [var(f"{c}_edge", "line", c, (side, LINE[1], LINE[2]), initial=at(*spot),
                description=f"the {c} edge of the square") for c, spot in zip(colors, spots,
                                                                             strict=True)]


@register("colored-cylinder-in-square", family="lines")
def colored_cylinder_in_square() -> TaskGraph:
    # GenSim's square has an edge per colour but five cylinders: its code puts the
    # fifth (orange) in the middle, here between the far and near edges.
    edges = _square_edges(FOUR)
    cylinders = colored("cylinder", (*FOUR, "orange"), CYLINDER)
    along = [use("align_along_line", objects=c, line=e)
             for c, e in zip(cylinders[:4], edges, strict=True)]
    return assemble("colored-cylinder-in-square",
                    "Put the red, blue, green and yellow cylinders on the middle of the edge "
                    "of the square of their colour, and the orange one in the middle of the "
                    "square, between its red and green edges.",
                    along, use("align_along_line", objects=cylinders[4],
                               line=[edges[0], edges[2]]))


#: The corner marker's inner vertex in its own frame (x = y), see corner_vertex.
_VERTEX = -CORNER[0] / 2 + corner_arm_width(CORNER)
#: Between the two base blocks along the corner's arms (they would touch corners).
_BASE_GAP = 0.002
#: A base block's centre along its arm, from the vertex: the square at the junction
#: stays open, a block's side plus the gap.
_ALONG = BLOCK[0] * 1.5 + _BASE_GAP
#: The top block's centre from the vertex (on the diagonal): over the open square's
#: far corner, resting on one corner of each base block (1.9 x 1.9 cm each).
_JUNCTION = BLOCK[0] + _BASE_GAP / 2

#: A corner of blocks: two along the corner's arms, one bridging them at the junction.
#: One task uses it (not registered, see templates.TEMPLATES).
_CORNER_JUNCTION = SubtaskTemplate(
    name="corner_junction",
    description="Put the {base} along the two arms of the {corner} and the {top} on both "
                "of them where the arms meet.",
    slots=[slot("base", "two blocks, one per arm", ["block"], many=True, movable=True),
           slot("top", "the block bridging them", ["block"], movable=True),
           slot("corner", "the corner marker", ["corner"])],
    factors=[
        SubtaskFactor(
            name="base", description="put the {base} along the two arms of the {corner}",
            goal=AtPose(objects=["base"], frame="corner", check_yaw=False, poses=[
                TargetPose(x=_VERTEX + _ALONG, y=_VERTEX + BLOCK[1] / 2),
                TargetPose(x=_VERTEX + BLOCK[0] / 2, y=_VERTEX + _ALONG)])),
        SubtaskFactor(
            name="junction", description="put the {top} on the {base} where the arms meet",
            after=["base"],
            # Its height is given: its centre is over the open square, not over a block.
            goal=AtPose(objects=["top"], frame="corner", check_yaw=False, poses=[
                TargetPose(x=_VERTEX + _JUNCTION, y=_VERTEX + _JUNCTION,
                           z=BLOCK[2] * 1.5 - CORNER[2] / 2)])),
    ],
)


@register("construct-corner-blocks", family="corners")
def construct_corner_blocks() -> TaskGraph:
    corner = var("corner", "corner", "gray", CORNER, description="the corner marker")
    reds = var("red_blocks", "block", "red", BLOCK, count=2)
    green, blue = colored("block", ("green", "blue"), BLOCK)
    junction = _CORNER_JUNCTION.instantiate(prefix="corner", base=reds, top=green,
                                            corner=corner)
    return assemble("construct-corner-blocks",
                    "Build a corner of blocks: the two red blocks along the corner's two "
                    "arms, the green block on both of them where the arms meet, then the "
                    "blue block on top of the green one.",
                    junction, use("place_on_top", objects=blue, support=green,
                                  after=[junction]))
