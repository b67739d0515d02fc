"""Library tasks that build structures: bridges, arches, cars, houses, pyramids, castles."""

from __future__ import annotations

from factask.graph import StateVariable, TaskGraph
from factask.library.builders import assemble, register, use, var
from factask.library.conventions import LOG

BLOCK = (0.04, 0.04, 0.04)
#: A deck bar long enough to span two pillars 8 cm apart (see BRIDGE_PILLAR_SPACING).
DECK = (0.14, 0.04, 0.02)
PALLET = (0.30, 0.25, 0.0375)
#: A zone shaped for a row of three blocks (Ravens' pyramid base zone is similar).
ROW_ZONE = (0.17, 0.06, 0.001)


@register("build-bridge")
def build_bridge() -> TaskGraph:
    pillars = var("yellow_pillars", "block", "yellow", BLOCK, count=2,
                  description="two yellow blocks: the bridge's pillars")
    deck = var("blue_deck", "box", "blue", DECK, description="the blue bar: the bridge deck")
    top = var("blue_block", "block", "blue", BLOCK, description="blue block on the deck")
    return assemble(
        "build-bridge",
        "Build a bridge: stand two yellow blocks apart, lay the blue bar across them and "
        "put a blue block on the middle of the deck.",
        use("bridge", pillars=pillars, deck=deck),
        use("place_on_top", objects=top, support=deck),
    )


@register("cylinder-balancing-on-blocks")
def cylinder_balancing_on_blocks() -> TaskGraph:
    pillars = var("red_blocks", "block", "red", BLOCK, count=2,
                  description="two red blocks: the bridge's pillars")
    deck = var("green_cylinder", "log", "green", LOG,
               description="the green cylinder, lying on its side across the blocks")
    return assemble(
        "cylinder-balancing-on-blocks",
        "Build a bridge: stand the two red blocks parallel with a gap between them, then "
        "balance the green cylinder horizontally across them.",
        use("bridge", pillars=pillars, deck=deck),
    )


@register("construct-colorful-arch")
def construct_colorful_arch() -> TaskGraph:
    pillars = var("red_pillars", "block", "red", BLOCK, count=2,
                  description="two red blocks: the arch's legs")
    lintel = var("blue_lintel", "box", "blue", DECK, description="the blue bar over the legs")
    caps = var("red_caps", "block", "red", BLOCK, count=2,
               description="two red blocks on top of the arch")
    return assemble(
        "construct-colorful-arch",
        "Construct a colourful arch: two red legs, a blue bar across them, and two red "
        "blocks side by side on the bar.",
        use("bridge", pillars=pillars, deck=lintel),
        use("place_on_top", objects=caps, support=lintel),
    )


@register("build-car")
def build_car() -> TaskGraph:
    wheels = var("black_wheels", "cylinder", "black", (0.04, 0.04, 0.04), count=2,
                 description="two upright black cylinders: the axles/wheels")
    chassis = var("blue_chassis", "box", "blue", (0.14, 0.05, 0.02),
                  description="the blue bar: the car's body")
    cabin = var("red_cabin", "block", "red", BLOCK, description="red block: the cabin")
    return assemble(
        "build-car",
        "Construct a simple car: two black cylinders as wheels, the blue body across them "
        "and a red cabin block on the body.",
        use("bridge", pillars=wheels, deck=chassis),
        use("place_on_top", objects=cabin, support=chassis),
    )


@register("build-house")
def build_house() -> TaskGraph:
    base = var("red_base_blocks", "block", "red", BLOCK, count=2,
               description="the house's base blocks")
    walls = var("blue_walls", "block", "blue", BLOCK, count=2,
                description="wall blocks, one on each base block")
    roof = var("yellow_roof", "box", "yellow", (0.12, 0.05, 0.02),
               description="the roof bar across both walls")
    chimney = var("green_chimney", "cylinder", "green", (0.03, 0.03, 0.04),
                  description="the chimney on the roof")
    return assemble(
        "build-house",
        "Build a small house: two red base blocks in a row, a blue wall block on each, a "
        "yellow roof bar across the walls and a green cylinder chimney on the roof.",
        use("build_row", objects=base),
        use("layer_on_row", layer=walls, below=base),
        use("place_on_top", objects=roof, support=walls),
        use("place_on_top", objects=chimney, support=roof),
    )


def _pyramid_on_zone(colors: tuple[str, str, str], zone: StateVariable,
                     sequential: bool) -> tuple[list[TaskGraph], list[StateVariable]]:
    """Fragments of a 3-2-1 block pyramid whose base row lies on ``zone``.

    Each layer is one variable (one colour): the ``row`` relation rests a layer on
    *one* variable below. ``sequential`` adds an explicit layer order.
    """
    bottom = var(f"{colors[0]}_base_blocks", "block", colors[0], BLOCK, count=3)
    middle = var(f"{colors[1]}_middle_blocks", "block", colors[1], BLOCK, count=2)
    top = var(f"{colors[2]}_top_block", "block", colors[2], BLOCK)
    f1 = use("align_along_line", objects=bottom, line=zone)
    f2 = use("pyramid_layer", layer=middle, below=bottom, after=[f1] if sequential else ())
    f3 = use("pyramid_layer", layer=top, below=middle, after=[f2] if sequential else ())
    return [f1, f2, f3], [bottom, middle, top]


@register("stack-block-pyramid")
def stack_block_pyramid() -> TaskGraph:
    zone = var("base_zone", "zone", "gray", ROW_ZONE, description="where the base row goes")
    fragments, _ = _pyramid_on_zone(("blue", "green", "red"), zone, sequential=False)
    return assemble(
        "stack-block-pyramid",
        "Stack six blocks into a 3-2-1 pyramid on the base zone: three blue blocks in a "
        "row, two green blocks on them, one red block on top.",
        fragments,
    )


@register("stack-block-pyramid-seq")
def stack_block_pyramid_seq() -> TaskGraph:
    zone = var("base_zone", "zone", "gray", ROW_ZONE, description="where the base row goes")
    fragments, _ = _pyramid_on_zone(("purple", "yellow", "orange"), zone, sequential=True)
    return assemble(
        "stack-block-pyramid-seq",
        "Build a 3-2-1 pyramid one instruction at a time: first the purple base row on "
        "the zone, then the yellow middle layer, then the orange top block.",
        fragments,
    )


@register("code-rainbow-pyramid")
def code_rainbow_pyramid() -> TaskGraph:
    pallet = var("pallet", "pallet", "brown", PALLET, description="the pallet")
    bottom = var("red_base_blocks", "block", "red", BLOCK, count=3)
    middle = var("green_middle_blocks", "block", "green", BLOCK, count=2)
    top = var("purple_top_block", "block", "purple", BLOCK)
    return assemble(
        "code-rainbow-pyramid",
        "Build a 3-2-1 pyramid on the pallet, one colour per layer: red base, green "
        "middle, purple top.",
        use("palletize_layer", objects=bottom, pallet=pallet),
        use("pyramid_layer", layer=middle, below=bottom),
        use("pyramid_layer", layer=top, below=middle),
    )


@register("sort-and-assemble-block-castle")
def sort_and_assemble_block_castle() -> TaskGraph:
    fragments: list[TaskGraph] = []
    for color in ("red", "green"):
        zone = var(f"{color}_zone", "zone", color, (0.12, 0.12, 0.001))
        base = var(f"{color}_castle_base", "block", color, BLOCK, count=2)
        keep = var(f"{color}_castle_keep", "block", color, BLOCK,
                   description=f"the {color} block bridging the base")
        tower = var(f"{color}_castle_tower", "block", color, BLOCK,
                    description=f"the {color} block on top")
        fragments += [
            use("align_along_line", objects=base, line=zone),
            use("pyramid_layer", layer=keep, below=base),
            use("place_on_top", objects=tower, support=keep),
        ]
    return assemble(
        "sort-and-assemble-block-castle",
        "Sort blocks by colour into the red and green zones and build a castle in each: "
        "two blocks side by side, one block bridging them, one block on top. (Two castles "
        "of four blocks, to stay within ten movable objects.)",
        fragments,
    )
