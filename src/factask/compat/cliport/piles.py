"""Ravens' piles in factask: many small blocks swept with a spatula become one pile.

A task that pushes (``ee = Spatula`` or ``primitive = primitives.push``, as
Ravens' sweeping and separating tasks, or one that called GenSim's ``make_piles``) and
has a ``zone`` goal over small blocks only (``block/small.urdf``, what
``make_piles`` adds) gets, for that goal, one ``pile`` variable of those blocks
(starting as a cluster centred where the task spawned them) and a
``pile_in_zone`` factor whose threshold is Ravens' own: an episode is done when
the zone metric is within 1 % of the goal's reward (:data:`RAVENS_PILE_FRACTION`).
The Ravens goal queue names the blocks by the pile's instance names, so Ravens'
zone metric scores the same blocks.

A goal over blocks of several colours (GenSim's mix-piles: two ``make_piles``
calls, one goal over both) gets one pile per colour, all in its one factor (the
share is over all of them, as Ravens' metric): a single pile variable has one
colour, and the blue blocks were drawn red. ``make_piles`` spawns every pile in the
same 20 x 20 cm square, so a pile whose starting cluster would overlap an earlier
pile's starts at a random free spot instead (warning, :func:`pile_variables`):
factask's piles are separate clusters, and pinned on top of each other the reset
found no layout in any episode.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from factask.compat.cliport import primitives
from factask.compat.cliport.goals import RecordedGoal
from factask.compat.cliport.grippers import Spatula
from factask.compat.cliport.recorder import RecordedObject
from factask.sim.layout.pile import pile_half_extent
from factask.vocabulary.names import instance_names, unique_name
from factask.vocabulary.variables import AtFixedPose, OnTable, StateVariable
from factask.vocabulary.world import WORKSPACE_X, WORKSPACE_Y

#: Ravens ends an episode when the zone metric is within 1 % of the goal's reward.
RAVENS_PILE_FRACTION = 0.99
#: Blocks no larger than this (m, every side) can be a pile's blocks.
PILE_BLOCK_MAX = 0.02


@dataclass
class Pile:
    """The blocks of one zone goal, as one pile variable.

    Attributes:
        name: The pile variable's name.
        goal: Index of the goal whose objects the blocks are.
        blocks: The recorded blocks, in the goal's order (instance k is block k).
    """

    name: str
    goal: int
    blocks: list[RecordedObject]

    def variable(self) -> StateVariable:
        """The pile variable: a cluster centred where the task spawned the blocks."""
        first = self.blocks[0]
        xy = np.mean([o.pos[:2] for o in self.blocks], axis=0)
        x = float(np.clip(xy[0], *WORKSPACE_X))
        y = float(np.clip(xy[1], *WORKSPACE_Y))
        colors = Counter(o.color for o in self.blocks)
        return StateVariable(
            name=self.name, kind="pile", count=len(self.blocks),
            description=f"{len(self.blocks)} x {first.urdf} (CLIPort objects "
                        f"{self.blocks[0].obj_id}..{self.blocks[-1].obj_id})",
            size=tuple(float(s) for s in first.size), color=colors.most_common(1)[0][0],
            initial=AtFixedPose(x=x, y=y))


def pushes(task: Any) -> bool:
    """True when the task sweeps with a spatula (Ravens' ``ee`` / ``primitive``, or
    GenSim's ``make_piles``, whose tasks get the spatula from their template)."""
    return (getattr(task, "ee", None) is Spatula
            or getattr(task, "primitive", None) is primitives.push
            or bool(getattr(task, "_factask_made_piles", False)))


def _pile_blocks(goal: RecordedGoal) -> bool:
    return goal.metric == "zone" and len(goal.objs) > 1 and all(
        o.kind == "block" and max(o.size) <= PILE_BLOCK_MAX for o in goal.objs)


def find_piles(task: Any, goals: list[RecordedGoal], names: dict[int, str]) -> list[Pile]:
    """The piles of a pushing task, one per zone goal over small blocks only; renames
    their blocks in ``names`` to the pile's instance names.

    Args:
        task: The reset task instance.
        goals: Its recorded goals.
        names: Object id -> variable name (updated in place).

    Returns:
        The piles (none for a task that does not push).
    """
    if not pushes(task):
        return []
    out: list[Pile] = []
    claimed: set[int] = set()
    taken = set(names.values())
    for g in goals:
        ids = [o.obj_id for o in g.objs]
        if not _pile_blocks(g) or claimed & set(ids):
            continue
        claimed |= set(ids)
        by_color: dict[str, list[RecordedObject]] = {}
        for o in g.objs:  # one pile per colour, in the order the colours first appear
            by_color.setdefault(o.color, []).append(o)
        for color, blocks in by_color.items():
            name = unique_name(f"pile_{color}", taken)
            for o, inst in zip(blocks, instance_names(name, len(blocks)), strict=True):
                names[o.obj_id] = inst
            out.append(Pile(name, g.index, blocks))
    return out


def pile_variables(piles: list[Pile], warn: Callable[[str], None]) -> list[StateVariable]:
    """The piles' variables: each a cluster where the task spawned its blocks, unless
    that cluster would overlap the cluster of an earlier pile kept there; such a pile
    starts at a random free spot (``OnTable``).

    Why: GenSim's ``make_piles`` spawns every pile in one 20 x 20 cm square, its
    blocks mixed; factask's piles are separate clusters, and two pinned at one
    centre left the reset no layout in any episode.

    Args:
        piles: The piles, in goal order.
        warn: Receives one warning per pile moved.

    Returns:
        One variable per pile, in the same order.
    """
    out: list[StateVariable] = []
    kept: list[tuple[str, np.ndarray, float]] = []  # (name, centre, half side)
    for p in piles:
        var = p.variable()
        init = var.initial
        if not isinstance(init, AtFixedPose):  # never: a pile starts where it was spawned
            out.append(var)
            continue
        centre, half = np.array([init.x, init.y]), pile_half_extent(var)
        clash = [name for name, c, h in kept if np.all(np.abs(centre - c) < half + h)]
        if clash:
            warn(f"{p.name}: its blocks were spawned where {', '.join(clash)} starts (GenSim's "
                 "make_piles spawns every pile in one square, mixed); it starts as a "
                 "separate cluster at a random free spot")
            var = var.model_copy(update={"initial": OnTable()})
        else:
            kept.append((p.name, centre, half))
        out.append(var)
    return out


def make_piles(env: Any, bounds: np.ndarray, num_blocks: int, block_color: Any = None,
               ) -> list[int]:
    """GenSim's ``Task.make_piles``: ``num_blocks`` small blocks at random in a
    20 x 20 cm square of the workspace; returns their ids.

    Args:
        env: The recording environment (its ``add_object``).
        bounds: The task's workspace bounds (3 x 2).
        num_blocks: How many blocks.
        block_color: Palette name or RGB, or None (the URDF's colour).
    """
    ids = []
    for _ in range(num_blocks):
        rx = bounds[0, 0] + 0.15 + np.random.rand() * 0.2
        ry = bounds[1, 0] + 0.4 + np.random.rand() * 0.2
        theta = np.random.rand() * 2 * np.pi
        quat = (0.0, 0.0, float(np.sin(theta / 2)), float(np.cos(theta / 2)))
        ids.append(env.add_object("block/small.urdf", ((rx, ry, 0.01), quat),
                                  color=block_color))
    return ids
