"""The oracle's next move for a ``rope_along`` factor: which segment, and where.

A rope is a chain: segment k's head (+x) is linked to segment k+1's tail. Two
rules make the moves converge (:func:`plan_rope_carry`):

* **Head first along the run.** A segment is set down on its slot turned to the
  run's direction there, its head towards the next segment's slot (the run's
  direction, or the opposite one when the rope lies reversed). A segment is a box,
  symmetric under a half turn, but its links are not: set down the other way
  round, its neighbour must fold back over it, and that fold holds rope the far
  end then lacks. Placing one end then drags the other end off, and back: the
  oscillation seen on 2 of 12 seeds before.
* **Slack.** Slots a whole segment apart (Ravens' bead targets) leave the rope no
  slack: laid exactly on them it is taut, and setting one end down drags the
  other off its slot. The oracle aims at the slots drawn together along the run
  towards its middle, :data:`~factask.relations.rope.SLOT_PITCH` of a segment
  apart (:func:`aim_points`; at most ~1 cm at the ends of a 20-segment rope,
  within Ravens' 2 cm); slots already that close are aimed at as they are.
* **Folds before the farthest segment.** After the two ends
  (:func:`~factask.relations.rope.rope_slot_order`), a segment near its slot but
  turned more than :data:`KINK_DEG` from the run's direction is placed next, even
  when it is within tolerance of its slot: straightening it gives the rope its
  length back. A segment straightened :data:`MAX_FOLD_FIXES` times that its
  neighbours turned back is no fold any more (the oracle's choice).
* **A slow carry.** The carry moves at
  :data:`~factask.sim.robots.low_carry.CARRY_SPEED`: carried fast, the rope trailing
  behind runs on when the segment stops and piles up over it (a tangle no single
  placement undoes).

* **The far end first.** Of the two ends, the one whose slot lies farther from
  the rope goes first: it drags the whole rope towards the run, past any block
  near the other end. Placing the near end first, a rope lying beyond a block
  at that end hooks round it, and setting the far end down then drags the whole
  rope back round the block (``connect-boxes-with-rope``: floating seeds 2 and
  28 of 0-39).
* **Round solid objects.** The cup carries a segment 2 cm high, lower than a
  block: a carry whose straight line passes within :data:`CLEARANCE` of a solid
  object taller than a segment goes to a waypoint beside it first
  (:func:`detour`; the next move goes on from there). A segment whose grasp
  would put the cup on such an object (the cup meets the object's top before
  the segment) is moved by the nearest neighbour in the chain that the cup can
  reach, to that neighbour's own slot.

Each move is a low carry (:mod:`factask.sim.robots.low_carry`): the segment is lifted
:data:`~factask.sim.robots.low_carry.ROPE_LIFT` and the rest of the rope slides after it.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping

import numpy as np

from factask.geometry import Pose, wrap_angle
from factask.relations.rope import SLOT_PITCH, rope_slot_order
from factask.relations.solving import SolvedFactor
from factask.relations.status import FactorStatus
from factask.scene.collision import WORKSPACE_CENTER, WORKSPACE_HALF
from factask.scene.objects import Area, SceneObject, top_z
from factask.scene.routes import RouteMap, gap_to, grown, keeps_clearance, ring_points
from factask.sim.robots.low_carry import ROPE_LIFT, CarryAction
from factask.sim.robots.suction import CUP_RADIUS

#: A segment turned more than this (degrees) from the run's direction is a fold...
KINK_DEG = 90.0
#: Straightening one segment this often is enough (its neighbours hold it turned).
MAX_FOLD_FIXES = 2
#: ... when it lies within this (m) of where it is aimed (farther off, it is merely
#: not laid out yet).
FOLD_NEAR = 0.04
#: A carried segment (and the cup over it) keeps this far (m) from a solid object's
#: footprint: the cup's radius and a little.
CLEARANCE = CUP_RADIUS + 0.004
#: A segment is grasped only where the cup keeps this far (m) from a solid object.
GRASP_CLEARANCE = CUP_RADIUS + 0.002
#: A waypoint of a detour lies this far (m) beyond :data:`CLEARANCE` from the object.
DETOUR_MARGIN = 0.01
#: Steps (m) at which a carry's straight line is checked.
PATH_STEP = 0.004
#: Neighbours (each way along the chain) tried when a segment cannot be grasped.
GRASP_REACH = 3


def segment_slots(solved: SolvedFactor, status: FactorStatus) -> dict[str, int]:
    """Every segment's slot in the rope's current direction (placed ones too)."""
    slots = {name: int(s) for name, s in status.placed.items() if s is not None}
    slots.update(status.targets)
    return slots


def heading(solved: SolvedFactor, objects: Mapping[str, SceneObject], name: str,
            slot: int) -> float:
    """The yaw (rad) segment ``name`` should have on ``slot``: its head towards the
    next segment's slot (the slot's yaw, turned half round when the rope lies
    reversed along the run)."""
    k = solved.objects.index(name)
    yaw = solved.target_pose(objects[name], slot).yaw
    return wrap_angle(yaw + (math.pi if slot != k else 0.0))


def aim_points(slots: np.ndarray, segment: float, pitch: float = SLOT_PITCH) -> np.ndarray:
    """Where to set the segments down: the run through ``slots`` (n, 2) drawn
    together towards its middle (along its length) until neighbours are at most
    ``pitch`` segment lengths apart.

    Args:
        slots: The slots' centres in run order.
        segment: A segment's length (m).
        pitch: The widest spacing aimed at, in segment lengths.
    """
    steps = np.linalg.norm(np.diff(slots, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(steps)])
    if len(slots) < 2 or s[-1] <= 0:
        return slots.copy()
    f = min(1.0, pitch * segment * (len(slots) - 1) / s[-1])
    want = s[-1] / 2 + (s - s[-1] / 2) * f
    return np.column_stack([np.interp(want, s, slots[:, 0]), np.interp(want, s, slots[:, 1])])


def solid_obstacles(objects: Mapping[str, SceneObject], poses: Mapping[str, Pose],
                    rope: Collection[str], height: float) -> list[tuple[SceneObject, Pose]]:
    """The objects a low carry must go round: solid (colliding), not a rope's
    segment or a pile's block, and taller than ``height`` (a segment).

    Args:
        objects: Scene objects by instance name.
        poses: Current poses.
        rope: The rope's own segments (never obstacles).
        height: A segment's height (m).
    """
    return [(o, poses[n]) for n, o in objects.items()
            if n not in rope and n in poses and o.collides and o.kind not in ("rope", "pile")
            and o.size[2] > height]


def footprints(obstacles: list[tuple[SceneObject, Pose]]) -> list[Area]:
    """The obstacles' footprints, as the route planner's rectangles."""
    return [Area(pose.pos[:2], pose.yaw, obj.half_xy) for obj, pose in obstacles]


def path_clear(a: np.ndarray, b: np.ndarray, obstacles: list[tuple[SceneObject, Pose]],
               clearance: float = CLEARANCE) -> bool:
    """True when a carry's straight line from ``a`` to ``b`` (x, y) keeps ``clearance``
    from every obstacle (:func:`factask.scene.routes.keeps_clearance`, every
    :data:`PATH_STEP`)."""
    return keeps_clearance(a, b, footprints(obstacles), clearance, PATH_STEP)


def detour(a: np.ndarray, b: np.ndarray, obstacles: list[tuple[SceneObject, Pose]],
           clearance: float = CLEARANCE) -> np.ndarray | None:
    """The first waypoint (x, y) of a carry from ``a`` to ``b`` whose straight line
    passes too near an obstacle, or None when the line is clear (or no way round is
    found).

    The route is :mod:`factask.scene.routes`' (fewest legs, then shortest): its
    waypoints are the points round each obstacle (its footprint's corners and edge
    middles, :data:`DETOUR_MARGIN` beyond ``clearance``) inside the workspace, every
    leg keeping ``clearance`` (:func:`path_clear`). The next move goes on from the
    waypoint.

    Args:
        a: Where the carry starts.
        b: Where it ends.
        obstacles: The solid objects (see :func:`solid_obstacles`).
        clearance: How far the legs keep from them.
    """
    rects = footprints(obstacles)

    def clear(p: np.ndarray, q: np.ndarray) -> bool:
        return keeps_clearance(p, q, rects, clearance, PATH_STEP)

    def to_b(q: np.ndarray) -> tuple[float, int]:
        return (float(np.linalg.norm(b - q)), 0) if clear(q, b) else (math.inf, 0)

    if clear(a, b):
        return None
    lo, hi = WORKSPACE_CENTER - WORKSPACE_HALF, WORKSPACE_CENTER + WORKSPACE_HALF
    nodes = [p for p in ring_points([grown(r, clearance) for r in rects], DETOUR_MARGIN, True)
             if np.all(p >= lo) and np.all(p <= hi)]
    route = RouteMap(nodes, to_b, clear).route_from(a, to_b, clear)
    return route.via if route is not None else None


def _graspable(name: str, rope: list[str], poses: Mapping[str, Pose],
               obstacles: list[tuple[SceneObject, Pose]]) -> str | None:
    """``name``, or the nearest segment along the chain that the cup can grasp
    without meeting an obstacle (at most :data:`GRASP_REACH` away); None if none."""
    k = rope.index(name)
    for d in range(GRASP_REACH + 1):
        for j in ((k - d, k + d) if d else (k,)):
            if 0 <= j < len(rope) and gap_to(poses[rope[j]].pos[:2],
                                             footprints(obstacles)) >= GRASP_CLEARANCE:
                return rope[j]
    return None


def plan_rope_carry(fname: str, solved: SolvedFactor, status: FactorStatus,
                    objects: Mapping[str, SceneObject], poses: Mapping[str, Pose],
                    settled: Collection[str] = (), lift: float = ROPE_LIFT
                    ) -> CarryAction | None:
    """The next low carry for a ``rope_along`` factor, or None when no segment is
    left to place.

    Args:
        fname: The factor.
        solved: Its solved slots.
        status: Its status now (which segments are placed, on which slots).
        objects: Scene objects by instance name.
        poses: Current poses.
        settled: Segments no longer treated as folds (straightened often enough: their
            neighbours turn them back).
        lift: How high the segment is carried.
    """
    if not status.targets:
        return None
    slots = segment_slots(solved, status)
    first = objects[solved.objects[0]]
    run = np.array([solved.target_pose(first, k).pos[:2] for k in range(len(solved.objects))])
    aims = aim_points(run, first.size[0])
    want = {name: heading(solved, objects, name, s) for name, s in slots.items()}
    dist = {name: float(np.linalg.norm(poses[name].pos[:2] - aims[s]))
            for name, s in slots.items()}
    bend = {name: abs(math.degrees(wrap_angle(poses[name].yaw - want[name])))
            for name in slots if name not in settled}
    # The end whose slot is farther from the rope goes first (see the module doc).
    centre = np.mean([poses[n].pos[:2] for n in solved.objects], axis=0)
    n = len(solved.objects)
    far_first = (n - 1 if np.linalg.norm(aims[-1] - centre) > np.linalg.norm(aims[0] - centre)
                 else 0)
    name = rope_slot_order(status.targets, n, dist, bend=bend,
                           kink_deg=KINK_DEG, near=FOLD_NEAR, first_end=far_first)
    obstacles = solid_obstacles(objects, poses, solved.objects, first.size[2])
    moved = _graspable(name, list(solved.objects), poses, obstacles) or name
    purpose = f"place {name}" if moved == name else f"place {name} by {moved}"
    obj, now = objects[moved], poses[moved]
    target = solved.target_pose(obj, slots[moved])
    pick = np.array([now.pos[0], now.pos[1], top_z(obj, now), now.yaw])
    aim = aims[slots[moved]]
    yaw = want[moved]
    via = detour(now.pos[:2], aim, obstacles)
    if via is not None:
        # Beside the obstacle first, turned part way (the next move goes on from there).
        aim, yaw = via, now.yaw + wrap_angle(yaw - now.yaw) / 2
        purpose += " (round an obstacle)"
    place = np.array([aim[0], aim[1], target.pos[2] + obj.half[2], yaw])
    return CarryAction(pick, place, lift, moved, fname, purpose)


__all__ = ["CLEARANCE", "FOLD_NEAR", "GRASP_CLEARANCE", "KINK_DEG", "MAX_FOLD_FIXES",
           "aim_points", "detour", "footprints", "heading", "path_clear", "plan_rope_carry",
           "segment_slots", "solid_obstacles"]
