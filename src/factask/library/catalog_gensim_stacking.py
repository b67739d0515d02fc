"""GenSim tasks that stack: towers on pallets, stands and cylinders, several columns,
small pyramids in zones, and little assemblies (cars, H-shapes, castles on a line).

Columns are ``stack_on_base``/``stack_column``; two-one pyramids are a row
(``align_along_line`` or ``build_row``) with a ``pyramid_layer`` on it.
"""

from __future__ import annotations

from collections.abc import Sequence

from factask.graph import StateVariable, TaskGraph
from factask.library.builders import (
    assemble,
    at,
    barrier,
    colored,
    region,
    register,
    start_inside,
    use,
    var,
)
from factask.library.conventions import BALL, BLOCK, CORNER, FIVE, FOUR
from factask.library.templates import match_pairs

PALLET = (0.30, 0.25, 0.0375)
STAND = (0.15, 0.05, 0.005)
#: A zone shaped for a base row of two blocks.
PAIR_ZONE = (0.12, 0.06, 0.001)


def _pallet(**extra: object) -> StateVariable:
    return var("pallet", "pallet", "brown", PALLET, description="the pallet", **extra)


def _tower(name: str, description: str, layers: list[StateVariable],
           base: StateVariable) -> TaskGraph:
    return assemble(name, description, use("stack_on_base", layers=layers, base=base))


@register("build-block-tower-on-pallet", family="stacking")
def build_block_tower_on_pallet() -> TaskGraph:
    layers = [var(f"{c}_block_{k // 2 + 1}", "block", c, BLOCK)
              for k, c in enumerate(("red", "blue") * 3)]
    return _tower("build-block-tower-on-pallet",
                  "Stack six blocks (three red, three blue) on the pallet in alternating "
                  "colours, starting with a red block at the bottom.", layers, _pallet())


@register("color-coordinated-tower", family="stacking")
def color_coordinated_tower() -> TaskGraph:
    return _tower("color-coordinated-tower",
                  "Stack five blocks on the pallet: red at the bottom, then blue, green, "
                  "yellow and orange at the top.", colored("block", FIVE, BLOCK), _pallet())


@register("color-coordinated-cylinder-stacking", family="stacking")
def color_coordinated_cylinder_stacking() -> TaskGraph:
    return _tower("color-coordinated-cylinder-stacking",
                  "Stack the three cylinders on the pallet: red at the bottom, blue in the "
                  "middle, green on top.",
                  colored("cylinder", ("red", "blue", "green"), (0.05, 0.05, 0.04)), _pallet())


@register("color-coordinated-box-in-pallet", family="stacking")
def color_coordinated_box_in_pallet() -> TaskGraph:
    return _tower("color-coordinated-box-in-pallet",
                  "Stack four boxes on the pallet in the colour sequence red at the bottom, "
                  "then blue, green and yellow.",
                  colored("box", ("red", "blue", "green", "yellow"), (0.06, 0.06, 0.04)),
                  _pallet())


@register("color-coordinated-cylinder-pyramid", family="stacking")
def color_coordinated_cylinder_pyramid() -> TaskGraph:
    # GenSim calls it a pyramid but gives one bottom-to-top sequence of five single
    # cylinders: a column (see docs/library.md).
    return _tower("color-coordinated-cylinder-pyramid",
                  "Stack five cylinders on the square pallet, from bottom to top orange, "
                  "blue, green, yellow and red.",
                  colored("cylinder", ("orange", "blue", "green", "yellow", "red"),
                          (0.05, 0.05, 0.03)),
                  var("pallet", "pallet", "brown", (0.2, 0.2, 0.0375),
                      description="the square pallet"))


@register("nested-boxes", family="stacking")
def nested_boxes() -> TaskGraph:
    big = var("yellow_box", "container", "yellow", (0.16, 0.16, 0.12),
              description="the large open yellow box")
    return _tower("nested-boxes",
                  "Place three smaller boxes inside the large yellow box: blue at the bottom, "
                  "then red, then green on top.",
                  colored("box", ("blue", "red", "green"), (0.07, 0.07, 0.03)), big)


@register("color-ordered-blocks-on-pallet", family="pallets")
def color_ordered_blocks_on_pallet() -> TaskGraph:
    colors = ("red", "blue", "green", "yellow", "orange", "purple")
    pallet = _pallet()
    return assemble("color-ordered-blocks-on-pallet",
                    "Pick up six coloured blocks and place each on the pallet in the colour "
                    "sequence red, blue, green, yellow, orange, purple.",
                    match_pairs("palletize_layer",
                                [(b, pallet) for b in colored("block", colors, BLOCK)],
                                sequential=True))


@register("color-sorted-blocks-on-pallet-with-barrier", family="pallets", tags=("barrier",))
def color_sorted_blocks_on_pallet_with_barrier() -> TaskGraph:
    pallet = _pallet(initial=at(0.65, 0.0, 90.0))
    blocks = colored("block", ("red", "blue", "green", "yellow"), BLOCK,
                     initial=region((0.27, 0.42), (-0.4, 0.4)))
    return assemble("color-sorted-blocks-on-pallet-with-barrier",
                    "Carry each block over the low barrier and place it on the pallet in the "
                    "sequence red, blue, green, yellow.",
                    match_pairs("palletize_layer", [(b, pallet) for b in blocks],
                                sequential=True),
                    extra=barrier(0.49, 0.6))


@register("sort-and-stack-clr-blocks", family="stacking")
def sort_and_stack_clr_blocks() -> TaskGraph:
    pallet = _pallet()
    blocks = colored("block", ("red", "blue", "green", "yellow"), BLOCK)
    # First every block on the pallet (a milestone), then the stack that must hold.
    sort = use("palletize_layer", objects=blocks, pallet=pallet, milestone=True)
    return assemble("sort-and-stack-clr-blocks",
                    "Place the red, blue, green and yellow blocks on the pallet, then stack "
                    "them on the pallet: red at the bottom, then blue, green, yellow.",
                    sort, use("stack_on_base", layers=blocks, base=pallet, after=[sort]))


@register("colorful-block-tower-on-cylinder-base", family="stacking")
def colorful_block_tower_on_cylinder_base() -> TaskGraph:
    base = var("cylinder_base", "cylinder", "gray", (0.06, 0.06, 0.04),
               description="the cylindrical base")
    corner = var("corner", "corner", "green", CORNER, description="the corner of the table")
    place = use("align_to_corner", objects=base, corner=corner)
    blocks = colored("block", ("red", "blue", "green", "yellow"), BLOCK)
    return assemble("colorful-block-tower-on-cylinder-base",
                    "Put the cylindrical base in the corner, then stack four blocks on it: "
                    "red, blue, green and yellow from bottom to top.",
                    place, use("stack_on_base", layers=blocks, base=base, after=[place]))


@register("corner-block-challenge", family="stacking")
def corner_block_challenge() -> TaskGraph:
    fragments: list[TaskGraph] = []
    for side, y in (("left", 0.2), ("right", -0.2)):
        corner = var(f"{side}_corner", "corner", "gray", CORNER, initial=at(0.6, y))
        bottom = var(f"{side}_red_bottom", "block", "red", BLOCK)
        rest = [var(f"{side}_red_top", "block", "red", BLOCK),
                var(f"{side}_green_block", "block", "green", BLOCK),
                var(f"{side}_blue_block", "block", "blue", BLOCK)]
        first = use("align_to_corner", objects=bottom, corner=corner)
        fragments += [first, use("stack_on_base", layers=rest, base=bottom, after=[first])]
    return assemble("corner-block-challenge",
                    "Construct two columns of four cubes, each in a corner: two red cubes, "
                    "then a green and a blue one (eight cubes: four red, two green, two blue).",
                    fragments)


@register("color-coordinated-block-tower", family="stacking")
def color_coordinated_block_tower() -> TaskGraph:
    colors = ("red", "blue", "green")
    stands = [var(f"{c}_stand", "stand", c, (0.07, 0.07, 0.005)) for c in colors]
    towers = [use("stack_on_base", layers=var(f"{c}_blocks", "block", c, BLOCK, count=5),
                  base=s) for c, s in zip(colors, stands, strict=True)]
    return assemble("color-coordinated-block-tower",
                    "Stack the fifteen blocks onto three stands by colour: a red, a blue and a "
                    "green tower of five blocks each.",
                    towers)


@register("stack-color-coordinated-blocks", family="stacking")
def stack_color_coordinated_blocks() -> TaskGraph:
    pallet = _pallet()
    return assemble("stack-color-coordinated-blocks",
                    "Stack six blocks on the pallet in two stacks: red, blue, green from "
                    "bottom to top, and yellow, orange, purple.",
                    use("stack_on_base", layers=colored("block", ("red", "blue", "green"),
                                                        BLOCK), base=pallet),
                    use("stack_on_base", layers=colored("block", ("yellow", "orange", "purple"),
                                                        BLOCK), base=pallet))


@register("symmetric-block-stand-assembly", family="stacking")
def symmetric_block_stand_assembly() -> TaskGraph:
    fragments = []
    for side in ("left", "right"):
        stand = var(f"{side}_stand", "stand", "gray", STAND, description=f"the {side} stand")
        for low, high in (("blue", "red"), ("red", "blue")):
            layers = [var(f"{side}_{low}_base", "block", low, BLOCK),
                      var(f"{side}_{high}_on_{low}", "block", high, BLOCK)]
            fragments.append(use("stack_on_base", layers=layers, base=stand))
    return assemble("symmetric-block-stand-assembly",
                    "On each of two stands build two columns side by side: a red block on a "
                    "blue one and a blue block on a red one, the two stands alike.", fragments)


@register("build-cylinder-structure", family="structures")
def build_cylinder_structure() -> TaskGraph:
    base = var("square_base", "pallet", "gray", (0.15, 0.15, 0.02), description="the square base")
    return assemble("build-cylinder-structure",
                    "On the square base stand the red and blue cylinders side by side, the "
                    "yellow one on the red and the green one on the blue: an 'H'.",
                    use("stack_on_base", layers=colored("cylinder", ("red", "yellow"),
                                                        (0.04, 0.04, 0.04)), base=base),
                    use("stack_on_base", layers=colored("cylinder", ("blue", "green"),
                                                        (0.04, 0.04, 0.04)), base=base))


def _two_one_pyramid(color: str, zone: StateVariable | list[StateVariable],
                     after: Sequence[TaskGraph] = ()) -> list[TaskGraph]:
    """A pyramid of two blocks in a row on ``zone`` (a zone, pallet or container; or
    two variables: in the gap between them) and one bridging them, begun after the
    fragments ``after``."""
    base = var(f"{color}_base_blocks", "block", color, BLOCK, count=2)
    top = var(f"{color}_top_block", "block", color, BLOCK)
    return [use("align_along_line", objects=base, line=zone, after=after),
            use("pyramid_layer", layer=top, below=base)]


@register("color-coordinated-block-pyramid-construction", family="structures")
def color_coordinated_block_pyramid_construction() -> TaskGraph:
    zones = [var(f"{side}_zone", "zone", "gray", PAIR_ZONE, initial=at(0.55, y),
                 description=f"the {side} zone") for side, y in (("left", 0.2), ("right", -0.2))]
    return assemble("color-coordinated-block-pyramid-construction",
                    "Build two pyramids of two blocks with one on top: a red one in the left "
                    "zone and a blue one in the right zone.",
                    _two_one_pyramid("red", zones[0]), _two_one_pyramid("blue", zones[1]))


@register("color-coordinated-zone-stacking", family="structures")
def color_coordinated_zone_stacking() -> TaskGraph:
    colors = ("red", "blue", "green")
    zones = [var(f"{c}_zone", "zone", c, PAIR_ZONE, initial=at(0.6, y))
             for c, y in zip(colors, (0.3, 0.0, -0.3), strict=True)]
    return assemble("color-coordinated-zone-stacking",
                    "In each of three zones (red, blue, green from left to right) build a "
                    "pyramid of its colour: two blocks at the base, one on top.",
                    *[_two_one_pyramid(c, z) for c, z in zip(colors, zones, strict=True)])


@register("triangle-block-arrangement", family="structures")
def triangle_block_arrangement() -> TaskGraph:
    bottom = var("red_blocks", "block", "red", BLOCK, count=3)
    middle = var("green_blocks", "block", "green", BLOCK, count=2)
    top = var("blue_block", "block", "blue", BLOCK)
    return assemble("triangle-block-arrangement",
                    "Arrange red, green and blue blocks in a triangle: three red blocks in a "
                    "row, two green ones on them and one blue block on top.",
                    use("build_row", objects=bottom),
                    use("pyramid_layer", layer=middle, below=bottom),
                    use("pyramid_layer", layer=top, below=middle))


@register("color-coordinated-zone-arrangement", family="pallets", tags=("barrier",))
def color_coordinated_zone_arrangement() -> TaskGraph:
    colors = ("red", "blue", "green")
    # Narrow pallets: three blocks fit on one only in a line.
    pallets = [var(f"{c}_pallet", "pallet", c, (0.17, 0.06, 0.02), initial=at(0.66, y, 90.0))
               for c, y in zip(colors, (0.3, 0.0, -0.3), strict=True)]
    blocks = [var(f"{c}_blocks", "block", c, BLOCK, count=3,
                  initial=region((0.27, 0.45), (-0.42, 0.42))) for c in colors]
    return assemble("color-coordinated-zone-arrangement",
                    "Place the three blocks of each colour on the pallet of that colour, in a "
                    "line, carrying them over a low barrier.",
                    match_pairs("palletize_layer", list(zip(blocks, pallets, strict=True))),
                    extra=barrier(0.53, 0.9))


@register("assemble-single-car", family="structures")
def assemble_single_car() -> TaskGraph:
    body = var("blue_body", "box", "blue", (0.10, 0.06, 0.04), description="the large blue box")
    wheels = [var(f"green_wheel_{k}", "box", "green", (0.03, 0.03, 0.03),
                  description="a tiny green box: a wheel") for k in (1, 2)]
    roof = var("red_roof", "box", "red", (0.05, 0.05, 0.03), description="the smaller red box")
    return assemble("assemble-single-car",
                    "Build a mini car: the large blue box as the body with a tiny green wheel "
                    "box on each side, and the smaller red box on top as the roof.",
                    use("build_row", objects=[wheels[0], body, wheels[1]]),
                    use("place_on_top", objects=roof, support=body))


@register("code-ball-on-line", family="lines")
def code_ball_on_line() -> TaskGraph:
    line = var("line", "line", "black", (0.30, 0.01, 0.001), description="the line")
    red, blue, green, yellow, orange = colored("block", FIVE, BLOCK)
    row = use("align_along_line", objects=[red, blue, orange], line=line)
    return assemble("code-ball-on-line",
                    "Arrange five blocks on the line: red at one end, blue in the middle, "
                    "orange at the other end, the green block on the blue one and the yellow "
                    "block on the green one.",
                    row, use("stack_on_base", layers=[green, yellow], base=blue, after=[row]))


@register("color-coordinated-arch-construction", family="structures",
          tags=("starts-inside",))
def color_coordinated_arch_construction() -> TaskGraph:
    box = var("container", "container", "brown", (0.20, 0.20, 0.05),
              description="the container the blocks start in")
    pallet = _pallet()
    reds = var("red_blocks", "block", "red", BLOCK, count=2, initial=start_inside(box))
    blue = var("blue_block", "block", "blue", BLOCK, initial=start_inside(box))
    return assemble("color-coordinated-arch-construction",
                    "Take the blocks out of the container and build an arch on the pallet: "
                    "two red blocks side by side and a blue block across them (one layer; "
                    "see docs/library.md).",
                    use("palletize_layer", objects=reds, pallet=pallet),
                    use("pyramid_layer", layer=blue, below=reds), extra=[box])


@register("symmetric-block-bridge-construction", family="structures")
def symmetric_block_bridge_construction() -> TaskGraph:
    stand = var("stand", "stand", "gray", STAND, description="the stand")
    base = var("red_base_blocks", "block", "red", BLOCK, count=2,
               description="two red blocks side by side: the bridge's base")
    deck = var("blue_block_1", "block", "blue", BLOCK, description="the blue block bridging "
               "the base")
    # Alternating above the deck; with two red blocks in the base, seven of GenSim's
    # eight blocks alternate (an eighth, blue, would sit on blue; docs/library.md).
    column = [var(f"{c}_block_{k}", "block", c, BLOCK)
              for c, k in (("red", 2), ("blue", 2), ("red", 3), ("blue", 3))]
    row = use("align_along_line", objects=base, line=stand)
    layer = use("pyramid_layer", layer=deck, below=base, after=[row])
    return assemble("symmetric-block-bridge-construction",
                    "On the stand, put two red blocks side by side, a blue block across them, "
                    "then red, blue, red and blue blocks on top: a symmetric bridge of "
                    "alternating colours.",
                    row, layer, use("stack_on_base", layers=column, base=deck, after=[layer]))


def _pyramids_on(kind: str, colors: tuple[str, ...], size: tuple[float, float, float],
                 sequential: bool) -> tuple[list[TaskGraph], list[StateVariable]]:
    """A two-one pyramid of each colour on the ``kind`` (container or pallet) of that
    colour; ``sequential`` builds them colour after colour."""
    fragments: list[TaskGraph] = []
    hosts = [var(f"{c}_{kind}", kind, c, size) for c in colors]  # type: ignore[arg-type]
    for c, host in zip(colors, hosts, strict=True):
        fragments += _two_one_pyramid(c, host, after=fragments[-1:] if sequential else ())
    return fragments, hosts


@register("container-block-pyramid-assembly", family="structures")
def container_block_pyramid_assembly() -> TaskGraph:
    fragments, _ = _pyramids_on("container", ("red", "blue", "green", "yellow"),
                                (0.13, 0.13, 0.05), sequential=True)
    return assemble("container-block-pyramid-assembly",
                    "Put the blocks of each colour into the container of that colour and stack "
                    "them there as a pyramid, two at the base and one on top: red first, then "
                    "blue, green and yellow.", fragments)


@register("color-sequenced-pyramid-packing", family="structures")
def color_sequenced_pyramid_packing() -> TaskGraph:
    fragments, _ = _pyramids_on("pallet", ("red", "green", "blue", "yellow"),
                                (0.13, 0.13, 0.02), sequential=False)
    return assemble("color-sequenced-pyramid-packing",
                    "Sort twelve cubes by colour onto four pallets and stack each colour on its "
                    "pallet as a pyramid: two cubes at the base, one on top.", fragments)



@register("block-pyramid-with-limited-space", family="structures")
def block_pyramid_with_limited_space() -> TaskGraph:
    # Zones just large enough for a pyramid's base (the "limited space"), in a
    # triangle; the yellow pyramid stands in their centre, in the gap between the
    # red and the blue zone (GenSim's code sets goals for the other nine only).
    zones = {c: var(f"{c}_zone", "zone", c, PAIR_ZONE, initial=at(x, y),
                    description=f"the {c} zone")
             for c, x, y in (("red", 0.42, 0.22), ("blue", 0.42, -0.22), ("green", 0.66, 0.0))}
    return assemble("block-pyramid-with-limited-space",
                    "Sort the twelve blocks by colour: build a pyramid of two blocks with one "
                    "on top in each zone (red, green, blue) of its colour, and a smaller "
                    "yellow pyramid in the centre of the zones.",
                    *(_two_one_pyramid(c, z) for c, z in zones.items()),
                    _two_one_pyramid("yellow", [zones["red"], zones["blue"]]))


@register("Four-corner-pyramid-challenge", family="stacking")
def four_corner_pyramid_challenge() -> TaskGraph:
    # "From bottom to top red, blue, green, yellow": a column of four in each zone
    # (as color-coordinated-cylinder-pyramid reads one bottom-to-top sequence).
    corners = ((0.33, 0.38), (0.33, -0.38), (0.67, 0.38), (0.67, -0.38))
    columns = []
    for k, (x, y) in enumerate(corners, start=1):
        zone = var(f"zone_{k}", "zone", "gray", (0.12, 0.12, 0.001), initial=at(x, y),
                   description=f"the zone in corner {k}")
        columns.append(use("stack_on_base", layers=colored("block", FOUR, BLOCK,
                                                           suffix=f"block_{k}"), base=zone))
    return assemble("Four-corner-pyramid-challenge",
                    "In each of the four zones in the corners of the table, stack a red, a "
                    "blue, a green and a yellow block, from bottom to top.", columns)



@register("color-coordinated-sphere-on-pallet-pyramid", family="structures")
def color_coordinated_sphere_on_pallet_pyramid() -> TaskGraph:
    # A two-one pyramid of each colour on the pallet of that colour, the pallets in a
    # line (red, blue, green from left to right), and the ball of that colour on the
    # pyramid's top block: a ball stays on a flat 4 cm top because balls have rolling
    # friction (sim.parts.BALL_FRICTION).
    colors = ("red", "blue", "green")
    fragments: list[TaskGraph] = []
    for c, y in zip(colors, (0.2, 0.0, -0.2), strict=True):
        pallet = var(f"{c}_pallet", "pallet", c, (0.12, 0.08, 0.02), initial=at(0.6, y, 90.0),
                     description=f"the {c} pallet")
        base = var(f"{c}_base_blocks", "block", c, BLOCK, count=2)
        top = var(f"{c}_top_block", "block", c, BLOCK)
        ball = var(f"{c}_ball", "ball", c, BALL)
        fragments += [use("align_along_line", objects=base, line=pallet),
                      use("pyramid_layer", layer=top, below=base),
                      use("place_on_top", objects=ball, support=top)]
    return assemble("color-coordinated-sphere-on-pallet-pyramid",
                    "On each of three pallets in a line (red, blue, green from left to right) "
                    "build a pyramid of the three blocks of its colour, two at the base and "
                    "one on top, and put the ball of that colour on top of the pyramid.",
                    fragments)
