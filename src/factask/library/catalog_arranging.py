"""Library tasks that arrange objects: rows, lines, circles."""

from __future__ import annotations

from factask.graph import TaskGraph
from factask.library.builders import assemble, register, use, var

BLOCK = (0.04, 0.04, 0.04)
LINE = (0.30, 0.01, 0.001)


@register("align-pair-colored-blocks-along-line")
def align_pair_colored_blocks_along_line() -> TaskGraph:
    reds = var("red_pair", "block", "red", BLOCK, count=2, description="two red blocks")
    blues = var("blue_pair", "block", "blue", BLOCK, count=2, description="two blue blocks")
    line = var("line", "line", "black", LINE, description="the marked line")
    return assemble(
        "align-pair-colored-blocks-along-line",
        "Place the pair of red blocks and then the pair of blue blocks in a row along the "
        "marked line.",
        use("align_along_line", objects=[reds, blues], line=line),
    )


@register("align-boxes-on-line")
def align_boxes_on_line() -> TaskGraph:
    boxes = [var(f"{c}_box", "box", c, (0.05, 0.05, 0.05)) for c in ("red", "blue", "green")]
    line = var("green_line", "line", "green", LINE, description="the green line")
    return assemble(
        "align-boxes-on-line",
        "Place the red, blue and green boxes in a row on the green line, in that order "
        "from left to right.",
        use("align_along_line", objects=boxes, line=line),
    )


@register("arrange-blocks-in-line")
def arrange_blocks_in_line() -> TaskGraph:
    blocks = [var(f"{c}_block", "block", c, BLOCK) for c in ("red", "yellow", "green", "blue")]
    return assemble(
        "arrange-blocks-in-line",
        "Arrange four coloured blocks in a straight line in rainbow order: red, yellow, "
        "green, blue.",
        use("build_row", objects=blocks),
    )


@register("build-two-circles")
def build_two_circles() -> TaskGraph:
    reds = var("red_blocks", "block", "red", BLOCK, count=5)
    blues = var("blue_blocks", "block", "blue", BLOCK, count=5)
    return assemble(
        "build-two-circles",
        "Construct two separate circles on the table, one of five red blocks and one of "
        "five blue blocks.",
        use("arrange_circle", objects=reds),
        use("arrange_circle", objects=blues),
    )


@register("arrange-cylinders-in-circle")
def arrange_cylinders_in_circle() -> TaskGraph:
    cyls = [var(f"{c}_cylinder", "cylinder", c, (0.04, 0.04, 0.06))
            for c in ("red", "orange", "yellow", "green", "blue", "purple")]
    return assemble(
        "arrange-cylinders-in-circle",
        "Arrange six coloured cylinders evenly on a circle, in rainbow order.",
        use("arrange_circle", objects=cyls),
    )


@register("put-blues-around-red")
def put_blues_around_red() -> TaskGraph:
    red = var("red_block", "block", "red", BLOCK, description="the red block in the middle")
    blues = var("blue_blocks", "block", "blue", BLOCK, count=4)
    return assemble(
        "put-blues-around-red",
        "Place the four blue blocks on a circle around the red block.",
        use("arrange_circle_around", objects=blues, center=red),
    )


@register("build-wheel")
def build_wheel() -> TaskGraph:
    hub = var("hub_zone", "zone", "gray", (0.06, 0.06, 0.001),
              description="the small zone marking the wheel's centre")
    reds = var("red_blocks", "block", "red", BLOCK, count=3)
    blues = var("blue_blocks", "block", "blue", BLOCK, count=3)
    ball = var("green_ball", "ball", "green", BLOCK, description="the green sphere: the hub")
    return assemble(
        "build-wheel",
        "Build a wheel: six red and blue blocks on a circle around the hub zone, and the "
        "green sphere in the hub zone at the centre.",
        use("arrange_circle_around", objects=[reds, blues], center=hub),
        use("place_in_zone", objects=ball, zone=hub),
    )
