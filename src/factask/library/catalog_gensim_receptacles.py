"""GenSim tasks that move the receptacles themselves: bowls and containers that
start nested in one another or on a pallet, or that must end in a row.

A free (``fixed: false``) bowl or container is carried by its rim
(:mod:`factask.sim.oracle.pick_points`). "Initially stacked" bowls and containers are
nested: each starts inside the next larger one (factask's receptacles have
straight walls, so equal ones cannot nest, and a rim is no support to rest one
on). Unstacking them is a row of the receptacles side by side on the table, and
the blocks are sorted into them after it.
"""

from __future__ import annotations

from collections.abc import Sequence

from factask.graph import StateVariable, TaskGraph
from factask.library.builders import (
    assemble,
    colored,
    region,
    register,
    start_inside,
    start_on,
    use,
    var,
)
from factask.library.conventions import BLOCK, BOWL, CORNER, FOUR
from factask.library.templates import match_pairs

#: Outer size of the larger and the smaller receptacle of a nested pair: the smaller
#: one (8.5 cm inside: a 4 cm block fits turned any way) leaves 1.25 cm of play each
#: side inside the larger, so the cup can take the larger one's rim beside it.
NESTED = (0.15, 0.105)
#: Height of a nested receptacle (m).
NESTED_HEIGHT = 0.05
#: Where stacked or scattered receptacles start: the near half of the workspace,
#: so the row they end in has room beyond them (no receptacle may start where its
#: own row slot is).
NEAR_HALF = region((0.25, 0.45), (-0.5, 0.5))
#: A container six of which stand in a row across the workspace (10 cm: 8 cm inside).
ROW_CONTAINER = (0.10, 0.10, 0.05)
SIX = ("red", "blue", "green", "yellow", "orange", "purple")


def _nested_pairs(kind: str, colors: Sequence[str]) -> list[StateVariable]:
    """Free receptacles of ``kind``, one per colour, stacked in pairs: the second
    colour of each pair starts inside the first. Two stacks of two rather than one of
    four: a fourth level would leave the smallest no room for a block, and the row
    they are unstacked into no room on the table."""
    out: list[StateVariable] = []
    for k, c in enumerate(colors):
        d = NESTED[k % 2]
        initial = start_inside(out[-1]) if k % 2 else NEAR_HALF
        out.append(var(f"{c}_{kind}", kind, c, (d, d, NESTED_HEIGHT), fixed=False,
                       initial=initial))
    return out


def _unstack_and_sort(name: str, description: str, kind: str) -> TaskGraph:
    receptacles = _nested_pairs(kind, FOUR)
    unstack = use("build_row", objects=receptacles)
    # The blocks start in the near half too: the row, kept clear of the receptacles'
    # starts only, then lies beyond them, not beside a block it could just touch (a
    # receptacle hangs from its rim less steadily than a block from its centre).
    blocks = colored("block", FOUR, BLOCK, initial=NEAR_HALF)
    return assemble(name, description, unstack,
                    [use("put_in_container", objects=b, container=r, after=[unstack])
                     for b, r in zip(blocks, receptacles, strict=True)])


@register("container-block-sorting", family="sorting")
def container_block_sorting() -> TaskGraph:
    return _unstack_and_sort(
        "container-block-sorting",
        "Sort four differently coloured blocks (red, blue, green, yellow) into the "
        "containers of the same colour. The containers start stacked (two nested pairs): "
        "unstack "
        "them side by side on the table before sorting the blocks into them.", "container")


@register("color-coordinated-block-bowl-sorting", family="sorting")
def color_coordinated_block_bowl_sorting() -> TaskGraph:
    return _unstack_and_sort(
        "color-coordinated-block-bowl-sorting",
        "Sort four differently coloured blocks (red, blue, green, yellow) into the bowls "
        "of the same colour. The bowls start stacked (two nested pairs): unstack them "
        "side by side "
        "on the table, then put each block into the bowl of its colour.", "bowl")


@register("color-ordered-container-arrangement", family="sorting")
def color_ordered_container_arrangement() -> TaskGraph:
    containers = colored("container", SIX, ROW_CONTAINER, fixed=False, initial=NEAR_HALF)
    sort = match_pairs("put_in_container",
                       list(zip(colored("block", SIX, BLOCK), containers, strict=True)))
    return assemble(
        "color-ordered-container-arrangement",
        "Put each block into the container of its colour, then arrange the containers "
        "in a line in the colour order red, blue, green, yellow, orange, purple.",
        # "Then" needs no `after`: each block's goal is anchored to its container, which
        # the row moves, so the row is solved (and done) first and the blocks follow.
        sort, use("build_row", objects=containers))


@register("move-bowl-from-pallet-to-corner", family="placing")
def move_bowl_from_pallet_to_corner() -> TaskGraph:
    pallet = var("pallet", "pallet", "brown", description="the pallet the bowl starts on")
    bowl = var("bowl", "bowl", "blue", BOWL, fixed=False, initial=start_on(pallet),
               description="the blue bowl on the pallet")
    return assemble(
        "move-bowl-from-pallet-to-corner",
        "Move the blue bowl from the pallet into the corner.",
        use("align_to_corner", objects=bowl,
            corner=var("corner", "corner", "gray", CORNER, description="the corner")),
        extra=[pallet])
