"""GenSim tasks that sort objects by colour into receptacles: containers, bowls, boxes.

Every task pairs each object with the receptacle of its colour
(:func:`~factask.library.templates.match_pairs` over ``put_in_container``);
``sequential`` tasks chain the pairs in the order their description gives.
GenSim's "box" receptacles (open boxes with a slot) are factask containers.
"""

from __future__ import annotations

from factask.graph import StateVariable, TaskGraph
from factask.library.builders import (
    assemble,
    at,
    barrier,
    colored,
    register,
    start_inside,
    start_on,
    use,
    var,
)
from factask.library.conventions import BALL, BLOCK, BOWL, CYLINDER, ELL, FOUR, NEAR, THREE
from factask.library.templates import match_pairs

#: A bowl an ell fits in (its 8 cm bounding box needs more than a 12 cm bowl's inside).
WIDE_BOWL = (0.16, 0.16, 0.05)
CONTAINER = (0.12, 0.12, 0.05)
BIG_CONTAINER = (0.20, 0.20, 0.06)

#: Where a row of receptacles beyond a barrier stands (x) and their y, left to right.
FAR_X = 0.64


def _far_row(n: int) -> list[tuple[float, float]]:
    """``n`` spots in a row beyond the barrier, left (+y) to right."""
    step = 0.8 / max(n, 1)
    return [(FAR_X, 0.4 - step / 2 - k * step) for k in range(n)]


def _sort(name: str, description: str, objects: list[StateVariable],
          targets: list[StateVariable], *, sequential: bool = False,
          extra: list[StateVariable] | None = None) -> TaskGraph:
    """Colour-matched sorting: each object into the receptacle at the same index."""
    return assemble(name, description,
                    match_pairs("put_in_container", list(zip(objects, targets, strict=True)),
                                sequential=sequential),
                    extra=extra or [])


@register("insert-sphere-into-container", family="placing")
def insert_sphere_into_container() -> TaskGraph:
    return assemble(
        "insert-sphere-into-container",
        "Pick up the blue sphere and place it into the open container.",
        use("put_in_container", objects=var("blue_sphere", "ball", "blue", BALL),
            container=var("container", "container", "brown", CONTAINER,
                          description="the open container")))


@register("insert-cylinder-in-container", family="placing")
def insert_cylinder_in_container() -> TaskGraph:
    return assemble(
        "insert-cylinder-in-container",
        "Pick up the blue cylinder and place it into the empty container.",
        use("put_in_container", objects=var("blue_cylinder", "cylinder", "blue", CYLINDER),
            container=var("container", "container", "brown", CONTAINER,
                          description="the empty container")))


@register("code-cylinder-in-colorful-container", family="sorting")
def code_cylinder_in_colorful_container() -> TaskGraph:
    return _sort("code-cylinder-in-colorful-container",
                 "Pick up each cylinder (red, blue, green, yellow) and place it in the "
                 "container of the same colour.",
                 colored("cylinder", FOUR, CYLINDER), colored("container", FOUR, CONTAINER))


@register("color-coordinated-container-sorting", family="sorting")
def color_coordinated_container_sorting() -> TaskGraph:
    return _sort("color-coordinated-container-sorting",
                 "Sort the blocks into the containers of the same colour in the order red, "
                 "blue, green, yellow.",
                 colored("block", FOUR, BLOCK), colored("container", FOUR, CONTAINER),
                 sequential=True)


@register("color-sequenced-block-in-container", family="placing")
def color_sequenced_block_in_container() -> TaskGraph:
    colors = ("red", "blue", "green", "yellow", "orange")
    box = var("container", "container", "brown", BIG_CONTAINER,
              description="the large container")
    return _sort("color-sequenced-block-in-container",
                 "Pick up the five blocks and place each in the large container in the "
                 "colour sequence red, blue, green, yellow, orange.",
                 colored("block", colors, BLOCK), [box] * len(colors), sequential=True)


@register("color-coordinated-bowl-and-cylinder-matching", family="sorting")
def color_coordinated_bowl_and_cylinder_matching() -> TaskGraph:
    return _sort("color-coordinated-bowl-and-cylinder-matching",
                 "Pick up each coloured cylinder and place it into the bowl of the same "
                 "colour (red, blue, green, yellow).",
                 colored("cylinder", FOUR, CYLINDER), colored("bowl", FOUR, BOWL))


@register("color-linked-ball-bowl-ordering", family="sorting")
def color_linked_ball_bowl_ordering() -> TaskGraph:
    # The bowls stand in a row, red on the left (+y): "from left to right".
    bowls = [var(f"{c}_bowl", "bowl", c, BOWL, initial=at(0.6, y))
             for c, y in zip(FOUR, (0.3, 0.1, -0.1, -0.3), strict=True)]
    return _sort("color-linked-ball-bowl-ordering",
                 "Pick up each ball and place it in the bowl of the same colour, in the "
                 "sequence red, blue, green, yellow from left to right.",
                 colored("ball", FOUR, BALL), bowls, sequential=True)


@register("color-coordinated-block-in-container-placement", family="sorting")
def color_coordinated_block_in_container_placement() -> TaskGraph:
    return _sort("color-coordinated-block-in-container-placement",
                 "Pick up each block and place it inside the container of the same colour, "
                 "in the sequence red, blue, green, yellow.",
                 colored("block", FOUR, BLOCK), colored("container", FOUR, CONTAINER),
                 sequential=True)


@register("color-coordinated-container-and-block-matching", family="sorting")
def color_coordinated_container_and_block_matching() -> TaskGraph:
    return _sort("color-coordinated-container-and-block-matching",
                 "Pick up each block and place it into the container of the same colour, "
                 "starting with red, then blue, green and yellow.",
                 colored("block", FOUR, BLOCK), colored("container", FOUR, CONTAINER),
                 sequential=True)


@register("sort-insert-color-coordinated-blocks", family="sorting")
def sort_insert_color_coordinated_blocks() -> TaskGraph:
    blocks = [var(f"{c}_blocks", "block", c, BLOCK, count=2) for c in THREE]
    boxes = [var(f"{c}_containers", "container", c, CONTAINER, count=2) for c in THREE]
    return _sort("sort-insert-color-coordinated-blocks",
                 "Sort six blocks (two red, two blue, two green) by colour into the six "
                 "containers: each block into a container of its colour.",
                 blocks, boxes)


def _balls_in_wrong_receptacles(name: str, description: str, sequential: bool) -> TaskGraph:
    """Four balls, each starting in a receptacle of another colour, sorted by colour."""
    boxes = colored("container", FOUR, CONTAINER)
    balls = [var(f"{c}_ball", "ball", c, BALL, initial=start_inside(boxes[(k + 1) % 4]))
             for k, c in enumerate(FOUR)]
    return _sort(name, description, balls, boxes, sequential=sequential)


@register("sphere-container-color-match", family="sorting", tags=("starts-mismatched",))
def sphere_container_color_match() -> TaskGraph:
    return _balls_in_wrong_receptacles(
        "sphere-container-color-match",
        "Four spheres start inside containers of another colour; put each into the "
        "container of its own colour.", sequential=False)


@register("align-balls-in-colored-boxes", family="sorting", tags=("starts-mismatched",))
def align_balls_in_colored_boxes() -> TaskGraph:
    return _balls_in_wrong_receptacles(
        "align-balls-in-colored-boxes",
        "Four balls start in open boxes of another colour; move each into the box of its "
        "own colour in the order red, blue, green, yellow.", sequential=True)


@register("color-coordinated-sphere-insertion", family="sorting",
          tags=("starts-mismatched",))
def color_coordinated_sphere_insertion() -> TaskGraph:
    return _balls_in_wrong_receptacles(
        "color-coordinated-sphere-insertion",
        "Each of four spheres is inside an open box of another colour; pick each up and "
        "place it in the box of its own colour.", sequential=False)


def _over_barrier(name: str, description: str, kind: str, size: tuple[float, ...],
                  target: str, colors: tuple[str, ...]) -> TaskGraph:
    """Objects start in front of a fixed barrier; their receptacles stand in a row
    beyond it."""
    spots = _far_row(len(colors))
    targets = [var(f"{c}_{target}", target, c, CONTAINER, initial=at(*xy))
               for c, xy in zip(colors, spots, strict=True)]
    objects = colored(kind, colors, size, initial=NEAR)
    return _sort(name, description, objects, targets,
                 extra=barrier(0.52))


@register("color-coordinated-box-ball-matching", family="sorting", tags=("barrier",))
def color_coordinated_box_ball_matching() -> TaskGraph:
    return _over_barrier("color-coordinated-box-ball-matching",
                         "Pick up each ball and place it inside the open box of the same "
                         "colour; the boxes stand in a line behind a low barrier.",
                         "ball", BALL, "container", FOUR)


@register("color-coordinated-ball-placement", family="sorting", tags=("barrier",))
def color_coordinated_ball_placement() -> TaskGraph:
    return _over_barrier("color-coordinated-ball-placement",
                         "Pick up each of the red, blue and yellow balls and place it inside "
                         "the box of the same colour without touching the barrier between "
                         "them.", "ball", BALL, "container", ("red", "blue", "yellow"))


@register("cylinder-and-box-arrangement", family="sorting", tags=("barrier",))
def cylinder_and_box_arrangement() -> TaskGraph:
    return _over_barrier("cylinder-and-box-arrangement",
                         "Pick up each of the red, blue and yellow cylinders and place it "
                         "inside the box of the same colour, reaching over the barrier.",
                         "cylinder", CYLINDER, "container", ("red", "blue", "yellow"))


@register("color-coordinated-cylinders-in-boxes", family="sorting")
def color_coordinated_cylinders_in_boxes() -> TaskGraph:
    return _sort("color-coordinated-cylinders-in-boxes",
                 "Put each of four cylinders (red, blue, green, yellow) into the open box of "
                 "the same colour.",
                 colored("cylinder", FOUR, CYLINDER), colored("container", FOUR, CONTAINER))


@register("align-cylinders-in-boxes", family="sorting")
def align_cylinders_in_boxes() -> TaskGraph:
    return _sort("align-cylinders-in-boxes",
                 "Pick up four cylinders and stand each upright inside the open box of the "
                 "same colour.",
                 colored("cylinder", FOUR, CYLINDER), colored("container", FOUR, CONTAINER))


def _from_pallet(name: str, description: str) -> TaskGraph:
    """Blocks start on a pallet; each goes into the container of its colour."""
    pallet = var("pallet", "pallet", "brown", (0.20, 0.20, 0.0375), description="the pallet")
    blocks = colored("block", FOUR, BLOCK, initial=start_on(pallet))
    return _sort(name, description, blocks, colored("container", FOUR, CONTAINER),
                 extra=[pallet])


@register("color-specific-container-fill", family="sorting", tags=("starts-on-pallet",))
def color_specific_container_fill() -> TaskGraph:
    return _from_pallet("color-specific-container-fill",
                        "Four coloured blocks sit on a pallet; pick each up and place it "
                        "inside the container of the same colour.")


@register("color-coordinated-container-fill", family="sorting", tags=("starts-on-pallet",))
def color_coordinated_container_fill() -> TaskGraph:
    return _from_pallet("color-coordinated-container-fill",
                        "Pick the red, blue, green and yellow blocks off the pallet and put "
                        "each inside the container marked in its colour.")


@register("color-coordinated-ball-stacking", family="sorting")
def color_coordinated_ball_stacking() -> TaskGraph:
    return _sort("color-coordinated-ball-stacking",
                 "Pick up each ball and put it into the container of the same colour, in "
                 "the order red, blue, green, yellow.",
                 colored("ball", FOUR, BALL), colored("container", FOUR, CONTAINER),
                 sequential=True)


@register("stack-cylinder-on-bowl", family="sorting")
def stack_cylinder_on_bowl() -> TaskGraph:
    return _sort("stack-cylinder-on-bowl",
                 "Pick up each cylinder and put it into the bowl of the same colour: red "
                 "first, then blue, then green.",
                 colored("cylinder", THREE, CYLINDER), colored("bowl", THREE, BOWL),
                 sequential=True)


@register("color-coordinated-bowl-insertion", family="sorting")
def color_coordinated_bowl_insertion() -> TaskGraph:
    return _sort("color-coordinated-bowl-insertion",
                 "Pick each L-shaped block and put it into the bowl of the same colour: red "
                 "first, then blue, then green.",
                 colored("ell", THREE, ELL), colored("bowl", THREE, WIDE_BOWL),
                 sequential=True)
