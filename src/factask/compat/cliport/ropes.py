"""Ravens' bead-chain ropes in factask: linked multibodies become one ``rope`` variable.

Ravens' rope tasks (and GenSim's ``make_ropes``) build a rope as beads made with
``createMultiBody`` and linked one to the next by ``createConstraint``. The
pattern is recognised from what was recorded (:mod:`factask.compat.cliport.bodies`),
never from a file or class name: every connected group of two or more multibodies
linked by point-to-point (or spherical, or fixed) constraints that forms a simple
chain of like beads is one rope (kind ``rope``; ``count`` = the beads, a segment as
long as the link pitch and as thick as a bead), its instances named in chain order.

A ``pose`` goal over all the beads of one rope becomes a
:class:`~factask.relations.RopeAlong` on ``points``: bead k's target (through
``matches``) is segment k's slot, and either end may go first when ``matches``
also lets every bead take the mirrored target (Ravens' ``eye + flipped eye``).
factask checks the whole rope in one direction; Ravens lets each bead take either
of its targets, so a rope factask accepts Ravens accepts too. The Ravens goal
queue keeps the beads as the rope's instances, so ``--ravens`` scores the same
segments with Ravens' pose metric.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import linear_sum_assignment

from factask.compat.cliport.bodies import LINK_JOINTS, MULTIBODY
from factask.compat.cliport.errors import Unsupported
from factask.compat.cliport.goals import RecordedGoal
from factask.compat.cliport.recorder import RecordedObject, Session
from factask.relations import RopeAlong, TargetPose
from factask.vocabulary.names import instance_names, unique_name
from factask.vocabulary.variables import AtFixedPose, OnTable, StateVariable
from factask.vocabulary.world import WORKSPACE_X, WORKSPACE_Y

#: Kinds of ``add_object`` bodies that may be a rope's beads when linked.
BEAD_KINDS = ("block", "ball", "cylinder")
#: Beads whose extents differ by more than this (m) are not one rope's.
SIZE_SLACK = 1e-4
#: A rope whose centre is within this (m) of a ``get_random_pose`` spot starts at a
#: random free spot each episode (Ravens drops its beads there).
SPOT_SLACK = 1e-3
#: Decimals kept of target coordinates (1 micrometre).
DECIMALS = 6


@dataclass
class Rope:
    """The beads of one chain, as one rope variable.

    Attributes:
        name: The rope variable's name.
        beads: The recorded beads in chain order (instance k is bead k).
        pitch: Distance between linked beads' centres (a segment's length), metres.
        random_start: The task dropped the beads at a ``get_random_pose`` spot.
    """

    name: str
    beads: list[RecordedObject]
    pitch: float
    random_start: bool = False

    @property
    def ids(self) -> list[int]:
        """The beads' object ids, in chain order."""
        return [b.obj_id for b in self.beads]

    def variable(self) -> StateVariable:
        """The rope variable: segments as long as the pitch, as thick as a bead."""
        xy = np.mean([b.pos[:2] for b in self.beads], axis=0)
        thick = float(max(self.beads[0].size))
        colors = Counter(b.color for b in self.beads)
        initial: Any = OnTable() if self.random_start else AtFixedPose(
            x=float(np.clip(xy[0], *WORKSPACE_X)), y=float(np.clip(xy[1], *WORKSPACE_Y)))
        return StateVariable(
            name=self.name, kind="rope", count=len(self.beads),
            description=f"a rope of {len(self.beads)} beads (CLIPort objects "
                        f"{self.beads[0].obj_id}..{self.beads[-1].obj_id}, linked "
                        f"{self.pitch * 100:.2f} cm apart)",
            size=(round(self.pitch, DECIMALS), thick, thick),
            color=colors.most_common(1)[0][0], initial=initial)


def _chains(session: Session, warn: Any) -> list[list[int]]:
    """Groups of linked bodies, each in chain order (from its lower-id end): beads made
    with ``createMultiBody``, or movable blocks, balls and cylinders added with
    ``add_object`` (three or more of them: two linked objects are no rope)."""
    bodies = {oid for oid, o in session.objects.items()
              if o.urdf == MULTIBODY or (o.category == "rigid" and o.kind in BEAD_KINDS)}
    adj: dict[int, set[int]] = {}
    for cid, c in session.constraints.items():
        if c.joint not in LINK_JOINTS or c.parent not in bodies or c.child not in bodies:
            warn(f"pybullet constraint {cid} (bodies {c.parent} -> {c.child}, joint type "
                 f"{c.joint}) is not a link between two beads; factask drops it")
            continue
        if c.links != (-1, -1):
            raise Unsupported(f"pybullet constraint {cid} links body links {c.links}; only "
                              "base-to-base links (a bead chain) are supported")
        adj.setdefault(c.parent, set()).add(c.child)
        adj.setdefault(c.child, set()).add(c.parent)
    out, seen = [], set()
    for start in sorted(adj):
        if start in seen:
            continue
        group, todo = set(), [start]
        while todo:
            b = todo.pop()
            if b not in group:
                group.add(b)
                todo.extend(adj[b] - group)
        seen |= group
        if len(group) < 3 and any(session.objects[b].urdf != MULTIBODY for b in group):
            warn(f"objects {sorted(group)} are linked by a constraint; factask drops it "
                 "(three or more linked beads make a rope)")
            continue
        edges = sum(len(adj[b]) for b in group) // 2
        ends = sorted(b for b in group if len(adj[b]) == 1)
        if edges != len(group) - 1 or len(ends) != 2:
            raise Unsupported(f"bodies {sorted(group)} are linked in a ring or a tree; "
                              "factask models one simple chain of beads as a rope")
        order, prev = [ends[0]], None
        while len(order) < len(group):
            nxt = next(b for b in adj[order[-1]] if b != prev)
            prev = order[-1]
            order.append(nxt)
        out.append(order)
    return out


def _pitch(session: Session, chain: list[int]) -> float:
    """Centre-to-centre distance of linked beads: the link points' offset, or (links
    at the centres) the beads' recorded distance."""
    steps = []
    for c in session.constraints.values():
        if {c.parent, c.child} <= set(chain):
            steps.append(float(np.linalg.norm(c.parent_frame - c.child_frame)))
    pitch = float(np.median(steps)) if steps else 0.0
    if pitch < 1e-6:
        pos = np.array([session.objects[b].pos for b in chain])
        pitch = float(np.median(np.linalg.norm(np.diff(pos, axis=0), axis=1)))
    if pitch < 1e-4:
        raise Unsupported(f"the beads {chain[0]}..{chain[-1]} are linked at one point; "
                          "a rope needs its beads apart")
    return pitch


def find_ropes(session: Session, names: dict[int, str], warn: Any) -> list[Rope]:
    """The ropes among the recorded bodies; renames their beads in ``names`` to the
    rope's instance names.

    Args:
        session: The load's recording (objects, constraints).
        names: Object id -> variable name (updated in place).
        warn: Records a warning.

    Raises:
        Unsupported: linked bodies that are not one simple chain of like beads.
    """
    out: list[Rope] = []
    taken = set(names.values())
    for chain in _chains(session, warn):
        beads = [session.objects[b] for b in chain]
        size = np.array(beads[0].size)
        if any(np.abs(np.array(b.size) - size).max() > SIZE_SLACK for b in beads):
            raise Unsupported(f"the linked bodies {chain[0]}..{chain[-1]} differ in size; "
                              "factask's rope has like segments")
        color = Counter(b.color for b in beads).most_common(1)[0][0]
        name = unique_name(f"rope_{color}", taken)
        for oid, inst in zip(chain, instance_names(name, len(chain)), strict=True):
            names[oid] = inst
        xy = np.mean([b.pos[:2] for b in beads], axis=0)
        random_start = any(float(np.linalg.norm(np.array(s[:2]) - xy)) < SPOT_SLACK
                           for s in session.random_spots)
        out.append(Rope(name, beads, _pitch(session, chain), random_start))
        warn(f"{name}: {len(chain)} linked beads become a rope of {len(chain)} segments "
             f"{out[-1].pitch * 100:.2f} cm long; it starts laid out straight (Ravens drops "
             "its beads in a heap)")
    return out


def _sequence(goal: RecordedGoal, rows: list[int]) -> tuple[list[int], bool]:
    """Target column of each bead in chain order (bead k is goal row ``rows[k]``),
    and whether the reversed sequence is allowed too.

    Of the assignments ``matches`` allows (each bead its own row's column when
    the targets follow the objects, or any full assignment), the one with the
    shortest run through the targets."""
    m = goal.matches
    pts = np.array([p[:2] for p, _ in goal.targets], dtype=float)
    candidates = []
    if m.shape[1] >= len(rows):
        candidates.append(list(rows))
    r, c = linear_sum_assignment(-m[rows, :])
    if m[np.asarray(rows)[r], c].all():
        seq = [0] * len(rows)
        for i, j in zip(r, c, strict=True):
            seq[i] = int(j)
        candidates.append(seq)
    valid = [s for s in candidates if len(set(s)) == len(s)
             and all(m[row, j] for row, j in zip(rows, s, strict=True))]
    if not valid:
        raise Unsupported(f"goal {goal.index}: matches give the rope's beads no target each")
    best = min(valid, key=lambda s: float(np.linalg.norm(np.diff(pts[s], axis=0),
                                                         axis=1).sum()))
    either = all(m[row, j] for row, j in zip(rows, best[::-1], strict=True))
    return best, either


def rope_goal(goal: RecordedGoal, ropes: list[Rope], extra: dict[str, Any]
              ) -> RopeAlong | None:
    """A ``rope_along`` for a goal over a rope's beads, or None if the goal names no
    bead.

    Args:
        goal: The recorded goal.
        ropes: The task's ropes.
        extra: Keyword arguments for the relation (tolerances).

    Raises:
        Unsupported: a goal over some beads only, beads and other objects, or a
            metric other than ``pose``.
    """
    ids = [o.obj_id for o in goal.objs]
    rope = next((r for r in ropes if set(r.ids) & set(ids)), None)
    if rope is None:
        return None
    if set(ids) != set(rope.ids) or len(ids) != len(rope.ids):
        raise Unsupported(f"goal {goal.index} names {len(set(ids) & set(rope.ids))} of the "
                          f"{len(rope.ids)} beads of {rope.name}"
                          + (" and other objects" if set(ids) - set(rope.ids) else "")
                          + "; factask's rope goals lay out a whole rope")
    if goal.metric != "pose":
        raise Unsupported(f"goal {goal.index}: a {goal.metric!r} goal over a rope's beads; "
                          "factask lays ropes out on pose targets")
    rows = [ids.index(b) for b in rope.ids]
    seq, either = _sequence(goal, rows)
    points = [TargetPose(x=round(float(goal.targets[j][0][0]), DECIMALS),
                         y=round(float(goal.targets[j][0][1]), DECIMALS)) for j in seq]
    return RopeAlong(objects=[rope.name], points=points, either_end=either, **extra)


def make_ropes(task: Any, env: Any, corners: Any, radius: float, n_parts: int,
               color_name: str) -> tuple[list[Any], list[Any], np.ndarray]:
    """GenSim's ``Task.make_ropes``, through the PyBullet stand-ins (so the rope is
    recognised as any bead chain is): ``n_parts`` cubes of half side ``radius``
    stacked up from a random spot, each linked to the one before by a point-to-point
    constraint one pitch above its centre; the inner beads coloured ``color_name``.

    Returns:
        (objects, targets, matches), as GenSim's.
    """
    from factask.compat.cliport import pybullet_stub as p
    from factask.compat.cliport import utils

    corner0, corner1 = corners
    increment = (np.float32(corner1) - np.float32(corner0)) / n_parts
    pitch = float(np.linalg.norm(increment))
    position, _ = task.get_random_pose(env, (0.1, 0.1, 0.1))
    position = np.float32(position)
    shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=[radius] * 3)
    visual = p.createVisualShape(p.GEOM_SPHERE, radius=radius * 1.5)
    objects, targets, parent = [], [], -1
    for i in range(n_parts):
        position[2] += pitch
        part = p.createMultiBody(0.1, shape, visual, basePosition=position)
        if parent > -1:
            link = p.createConstraint(parent, -1, part, -1, p.JOINT_POINT2POINT, (0, 0, 0),
                                      (0, 0, pitch), (0, 0, 0))
            p.changeConstraint(link, maxForce=100)
        if 0 < i < n_parts - 1:
            p.changeVisualShape(part, -1, rgbaColor=[*utils.COLORS[color_name], 1])
        env.obj_ids["rigid"].append(part)
        parent = part
        objects.append((part, (0, None)))
        targets.append((np.float32(corner0) + i * increment + increment / 2, (0, 0, 0, 1)))
    matches = np.clip(np.eye(n_parts) + np.eye(n_parts)[::-1], 0, 1)
    return objects, targets, matches


__all__ = ["Rope", "find_ropes", "make_ropes", "rope_goal"]
