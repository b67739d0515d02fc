"""GenSim pyramids and bridges whose layers mix colours.

A layer is a ``pyramid_layer`` (or ``layer_on_row``) on the row below, and that row
may be made of several variables (``row``'s ``on`` takes a list): a base of two
green blocks and a blue one carries the red layer of ``create-pyramid-blocks-and-
container``. The base rows lie along their zone, pallet or container
(``align_along_line``), listed from one end to the other.
"""

from __future__ import annotations

import math

from factask.graph import StateVariable, SubtaskFactor, SubtaskTemplate, TaskGraph
from factask.library.builders import assemble, register, use, var
from factask.library.conventions import BLOCK
from factask.library.templates import slot
from factask.relations import AtPose, TargetPose

#: A pallet a row of five blocks fits along (GenSim's bridge pallet).
LONG_PALLET = (0.30, 0.15, 0.02)
#: A zone a three-block base row (14 cm end to end) fits inside.
PYRAMID_ZONE = (0.16, 0.16, 0.001)
#: A container a three-block base row fits in, walls included.
PYRAMID_CONTAINER = (0.20, 0.20, 0.05)


def _blocks(layer: str, colors: tuple[str, ...]) -> list[StateVariable]:
    """One block per colour of a layer, named ``<layer>_<colour>``, listed in order."""
    return [var(f"{layer}_{c}", "block", c, BLOCK, description=f"the {c} block of the "
                f"{layer} layer") for c in colors]


def _pyramid(base: list[StateVariable], host: StateVariable,
             layers: list[list[StateVariable]], template: str = "pyramid_layer"
             ) -> list[TaskGraph]:
    """A base row along ``host``, then each of ``layers`` on the one below it (with
    ``template``: ``pyramid_layer`` bridges neighbours, ``layer_on_row`` one on each)."""
    fragments = [use("align_along_line", objects=base, line=host)]
    below = base
    for layer in layers:
        fragments.append(use(template, layer=layer, below=below))
        below = layer
    return fragments


@register("rainbow-pyramid-in-zone", family="structures")
def rainbow_pyramid_in_zone() -> TaskGraph:
    # GenSim's code builds it from six blocks in rainbow order (its description names
    # five of the colours): red, orange, yellow at the base, green and blue, purple.
    zone = var("zone", "zone", "gray", PYRAMID_ZONE, description="the marked zone")
    return assemble("rainbow-pyramid-in-zone",
                    "Build a pyramid in the marked zone from six blocks in rainbow order: red, "
                    "orange and yellow at the base, green and blue on them, purple on top.",
                    _pyramid(_blocks("base", ("red", "orange", "yellow")), zone,
                             [_blocks("middle", ("green", "blue")), _blocks("top", ("purple",))]))


@register("create-pyramid-blocks-and-container", family="structures")
def create_pyramid_blocks_and_container() -> TaskGraph:
    box = var("container", "container", "brown", PYRAMID_CONTAINER,
              description="the container the pyramid stands in")
    greens = var("green_blocks", "block", "green", BLOCK, count=2,
                 description="the two green blocks of the first layer")
    blue = var("blue_base_block", "block", "blue", BLOCK,
               description="the blue block of the first layer")
    reds = var("red_blocks", "block", "red", BLOCK, count=2, description="the two red blocks")
    top = var("blue_top_block", "block", "blue", BLOCK, description="the blue block on top")
    return assemble("create-pyramid-blocks-and-container",
                    "Build a pyramid of six blocks inside the container: the two green blocks "
                    "and a blue one in the first layer, the two red blocks on them, the other "
                    "blue block on top.",
                    _pyramid([greens, blue], box, [[reds], [top]]))


@register("pyramid-blocks-assemble", family="structures")
def pyramid_blocks_assemble() -> TaskGraph:
    # 5-3-1: the middle layer stands one on each of the inner three bottom blocks, the
    # top block on the middle one.
    pallet = var("pallet", "pallet", "brown", LONG_PALLET, description="the pallet")
    middle = _blocks("middle", ("yellow", "red", "blue"))
    return assemble("pyramid-blocks-assemble",
                    "Build a pyramid of nine blocks on the pallet: red, blue, green, yellow and "
                    "orange at the bottom from left to right, yellow, red and blue in the "
                    "middle, and a green block on top.",
                    _pyramid(_blocks("bottom", ("red", "blue", "green", "yellow", "orange")),
                             pallet, [middle], template="layer_on_row"),
                    use("place_on_top", objects=_blocks("top", ("green",)), support=middle[1]))


@register("color-coordinated-block-bridge", family="structures")
def color_coordinated_block_bridge() -> TaskGraph:
    # Red at the edges, blue in the middle, a green block on each red and blue pair,
    # the sequence repeated along the pallet: GenSim's nine blocks.
    pallet = var("pallet", "pallet", "brown", LONG_PALLET, description="the pallet")
    base = [var(f"{c}_block_{k}", "block", c, BLOCK, description=f"{c} block {k} of the base")
            for c, k in (("red", 1), ("blue", 1), ("red", 2), ("blue", 2), ("red", 3))]
    greens = var("green_blocks", "block", "green", BLOCK, count=4,
                 description="four green blocks, each on a red and a blue block")
    return assemble("color-coordinated-block-bridge",
                    "Build a bridge along the pallet: red, blue, red, blue and red blocks in a "
                    "row (red at the edges, blue between), and a green block on each red and "
                    "blue pair.",
                    _pyramid(base, pallet, [[greens]]))


#: A square pallet the triangle pyramid stands on.
TRIANGLE_PALLET = (0.20, 0.20, 0.0375)
#: Side of the triangle of block centres (m): 4 cm cubes at its corners, all at yaw
#: 0, keep 3 mm between the nearest two; the layer above (the triangle turned 60
#: degrees) then rests on corners of two blocks each, its centres at least 5.5 mm
#: inside the hull of what holds them (more apart, that margin shrinks).
TRIANGLE_SIDE = 0.05


def _triangle(turn_deg: float, z: float | None = None) -> list[TargetPose]:
    """Block centres at the corners of a triangle of :data:`TRIANGLE_SIDE` centred on
    the pallet, the first corner at ``90 + turn_deg`` degrees."""
    radius = TRIANGLE_SIDE / math.sqrt(3)
    return [TargetPose(x=radius * math.cos(math.radians(90 + turn_deg + 120 * k)),
                       y=radius * math.sin(math.radians(90 + turn_deg + 120 * k)), z=z)
            for k in range(3)]


#: Two triangle layers, the upper one turned 60 degrees: each upper block over an edge
#: of the lower triangle. One task uses it (not registered, see templates.TEMPLATES).
_TRIANGLE_LAYERS = SubtaskTemplate(
    name="triangle_layers",
    description="Lay the {lower} in a triangle on the {pallet}, then the {upper} on them "
                "in a triangle turned 60 degrees.",
    slots=[slot("lower", "three blocks", ["block"], many=True, movable=True),
           slot("upper", "three blocks", ["block"], many=True, movable=True),
           slot("pallet", "the pallet", ["pallet"])],
    factors=[
        SubtaskFactor(name="lower", description="lay the {lower} in a triangle on the "
                      "{pallet}", goal=AtPose(objects=["lower"], frame="pallet",
                                              check_yaw=False, poses=_triangle(0.0))),
        SubtaskFactor(name="upper", description="put the {upper} on the {lower} in a "
                      "triangle turned 60 degrees", after=["lower"],
                      # Heights given: an upper centre lies over the gap between two
                      # lower blocks, not over one of them.
                      goal=AtPose(objects=["upper"], frame="pallet", check_yaw=False,
                                  poses=_triangle(60.0, TRIANGLE_PALLET[2] / 2
                                                  + BLOCK[2] * 1.5))),
    ],
)


@register("multi-level-pyramid-construction", family="structures")
def multi_level_pyramid_construction() -> TaskGraph:
    pallet = var("pallet", "pallet", "brown", TRIANGLE_PALLET, description="the pallet")
    greens = var("green_blocks", "block", "green", BLOCK, count=3)
    blues = var("blue_blocks", "block", "blue", BLOCK, count=3)
    return assemble("multi-level-pyramid-construction",
                    "Build a two-level pyramid on the pallet: the three green blocks side by "
                    "side in a triangle, then the three blue blocks on them in a triangle "
                    "turned 60 degrees.",
                    _TRIANGLE_LAYERS.instantiate(prefix="pyramid", lower=greens, upper=blues,
                                                 pallet=pallet))
