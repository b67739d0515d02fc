"""Library tasks that stack: columns, towers on bases, pallet layers, walls."""

from __future__ import annotations

from factask.graph import TaskGraph
from factask.library.builders import assemble, register, start_inside, start_on, use, var

BLOCK = (0.04, 0.04, 0.04)
#: A wide bowl: two 4 cm blocks fit side by side inside its round wall (a 12 cm
#: bowl holds only one).
WIDE_BOWL = (0.16, 0.16, 0.05)
CONTAINER = (0.16, 0.16, 0.05)
PALLET = (0.30, 0.25, 0.0375)
SQUARE_STAND = (0.09, 0.09, 0.005)


def _blocks(colors: tuple[str, ...], suffix: str = "block", size=BLOCK) -> list:
    return [var(f"{c}_{suffix}", "block", c, size) for c in colors]


#: The seven moves that take three disks from the first stand to the third, the
#: smallest never under a bigger one: (disk, where it goes), ``None`` = a stand.
HANOI_MOVES = (("small", "goal"), ("medium", "spare"), ("small", "medium"),
               ("large", "goal"), ("small", "start"), ("medium", "large"), ("small", "medium"))


@register("towers-of-hanoi")
def towers_of_hanoi() -> TaskGraph:
    stands = {
        role: var(f"{role}_stand", "stand", color, SQUARE_STAND, description=f"the {role} stand")
        for role, color in (("start", "gray"), ("spare", "white"), ("goal", "brown"))}
    large = var("large_disk", "cylinder", "red", (0.07, 0.07, 0.02),
                initial=start_on(stands["start"]),
                description="the largest disk, at the bottom of the start stack")
    medium = var("medium_disk", "cylinder", "green", (0.055, 0.055, 0.02),
                 initial=start_on(large), description="the middle disk")
    small = var("small_disk", "cylinder", "blue", (0.04, 0.04, 0.02), initial=start_on(medium),
                description="the smallest disk, on top of the start stack")
    disks = {"large": large, "medium": medium, "small": small}
    last_move = {disk: k for k, (disk, _) in enumerate(HANOI_MOVES)}
    moves: list[TaskGraph] = []
    for k, (disk, onto) in enumerate(HANOI_MOVES):
        support = disks.get(onto) or stands[onto]
        # A disk's last move must hold at the end; its earlier moves are milestones.
        moves.append(use("place_on_top", objects=[disks[disk]], support=support,
                         prefix=f"move_{k + 1}", after=moves[-1:],
                         milestone=k != last_move[disk]))
    return assemble(
        "towers-of-hanoi",
        "Three disks of decreasing size start stacked on the first of three stands; move "
        "them to the third stand one at a time, never a bigger disk on a smaller one: "
        "seven moves, each its own milestone, ending largest at the bottom.",
        *moves, extra=list(stands.values()),
    )


@register("stack-blocks-in-container")
def stack_blocks_in_container() -> TaskGraph:
    blocks = _blocks(("red", "blue", "green", "yellow", "orange"))
    container = var("container", "container", "brown", CONTAINER, description="the container")
    return assemble(
        "stack-blocks-in-container",
        "Stack five coloured blocks inside the container: red at the bottom, then blue, "
        "green, yellow and orange at the top.",
        use("stack_on_base", layers=blocks, base=container),
    )


@register("color-sorted-container-stack")
def color_sorted_container_stack() -> TaskGraph:
    bowl_a = var("left_bowl", "bowl", "white", WIDE_BOWL,
                 description="bowl holding red and blue")
    bowl_b = var("right_bowl", "bowl", "white", WIDE_BOWL,
                 description="bowl holding yellow and green")
    colors_bowl = {"red": bowl_a, "blue": bowl_a, "green": bowl_b, "yellow": bowl_b}
    blocks = [var(f"{c}_block", "block", c, BLOCK, initial=start_inside(b))
              for c, b in colors_bowl.items()]
    container = var("container", "container", "brown", CONTAINER, description="the container")
    return assemble(
        "color-sorted-container-stack",
        "The red and blue blocks start in one bowl, the green and yellow ones in another; "
        "stack them inside the container in the order red, blue, green, yellow.",
        use("stack_on_base", layers=blocks, base=container),
        extra=[bowl_a, bowl_b],
    )


@register("color-coordinated-cylinder-tower")
def color_coordinated_cylinder_tower() -> TaskGraph:
    cyls = [var(f"{c}_cylinder", "cylinder", c, (0.05, 0.05, 0.04))
            for c in ("blue", "green", "red", "yellow")]
    stand = var("square_stand", "stand", "gray", SQUARE_STAND, description="the square stand")
    return assemble(
        "color-coordinated-cylinder-tower",
        "Stack four cylinders on the square stand: blue at the bottom, then green, red, and "
        "yellow at the top.",
        use("stack_on_base", layers=cyls, base=stand),
    )


@register("rainbow-stack")
def rainbow_stack() -> TaskGraph:
    blocks = _blocks(("red", "orange", "yellow", "green", "blue", "purple"))
    stand = var("stand", "stand", "gray", (0.15, 0.05, 0.005), description="the stand")
    return assemble(
        "rainbow-stack",
        "Stack the blocks on the stand in the order of the rainbow from bottom to top.",
        use("stack_on_base", layers=blocks, base=stand),
    )


@register("place-box-in-pallet")
def place_box_in_pallet() -> TaskGraph:
    boxes = [var(f"{c}_box", "box", c, (0.06, 0.06, 0.06)) for c in ("red", "blue", "green")]
    pallet = var("pallet", "pallet", "brown", PALLET, description="the pallet")
    return assemble(
        "place-box-in-pallet",
        "Stack three boxes on the pallet: red at the bottom, blue in the middle, green on top.",
        use("stack_on_base", layers=boxes, base=pallet),
    )


@register("stack-boxes-in-pallet")
def stack_boxes_in_pallet() -> TaskGraph:
    boxes = [var(f"{c}_box", "box", c, (0.07, 0.07, 0.05)) for c in ("yellow", "green", "blue")]
    pallet = var("pallet", "pallet", "brown", PALLET, description="the pallet")
    return assemble(
        "stack-boxes-in-pallet",
        "Stack the yellow, green and blue boxes on the pallet in that order from bottom "
        "to top.",
        use("stack_on_base", layers=boxes, base=pallet),
    )


@register("stack-boxes-column")
def stack_boxes_column() -> TaskGraph:
    boxes = var("boxes", "box", "brown", (0.07, 0.07, 0.07), count=3,
                description="three identical 7 cm boxes")
    return assemble(
        "stack-boxes-column",
        "Stack the three boxes into a single column on the table.",
        use("stack_column", layers=boxes),
    )


@register("color-structured-block-tower")
def color_structured_block_tower() -> TaskGraph:
    order = [("red", "low"), ("blue", "low"), ("green", "low"),
             ("red", "high"), ("blue", "high"), ("green", "high")]
    blocks = [var(f"{c}_block_{h}", "block", c, BLOCK) for c, h in order]
    return assemble(
        "color-structured-block-tower",
        "Build a tower of six blocks: red at the base, then blue, green, red, blue and "
        "green at the top.",
        use("stack_column", layers=blocks),
    )


@register("palletizing-boxes")
def palletizing_boxes() -> TaskGraph:
    pallet = var("pallet", "pallet", "brown", PALLET, description="the pallet")
    lower = var("lower_boxes", "box", "tan", (0.08, 0.08, 0.06), count=3,
                description="boxes of the first layer")
    upper = var("upper_boxes", "box", "tan", (0.08, 0.08, 0.06), count=3,
                description="boxes of the second layer")
    first = use("palletize_layer", objects=lower, pallet=pallet)
    return assemble(
        "palletizing-boxes",
        "Palletize six identical boxes in two layers: three side by side on the pallet, "
        "then three more, one on each.",
        first,
        use("layer_on_row", layer=upper, below=lower),
    )


@register("multi-level-block-construction")
def multi_level_block_construction() -> TaskGraph:
    pallet = var("pallet", "pallet", "brown", PALLET, description="the pallet")
    reds = var("red_blocks", "block", "red", BLOCK, count=2)
    blues = var("blue_blocks", "block", "blue", BLOCK, count=2)
    return assemble(
        "multi-level-block-construction",
        "Build a two-level structure on the pallet: two red blocks side by side, then a "
        "blue block on each red block.",
        use("palletize_layer", objects=reds, pallet=pallet),
        use("layer_on_row", layer=blues, below=reds),
    )


@register("stack-three-layer-red-wall")
def stack_three_layer_red_wall() -> TaskGraph:
    rows = [var(f"red_bricks_{h}", "block", "red", BLOCK, count=3,
                description=f"the three red blocks of the {h} layer")
            for h in ("bottom", "middle", "top")]
    return assemble(
        "stack-three-layer-red-wall",
        "Build a wall three blocks wide and three layers high from nine red blocks.",
        use("build_row", objects=rows[0]),
        use("layer_on_row", layer=rows[1], below=rows[0]),
        use("layer_on_row", layer=rows[2], below=rows[1]),
    )
