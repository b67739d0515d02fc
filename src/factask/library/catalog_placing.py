"""Library tasks that put objects somewhere: zones, bowls, containers, fixtures, corners.

Each builder declares variables, instantiates templates and assembles them;
names follow GenSim's task list (``factask/data/gensim_tasks.json``).
"""

from __future__ import annotations

from factask.graph import TaskGraph
from factask.library.builders import assemble, at, region, register, use, var
from factask.library.templates import match_pairs

BOWL = (0.12, 0.12, 0.05)
CONTAINER = (0.16, 0.16, 0.05)
ZONE = (0.12, 0.12, 0.001)
BLOCK = (0.04, 0.04, 0.04)
ELL = (0.08, 0.08, 0.04)
#: A fixture for an ell (the kind's default: 2 cm of wall and clearance around it).
ELL_FIXTURE = (0.12, 0.12, 0.04)
#: A fixture whose square hollow takes one 4 cm block.
BLOCK_FIXTURE = (0.08, 0.08, 0.04)
CORNER = (0.055, 0.055, 0.001)


@register("place-red-in-green")
def place_red_in_green() -> TaskGraph:
    reds = [var(f"red_block_{i}", "block", "red", BLOCK) for i in "ab"]
    greens = [var(f"green_bowl_{i}", "bowl", "green", BOWL) for i in "ab"]
    return assemble(
        "place-red-in-green",
        "Pick up the red blocks and place each into a green bowl, amidst a blue bowl and "
        "a yellow block that stay where they are.",
        match_pairs("put_in_container", list(zip(reds, greens, strict=True))),
        extra=[var("blue_bowl", "bowl", "blue", BOWL, description="distractor bowl"),
               var("yellow_block", "block", "yellow", BLOCK, description="distractor block")],
    )


@register("put-block-in-bowl")
def put_block_in_bowl() -> TaskGraph:
    block = var("blue_block", "block", "blue", BLOCK)
    bowl = var("yellow_bowl", "bowl", "yellow", BOWL)
    return assemble(
        "put-block-in-bowl",
        "Place the blue block in the yellow bowl; the red block and green bowl are distractors.",
        use("put_in_container", objects=block, container=bowl),
        extra=[var("red_block", "block", "red", BLOCK, description="distractor block"),
               var("green_bowl", "bowl", "green", BOWL, description="distractor bowl")],
    )


@register("cylinder-container-sorting")
def cylinder_container_sorting() -> TaskGraph:
    colors = ("red", "green", "blue")
    cyls = [var(f"{c}_cylinder", "cylinder", c, (0.04, 0.04, 0.06)) for c in colors]
    boxes = [var(f"{c}_container", "container", c, CONTAINER) for c in colors]
    return assemble(
        "cylinder-container-sorting",
        "Pick up cylinders of three colours (red, green, blue) and place each into the "
        "container of the matching colour.",
        match_pairs("put_in_container", list(zip(cyls, boxes, strict=True))),
    )


@register("align-spheres-in-colored-zones")
def align_spheres_in_colored_zones() -> TaskGraph:
    colors = ("red", "blue", "green", "yellow")
    balls = [var(f"{c}_sphere", "ball", c, BLOCK) for c in colors]
    zones = [var(f"{c}_zone", "zone", c, ZONE) for c in colors]
    return assemble(
        "align-spheres-in-colored-zones",
        "Pick up each of four coloured spheres (red, blue, green, yellow) and place it in "
        "the zone of the matching colour.",
        match_pairs("place_in_zone", list(zip(balls, zones, strict=True))),
    )


@register("code-cylinder-in-zone")
def code_cylinder_in_zone() -> TaskGraph:
    cyl = var("blue_cylinder", "cylinder", "blue", (0.04, 0.04, 0.06))
    zone = var("green_zone", "zone", "green", ZONE)
    return assemble(
        "code-cylinder-in-zone",
        "Place the blue cylinder in the green zone; the yellow zone is a distractor.",
        use("place_in_zone", objects=cyl, zone=zone),
        extra=[var("yellow_zone", "zone", "yellow", ZONE, description="distractor zone")],
    )


@register("insertion-in-color-sequenced-zones")
def insertion_in_color_sequenced_zones() -> TaskGraph:
    colors = ("red", "blue", "green", "yellow")
    # Zones in a fixed row, red on the left (+y) to yellow on the right. The ells
    # start in a strip in front of the zones, not inside a wrong zone as in GenSim:
    # a one-object-per-action oracle could not free a zone held by another ell.
    zones = [var(f"{c}_zone", "zone", c, ZONE, initial=at(0.62, y))
             for c, y in zip(colors, (0.3, 0.1, -0.1, -0.3), strict=True)]
    ells = [var(f"{c}_ell", "ell", c, ELL, initial=region((0.28, 0.45), (-0.45, 0.45)))
            for c in colors]
    return assemble(
        "insertion-in-color-sequenced-zones",
        "Pick up each ell and place it in the zone of the same colour, in the sequence "
        "red, blue, green, yellow; the zones run left to right in that order.",
        match_pairs("place_in_zone", list(zip(ells, zones, strict=True)), sequential=True),
    )


@register("block-insertion")
def block_insertion() -> TaskGraph:
    ell = var("red_ell", "ell", "red", ELL)
    fixture = var("green_fixture", "fixture", "green", ELL_FIXTURE)
    return assemble(
        "block-insertion",
        "Put the L-shaped block into the L-shaped hole of its fixture.",
        use("insert_into_fixture", objects=ell, fixture=fixture),
    )


@register("color-coordinated-insertion")
def color_coordinated_insertion() -> TaskGraph:
    colors = ("red", "blue", "green")
    ells = [var(f"{c}_ell", "ell", c, ELL) for c in colors]
    fixtures = [var(f"{c}_fixture", "fixture", c, ELL_FIXTURE) for c in colors]
    return assemble(
        "color-coordinated-insertion",
        "Insert each of three ells into the fixture of the same colour, red first, then "
        "blue, then green.",
        match_pairs("insert_into_fixture", list(zip(ells, fixtures, strict=True)), sequential=True),
    )


@register("color-coordinated-block-insertion")
def color_coordinated_block_insertion() -> TaskGraph:
    colors = ("red", "blue", "green", "yellow")
    blocks = [var(f"{c}_block", "block", c, BLOCK) for c in colors]
    fixtures = [var(f"{c}_fixture", "fixture", c, BLOCK_FIXTURE) for c in colors]
    return assemble(
        "color-coordinated-block-insertion",
        "Insert four coloured blocks into the fixtures of matching colour in the sequence "
        "red, blue, green, yellow.",
        match_pairs("insert_into_fixture", list(zip(blocks, fixtures, strict=True)),
                    sequential=True),
    )


@register("align-box-corner")
def align_box_corner() -> TaskGraph:
    box = var("brown_box", "box", "brown", (0.07, 0.05, 0.05), description="a box of odd size")
    corner = var("corner_marker", "corner", "green", CORNER,
                 description="the L-shaped corner marker")
    return assemble(
        "align-box-corner",
        "Pick up the box and align one of its corners with the L-shaped marker.",
        use("align_to_corner", objects=box, corner=corner),
    )


@register("color-coordinated-block-corner-alignment")
def color_coordinated_block_corner_alignment() -> TaskGraph:
    # Corners fixed from top left (far, +y) to bottom right: red, green, blue, yellow.
    spots = {"red": (0.65, 0.25), "green": (0.65, -0.25), "blue": (0.38, 0.25),
             "yellow": (0.38, -0.25)}
    blocks = [var(f"{c}_block", "block", c, BLOCK) for c in spots]
    corners = [var(f"{c}_corner", "corner", c, CORNER, initial=at(*xy))
               for c, xy in spots.items()]
    return assemble(
        "color-coordinated-block-corner-alignment",
        "Align each of four coloured blocks into the corner marker of the same colour; the "
        "corners run red, green, blue, yellow from top left to bottom right.",
        match_pairs("align_to_corner", list(zip(blocks, corners, strict=True))),
    )


@register("packing-boxes")
def packing_boxes() -> TaskGraph:
    sizes = {"red": (0.07, 0.06, 0.05), "blue": (0.06, 0.07, 0.04),
             "green": (0.07, 0.07, 0.04), "yellow": (0.05, 0.07, 0.05)}
    boxes = [var(f"{c}_box", "box", c, s) for c, s in sizes.items()]
    # 18 cm inside the walls: the four boxes fit two by two with room to spare.
    container = var("brown_container", "container", "brown", (0.20, 0.20, 0.06),
                    description="the open container to pack")
    return assemble(
        "packing-boxes",
        "Pick up four boxes of different sizes and pack them all into the container.",
        use("put_in_container", objects=boxes, container=container),
    )
