"""GenSim insertion and kitting tasks: pieces into fixtures of their colour or shape.

A fixture is an open frame whose hollow matches a piece (``insert_into_fixture``).
Kitting boards are a ``kit`` plate with one fixture per silhouette standing on it,
so "put the shape in its silhouette" is the same insertion subtask.
"""

from __future__ import annotations

from factask.graph import StateVariable, SubtaskFactor, SubtaskTemplate, TaskGraph
from factask.library.builders import (
    assemble,
    at,
    barrier,
    colored,
    region,
    register,
    use,
    var,
)
from factask.library.catalog_deformable import BAND, PILE_X, SMALL_BLOCK, ZONE_X
from factask.library.conventions import (
    BALL,
    BLOCK,
    BLOCK_FIXTURE,
    CORNER,
    ELL,
    ELL_FIXTURE,
    FOUR,
    LOG,
    LOG_FIXTURE,
    NEAR,
    THREE,
    TUBE,
)
from factask.library.templates import match_pairs, slot
from factask.relations import Aligned
from factask.vocabulary.world import WORKSPACE_Y


def _row(n: int, x: float = 0.64, span: float = 0.7) -> list[tuple[float, float]]:
    """``n`` spots in a row at depth ``x``, left (+y) to right."""
    step = span / n
    return [(x, span / 2 - step / 2 - k * step) for k in range(n)]


def _insert(name: str, description: str, pieces: list[StateVariable],
            fixtures: list[StateVariable], *, sequential: bool = False,
            extra: list[StateVariable] | None = None) -> TaskGraph:
    return assemble(name, description,
                    match_pairs("insert_into_fixture", list(zip(pieces, fixtures, strict=True)),
                                sequential=sequential),
                    extra=extra or [])


@register("insert-ell-in-fixture", family="insertion")
def insert_ell_in_fixture() -> TaskGraph:
    return assemble("insert-ell-in-fixture",
                    "Pick up the L-shaped block and insert it into the fixture on the tabletop.",
                    use("insert_into_fixture", objects=var("blue_ell", "ell", "blue", ELL),
                        fixture=var("fixture", "fixture", "gray", ELL_FIXTURE)))


def _ordered_ells(name: str, description: str) -> TaskGraph:
    fixtures = [var(f"{c}_fixture", "fixture", c, ELL_FIXTURE, initial=at(*xy))
                for c, xy in zip(FOUR, _row(4, 0.62, 0.8), strict=True)]
    return _insert(name, description, colored("ell", FOUR, ELL, initial=NEAR), fixtures,
                   sequential=True)


@register("color-ordered-insertion", family="insertion")
def color_ordered_insertion() -> TaskGraph:
    return _ordered_ells("color-ordered-insertion",
                         "Insert each of four ells into the fixture of its colour, in order "
                         "from left to right: red, blue, green, yellow.")


@register("color-ordered-insertion-new", family="insertion")
def color_ordered_insertion_new() -> TaskGraph:
    return _ordered_ells("color-ordered-insertion-new",
                         "Pick up the red, blue, green and yellow ells and insert each into the "
                         "matching fixture, left to right in that order.")


@register("sequential-block-insertion", family="insertion")
def sequential_block_insertion() -> TaskGraph:
    return _insert("sequential-block-insertion",
                   "Insert each of four blocks into the fixture of its colour in the sequence "
                   "red, blue, green, yellow.",
                   colored("block", FOUR, BLOCK), colored("fixture", FOUR, BLOCK_FIXTURE),
                   sequential=True)


def _beyond_barrier(name: str, description: str, span: float = 0.8) -> TaskGraph:
    fixtures = [var(f"{c}_fixture", "fixture", c, BLOCK_FIXTURE, initial=at(*xy))
                for c, xy in zip(FOUR, _row(4, 0.64, span), strict=True)]
    return _insert(name, description, colored("block", FOUR, BLOCK, initial=NEAR), fixtures,
                   extra=barrier(0.52, span))


@register("insert-blocks-lineup", family="insertion", tags=("barrier",))
def insert_blocks_lineup() -> TaskGraph:
    return _beyond_barrier("insert-blocks-lineup",
                           "Insert each block into the fixture of its colour; the fixtures "
                           "stand in a straight line behind a low barrier.")


@register("mixed-color-block-barrier-insertion", family="insertion", tags=("barrier",))
def mixed_color_block_barrier_insertion() -> TaskGraph:
    return _beyond_barrier("mixed-color-block-barrier-insertion",
                           "Insert the red, blue, green and yellow blocks into the fixtures of "
                           "their colours, reaching over the barrier between blocks and "
                           "fixtures.", span=0.6)


@register("insert-ell-along-square-path", family="insertion")
def insert_ell_along_square_path() -> TaskGraph:
    # The fixtures stand on the corners of a square path (GenSim marks the path with
    # small blocks; here the corners carry the fixtures and the path is not drawn).
    spots = ((0.66, 0.25), (0.66, -0.25), (0.36, 0.25), (0.36, -0.25))
    fixtures = [var(f"{c}_fixture", "fixture", c, ELL_FIXTURE, initial=at(*xy))
                for c, xy in zip(FOUR, spots, strict=True)]
    return _insert("insert-ell-along-square-path",
                   "Insert each of four ells into the fixture of its colour; the fixtures "
                   "stand on the corners of a square.",
                   colored("ell", FOUR, ELL, initial=region((0.42, 0.6), (-0.15, 0.15))),
                   fixtures)


@register("color-coordinated-cylinder-in-box", family="insertion")
def color_coordinated_cylinder_in_box() -> TaskGraph:
    # GenSim's boxes with a slot on top: fixtures whose hollow takes a 4 cm cylinder.
    return _insert("color-coordinated-cylinder-in-box",
                   "Pick up each cylinder and insert it into the slot of the box of the same "
                   "colour.", colored("cylinder", FOUR, (0.04, 0.04, 0.06)),
                   colored("fixture", FOUR, BLOCK_FIXTURE, suffix="box"))


@register("color-coordinated-cylinder-and-box-insertion", family="insertion")
def color_coordinated_cylinder_and_box_insertion() -> TaskGraph:
    colors = ("red", "blue", "yellow", "green")
    return _insert("color-coordinated-cylinder-and-box-insertion",
                   "Insert each cylinder into the slot on top of the box of the same colour, "
                   "in the order red, blue, yellow, green.",
                   colored("cylinder", colors, (0.04, 0.04, 0.06)),
                   colored("fixture", colors, BLOCK_FIXTURE, suffix="box"), sequential=True)


def _corner_pyramid(colors: tuple[str, ...]) -> list[StateVariable]:
    """Corner markers laid out as a pyramid: a base row and the rest above it."""
    if len(colors) == 3:
        spots = [(0.42, 0.1), (0.42, -0.1), (0.62, 0.0)]
    else:
        spots = [(0.40, 0.18), (0.40, 0.0), (0.40, -0.18), (0.62, 0.0)]
    return [var(f"{c}_corner", "corner", c, CORNER, initial=at(*xy),
                description=f"the {c} slot of the corner pyramid")
            for c, xy in zip(colors, spots, strict=True)]


@register("insert-blocks-into-pyramid", family="corners")
def insert_blocks_into_pyramid() -> TaskGraph:
    return assemble("insert-blocks-into-pyramid",
                    "Corner markers form a pyramid of colour-coded slots; put each of the red, "
                    "blue and green blocks into the slot of its colour, from the bottom up.",
                    match_pairs("align_to_corner",
                                list(zip(colored("block", THREE, BLOCK), _corner_pyramid(THREE),
                                         strict=True)), sequential=True))


@register("block-insertion-in-corner-pyramid", family="corners")
def block_insertion_in_corner_pyramid() -> TaskGraph:
    return assemble("block-insertion-in-corner-pyramid",
                    "A pyramid of corner markers has a slot per colour; insert the red, blue, "
                    "green and yellow blocks into their slots from the bottom up.",
                    match_pairs("align_to_corner",
                                list(zip(colored("block", FOUR, BLOCK), _corner_pyramid(FOUR),
                                         strict=True)), sequential=True))


# ----------------------------------------------------------------------- kitting
#: Kitting pieces and the hollow of each (GenSim's kit objects are letters and
#: shapes; factask's rigid pieces are ells, blocks, boxes and cylinders).
SHAPES = (("ell", (0.08, 0.08, 0.03), (0.12, 0.12, 0.03)),
          ("block", (0.04, 0.04, 0.03), BLOCK_FIXTURE),
          ("cylinder", (0.04, 0.04, 0.03), BLOCK_FIXTURE))
#: Where the silhouettes sit: side by side, together the kitting board.
BOARD = ((0.60, 0.11), (0.62, -0.01), (0.62, -0.10))


def _kit(colors: tuple[str, ...]) -> tuple[list[StateVariable], list[StateVariable]]:
    """Pieces and their silhouettes: fixtures side by side that make up the kitting
    board (fixtures standing on a ``kit`` plate are not used: the layout sampler
    can stack one start-on object on another, see docs/library.md)."""
    pieces, holes = [], []
    for (kind, size, hole), color, xy in zip(SHAPES, colors, BOARD, strict=True):
        pieces.append(var(f"{color}_{kind}", kind, color, size))  # type: ignore[arg-type]
        holes.append(var(f"{kind}_silhouette", "fixture", "gray", hole, initial=at(*xy),
                         description=f"the {kind}'s silhouette on the kitting board"))
    return pieces, holes


@register("assembling-kits", family="kitting")
def assembling_kits() -> TaskGraph:
    pieces, holes = _kit(("red", "blue", "green"))
    return _insert("assembling-kits",
                   "Pick up the different pieces and put each into its silhouette on the "
                   "kitting board.", pieces, holes)


@register("assembling-kits-seq", family="kitting")
def assembling_kits_seq() -> TaskGraph:
    pieces, holes = _kit(("red", "blue", "green"))
    return _insert("assembling-kits-seq",
                   "Place each piece in its silhouette on the kitting board in the order "
                   "given: the ell, then the block, then the cylinder.", pieces, holes,
                   sequential=True)


def _tubes(colors: tuple[str, ...]) -> list[StateVariable]:
    """One open tube (a bowl taller than wide) per colour, named ``<colour>_cylinder``
    as GenSim calls them."""
    return [var(f"{c}_cylinder", "bowl", c, TUBE,
                description=f"the {c} cylinder, open on top (a tube)") for c in colors]


@register("insert-color-blocks-into-cylinders", family="insertion")
def insert_color_blocks_into_cylinders() -> TaskGraph:
    pairs = list(zip(colored("block", FOUR, BLOCK), _tubes(FOUR), strict=True))
    return assemble("insert-color-blocks-into-cylinders",
                    "Insert each block into the open cylinder of its colour: red first, then "
                    "blue, green and yellow.",
                    match_pairs("put_in_container", pairs, sequential=True))


@register("color-coordinated-sphere-cylinder-matching", family="insertion")
def color_coordinated_sphere_cylinder_matching() -> TaskGraph:
    pairs = list(zip(colored("ball", FOUR, BALL, suffix="sphere"), _tubes(FOUR), strict=True))
    return assemble("color-coordinated-sphere-cylinder-matching",
                    "Drop each sphere into the open cylinder of its colour.",
                    match_pairs("put_in_container", pairs))


@register("sequential-insertion-and-stacking", family="insertion")
def sequential_insertion_and_stacking() -> TaskGraph:
    fixtures = [var(f"{c}_fixture", "fixture", c, ELL_FIXTURE, initial=at(*xy))
                for c, xy in zip(THREE, _row(3, 0.64, 0.6), strict=True)]
    ells = colored("ell", THREE, ELL, initial=NEAR)
    corner = var("corner", "corner", "gray", (ELL[0], ELL[1], 0.001),
                 description="the corner of the tabletop the ells are stacked in")
    inserts: list[TaskGraph] = []
    for ell, fixture in zip(ells, fixtures, strict=True):  # each undone by the stack
        inserts.append(use("insert_into_fixture", objects=ell, fixture=fixture,
                           after=inserts[-1:], milestone=True))
    return assemble("sequential-insertion-and-stacking",
                    "Insert the red, blue and green ells into the fixtures of their colours, in "
                    "that order; then take them out again and stack them in the corner: red "
                    "at the bottom, blue in the middle, green on top.",
                    inserts, use("stack_on_base", layers=ells, base=corner, after=inserts))


@register("create-pyramid-with-color-coded-ells", family="insertion")
def create_pyramid_with_color_coded_ells() -> TaskGraph:
    # GenSim's code: red, blue and yellow in a row on the pallet, green on the middle
    # one (an ell carries only an equal ell, laid exactly on it).
    pallet = var("pallet", "pallet", "brown", (0.30, 0.15, 0.02), description="the pallet")
    red, blue, yellow, green = colored("ell", ("red", "blue", "yellow", "green"), ELL)
    row = use("align_along_line", objects=[red, blue, yellow], line=pallet)
    return assemble("create-pyramid-with-color-coded-ells",
                    "Build a pyramid of ells on the pallet: red, blue and yellow side by side "
                    "at the bottom, the green ell on top of the blue one.",
                    row, use("stack_on_base", layers=[green], base=blue, after=[row]))


@register("vertical-insertion-blocks", family="insertion")
def vertical_insertion_blocks() -> TaskGraph:
    # GenSim's "stands set upright" that blocks are inserted into (its code overlaps
    # each block with a stand): upright square sleeves, block fixtures 8 cm tall.
    sleeves = [var(f"{c}_stand", "fixture", c, (BLOCK_FIXTURE[0], BLOCK_FIXTURE[1], 0.08),
                   description=f"the upright {c} stand a block is inserted into")
               for c in FOUR]
    return _insert("vertical-insertion-blocks",
                   "Insert each block into the upright stand of its colour: red into red, "
                   "blue into blue, green into green, yellow into yellow.",
                   colored("block", FOUR, BLOCK), sleeves)


#: GenSim's three ell sizes (large, medium, small), each 2 cm tall.
ELL_SIZES = (("large", (0.08, 0.08, 0.02)), ("medium", (0.06, 0.06, 0.02)),
             ("small", (0.04, 0.04, 0.02)))


@register("multi-level-insertion-and-zone-matching", family="insertion")
def multi_level_insertion_and_zone_matching() -> TaskGraph:
    # GenSim's code sends the three ells of a colour to its zone's pose in the order
    # large, medium, small: a column of three levels, each ell centred on the larger.
    fragments = []
    for c in THREE:
        zone = var(f"{c}_zone", "zone", c, (0.12, 0.12, 0.001), description=f"the {c} zone")
        ells = [var(f"{size}_{c}_ell", "ell", c, dims, description=f"the {size} {c} ell")
                for size, dims in ELL_SIZES]
        fragments.append(use("stack_on_base", layers=ells, base=zone))
    return assemble("multi-level-insertion-and-zone-matching",
                    "Put the ells of each colour into the zone of that colour in three levels: "
                    "the large one first, the medium one on it, the small one on top.",
                    fragments)


@register("rotate-and-insert-cylinder", family="insertion")
def rotate_and_insert_cylinder() -> TaskGraph:
    # The cylinder lies on its side (a log) from the start: a top-down suction cup
    # cannot tip an upright one over; "rotate it horizontally" is the turn about the
    # vertical that lines it up with the fixture's slot (both start at random yaws).
    return assemble("rotate-and-insert-cylinder",
                    "Pick up the red cylinder lying on the table, turn it to line up with "
                    "the slot of the green fixture and insert it there.",
                    use("insert_into_fixture", objects=var("red_cylinder", "log", "red", LOG),
                        fixture=var("green_fixture", "fixture", "green", LOG_FIXTURE)))


#: A box with a hole in its side, as high as a log is thick (its hole, in the middle of
#: the side, then faces a log lying on the table: ``aligned`` mode ``hole``).
HOLED_BOX = (0.08, 0.08, LOG[2] + 0.01)

#: Line a log up with a box's hole. One task uses it, so it is not a library template
#: (``templates.TEMPLATES`` holds the shared ones); it only writes the three factors.
_ALIGN_WITH_HOLE = SubtaskTemplate(
    name="align_with_hole",
    description="Line the {objects} up with the hole in the {box}.",
    slots=[slot("objects", "the log to line up", ["log"], many=True, movable=True),
           slot("box", "the box whose side has the hole", ["holed_box"])],
    factors=[SubtaskFactor(
        name="align", description="line the {objects} up with the hole in the {box}",
        goal=Aligned(objects=["objects"], reference="box", mode="hole"))],
)


@register("cylinder-alignment", family="insertion")
def cylinder_alignment() -> TaskGraph:
    # A cylinder "aligned with the hole" lies on the table in front of the hole, its
    # axis through it: a log (a suction cup cannot tip an upright cylinder over), in
    # a box whose hole is at the height of the log's axis.
    logs = colored("log", THREE, LOG, suffix="cylinder")
    boxes = colored("holed_box", THREE, HOLED_BOX, suffix="box")
    return assemble("cylinder-alignment",
                    "Line each cylinder up with the hole in the side of the box of its "
                    "colour: red first, then blue, then green.",
                    match_pairs(_ALIGN_WITH_HOLE, list(zip(logs, boxes, strict=True)),
                                sequential=True))


#: color-coordinated-insertion-and-sweeping: a zone wide enough for its ell fixture
#: and, on the side the pile comes from, a strip the swept blocks rest in.
SWEEP_ZONE = (0.16, 0.16, 0.001)
#: How far (m) the ell stands from its zone's centre, away from the pile's side.
ELL_BACK = 0.02


@register("color-coordinated-insertion-and-sweeping", family="deformable")
def color_coordinated_insertion_and_sweeping() -> TaskGraph:
    # The description inserts small blocks into ell-shaped fixtures and then sweeps
    # the same blocks into zones; the assets are ell pieces, small blocks and zones.
    # One tool does not do both (a spatula cannot pick; a suction cup cannot sweep),
    # and a block cannot end in two places, so the ell fixtures stand in the zones of
    # their colours (fixed, as fixtures are) and each colour's blocks, a pile, are
    # swept into the zone holding its ell: into the fixture's zone, beside the ell.
    # Each colour has its own band across the table, as in sweep-and-sort-blocks.
    colors = THREE
    width = (WORKSPACE_Y[1] - WORKSPACE_Y[0] - 0.2) / len(colors)
    fragments, ells = [], []
    for k, c in enumerate(colors):
        y = WORKSPACE_Y[0] + 0.1 + (k + 0.5) * width
        pile = var(f"{c}_pile", "pile", c, SMALL_BLOCK, count=10,
                   initial=region(PILE_X, (y - BAND, y + BAND)),
                   description=f"a pile of 10 small {c} blocks")
        zone = var(f"{c}_zone", "zone", c, SWEEP_ZONE, initial=at(ZONE_X, y),
                   description=f"the {c} zone")
        ells.append(var(f"{c}_ell", "ell", c, ELL, fixed=True,
                        initial=at(ZONE_X + ELL_BACK, y, 180.0),
                        description=f"the {c} ell-shaped fixture in the {c} zone"))
        fragments.append(use("push_pile_into_zone", prefix=c, objects=[pile], zone=zone))
    return assemble(
        "color-coordinated-insertion-and-sweeping",
        "Red, blue and green ell-shaped fixtures stand in the zones of their colours; "
        "sweep the piles of small blocks of the same colours into those zones, beside "
        "their fixtures, without pushing blocks across another colour's zone.",
        fragments, extra=ells)
