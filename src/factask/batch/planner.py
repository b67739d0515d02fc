"""The oracle's next action in every world at once: planning as array work.

The single env's scripted oracle (:class:`factask.sim.oracle.scripted.Oracle`) plans
one world in Python. :class:`LockstepPlanner` plans every world of a batch with NumPy
over the world axis, for the case that makes up nearly every action: take the first
goal not yet met, give each object still to place its free slot by one optimal
assignment (:func:`factask.batch.assignment.assign_min_cost`), choose the object whose
target is lowest (farthest first on ties), check that nothing rests on it, stands
where it goes or lies under its target that a later goal moves, and turn the move
into the tool's pick and place (x, y, z, yaw). Each step is the scalar oracle's own
rule, written over worlds.

A world whose next step is anything else falls back to the scalar oracle, alone,
and the plan says so (:attr:`LockstepPlan.fallback`, and why in
:attr:`LockstepPlanner.fallback_reasons`): moving an obstacle out of the way (a
parking spot drawn at random), a goal done by pushes or rope carries, an object
lying tilted, a retry past the attempt
budget, no free slot, more objects than free slots. The fallback reads the same
status and keeps the same attempt counts (the arrays here are the one record; they
are copied into the world's scalar oracle before it plans and back after), so a
world's actions are the scalar oracle's whichever way each was planned.
``tests/test_batch_planner.py`` holds the plans to the scalar oracle's on random
states and along every library task's episodes.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, cast

import numpy as np

from factask.batch.assignment import assign_min_cost
from factask.batch.checks import area_contains, placement_areas, rest_surfaces
from factask.batch.geometry import (
    box_z_range,
    footprint_rects,
    rects_overlap,
    rotate_2d,
    tilts_deg,
    yaws,
)
from factask.batch.grasp import rim_offsets
from factask.batch.scene import BatchScene
from factask.batch.status import BatchTaskStatus
from factask.batch.targets import BatchTargets
from factask.geometry import Pose
from factask.graph.taskgraph import TaskGraph
from factask.relations.solving import SolvedFactor
from factask.relations.status import MAX_TILT_DEG
from factask.scene.collision import REST_EPS
from factask.scene.objects import SPHERE_KINDS, SceneObject, footprint_radius
from factask.sim.layout.checks import TaskStatus, check_task
from factask.sim.oracle.pick_points import takes_by_rim
from factask.sim.oracle.scripted import MAX_ATTEMPTS_PER_OBJECT, Oracle, OracleAction
from factask.vocabulary.kinds import yaw_symmetry_deg

if TYPE_CHECKING:
    from factask.sim.env import FactaskEnv

#: Relation kinds whose oracle actions (pushes, low carries, a drawer's slide, a
#: switch's press) the lockstep primitive does not run yet: their worlds go to the
#: scalar oracle, which asks for one and stops.
NOT_BATCHED = frozenset({"pile_in_zone", "rope_along", "open", "closed", "switched_on",
                         "switched_off"})
#: Assignment cost of a slot an object may not take (the scalar status's).
_FORBIDDEN = 1e6
#: Margin (m) the scalar occupancy checks shrink the moved object's footprint by.
_SHRINK = -0.002
#: A target height this close (in mm) to a half millimetre is rounded by Python
#: (Python's ``round`` and NumPy's may part there).
_ROUND_GUARD = 1e-6


class WorldView:
    """One world, read as the oracle reads a :class:`~factask.sim.env.FactaskEnv`
    (the scalar oracle's :class:`~factask.sim.oracle.scripted.OracleView`).

    Args:
        graph: The task.
        objects: Scene objects by instance name.
        solved: The world's solved factors (its own layout's targets).
    """

    def __init__(self, graph: TaskGraph, objects: Mapping[str, SceneObject],
                 solved: Mapping[str, SolvedFactor]) -> None:
        self.graph, self.objects, self._solved = graph, objects, solved
        self._poses: dict[str, Pose] = {}
        self._held: set[str] = set()
        self._reached: set[str] = set()

    @property
    def solved(self) -> Mapping[str, SolvedFactor]:
        """The world's solved factors."""
        return self._solved

    def refresh(self, names: Sequence[str], pos: np.ndarray, quat: np.ndarray,
                held: set[str], reached: set[str]) -> None:
        """Take this world's poses ((n, 3), (n, 4)), held objects and reached factors."""
        self._poses = {n: Pose(p, q) for n, p, q in zip(names, pos, quat, strict=True)}
        self._held, self._reached = set(held), set(reached)

    def object_poses(self) -> dict[str, Pose]:
        """Every object's pose (as of the last refresh)."""
        return dict(self._poses)

    def held_objects(self) -> set[str]:
        """What the cup holds (as of the last refresh)."""
        return set(self._held)

    def status(self) -> TaskStatus:
        """The scalar status (milestones reached so far kept latched)."""
        return check_task(self.graph, self._solved, self._poses, self._held, self.objects,
                          self._reached)


@dataclass(frozen=True)
class LockstepPlan:
    """The next action of every world.

    Attributes:
        pick: (W, 4) the tool's pick (x, y, z, yaw) where ``act``.
        place: (W, 4) its place where ``act``.
        act: Worlds with a pick-and-place to run (W,).
        stop: Worlds that stop: done, or the oracle gave up or asked for an action
            the batch does not run (W,).
        failure: Why each stopping world stopped short (None where done or acting).
        fallback: Worlds planned by the scalar oracle this time (W,).
        objects: The object each acting world moves ("" elsewhere).
    """

    pick: np.ndarray
    place: np.ndarray
    act: np.ndarray
    stop: np.ndarray
    failure: list[str | None]
    fallback: np.ndarray
    objects: list[str]


@dataclass(frozen=True)
class _Factor:
    """What the planner reads of one factor, fixed for the batch's resets."""

    name: str
    column: int  # in the status's factor columns
    rank: int  # in the oracle's order
    milestone: bool
    arrays: bool  # planned here (else: pushes, rope carries go to the scalar oracle)
    targets: BatchTargets
    cols: np.ndarray  # the factor's objects' columns in the scene
    meant: np.ndarray  # (W, N) what the factor's slots rest on, per world


class LockstepPlanner:
    """Plans the oracle's next action in every world of a batch (see the module).

    Args:
        graph: The task.
        objects: Scene objects by instance name.
        names: Instance names in the scene's column order.
        solved: Per world, its solved factors (every factor).
        seeds: Per world, the seed of its scalar oracle's own choices (the reset seed,
            as :func:`factask.sim.episode.run_episode` seeds its oracle).
    """

    def __init__(self, graph: TaskGraph, objects: Mapping[str, SceneObject],
                 names: Sequence[str], solved: Sequence[Mapping[str, SolvedFactor]],
                 seeds: Sequence[int]) -> None:
        self.graph, self.objects, self.names = graph, objects, tuple(names)
        self.num_worlds = len(solved)
        index = {n: k for k, n in enumerate(self.names)}
        columns = {n: k for k, n in enumerate(graph.factor_names())}
        order = graph.factor_order()
        self._factors: list[_Factor] = []
        for rank, fname in enumerate(order):
            factor = graph.factor(fname)
            per_world = [s[fname] for s in solved]
            meant = np.zeros((self.num_worlds, len(self.names)), dtype=bool)
            for w, s in enumerate(per_world):
                for inst in {*s.supports, *s.support_group}:
                    if inst in index:
                        meant[w, index[inst]] = True
            arrays = factor.goal.kind() not in NOT_BATCHED
            self._factors.append(_Factor(
                fname, columns[fname], rank, bool(factor.milestone), arrays,
                BatchTargets.stack(per_world),
                np.array([index[o] for o in per_world[0].objects], dtype=int), meant))
        objs = [objects[n] for n in self.names]
        self._objs = objs
        self._half = np.array([o.half for o in objs], dtype=float)  # (N, 3)
        self._half_xy = np.array([o.half_xy for o in objs], dtype=float)
        self._sphere = np.array([o.kind in SPHERE_KINDS for o in objs])
        self._round = np.array([bool(o.is_round) for o in objs])
        self._radius = np.array([footprint_radius(o) for o in objs])
        self._obstacle = np.array([not o.fixed and bool(o.collides) for o in objs])
        self._rim = np.array([takes_by_rim(o) for o in objs])
        self._receptacle = np.array([bool(o.spec.receptacle) for o in objs])
        self._symmetry = np.array([o.symmetry_deg or yaw_symmetry_deg(o.kind, o.size)
                                   for o in objs], dtype=float)
        #: Attempts per world, factor (oracle order) and object: the one record.
        self.attempts = np.zeros((self.num_worlds, len(order), len(self.names)), dtype=int)
        self._solved = list(solved)
        self._seeds = [int(s) for s in seeds]
        # Each world's scalar oracle, made at its first fallback (seeded then: it draws
        # nothing before).
        self._oracles: dict[int, tuple[Oracle, WorldView]] = {}
        #: Actions planned here and by the scalar oracle so far.
        self.planned_arrays = 0
        self.planned_fallback = 0
        #: Why worlds went to the scalar oracle, counted.
        self.fallback_reasons: Counter[str] = Counter()

    # ---------------------------------------------------------------- plan
    def plan(self, scene: BatchScene, status: BatchTaskStatus,
             worlds: np.ndarray | None = None) -> LockstepPlan:
        """The next action of each chosen world.

        Args:
            scene: Every world's poses and held objects now.
            status: The batched status of that scene (milestones latched).
            worlds: Worlds to plan (W,) bool (default all).

        Returns:
            The :class:`LockstepPlan`.
        """
        w = self.num_worlds
        chosen = np.ones(w, dtype=bool) if worlds is None else np.asarray(worlds, dtype=bool)
        pick, place = np.zeros((w, 4)), np.zeros((w, 4))
        act = np.zeros(w, dtype=bool)
        fallback = np.zeros(w, dtype=bool)
        stop = chosen & status.success
        moved = [""] * w
        todo = chosen & ~status.success
        # Worlds whose poses are not finite: the scalar oracle's check says why.
        fallback |= todo & ~scene.finite()
        self.fallback_reasons["poses not finite"] += int((todo & ~scene.finite()).sum())
        todo &= ~fallback
        factor = self._next_factor(status, todo)
        fallback |= todo & (factor < 0)
        self.fallback_reasons["no open goal"] += int((todo & (factor < 0)).sum())
        for k, f in enumerate(self._factors):
            here = todo & (factor == k)
            if not here.any():
                continue
            if not f.arrays:
                fallback |= here
                self.fallback_reasons["a push or a rope carry"] += int(here.sum())
                continue
            sel = np.flatnonzero(here)
            ok, obj, pk, pl = self._plan_factor(k, f, sel, scene, status)
            fallback[sel[~ok]] = True
            good = sel[ok]
            act[good], pick[good], place[good] = True, pk[ok], pl[ok]
            for g, i in zip(good, obj[ok], strict=True):
                moved[g] = self.names[i]
        failure: list[str | None] = [None] * w
        self.planned_arrays += int(act.sum())
        for k in np.flatnonzero(fallback):
            planned = self._scalar_plan(int(k), scene, status)
            if isinstance(planned, OracleAction):
                pick[k], place[k], act[k], moved[k] = planned.pick, planned.place, True, planned.obj
                self.planned_fallback += 1
            else:
                stop[k] = True
                failure[k] = (self._oracles[k][0].failure or "the oracle stopped"
                              if planned is None else
                              f"{type(planned).__name__} is not batched yet")
        return LockstepPlan(pick, place, act, stop, failure, fallback, moved)

    def _next_factor(self, status: BatchTaskStatus, todo: np.ndarray) -> np.ndarray:
        """The factor (index in oracle order) each world works on next, -1 where none:
        the first not satisfied, skipping one reached earlier while a milestone after
        it is still pending (the scalar oracle's rule)."""
        w = self.num_worlds
        factor = np.full(w, -1)
        pending_after = np.zeros(w, dtype=bool)  # a pending milestone later in the order
        skip = np.zeros((w, len(self._factors)), dtype=bool)
        for k in range(len(self._factors) - 1, -1, -1):
            f = self._factors[k]
            reached = status.reached[:, f.column]
            skip[:, k] = reached & pending_after
            if f.milestone:
                pending_after |= ~reached
        for k in range(len(self._factors) - 1, -1, -1):
            f = self._factors[k]
            open_ = todo & ~status.satisfied[:, f.column] & ~skip[:, k]
            factor[open_] = k
        return factor

    def _plan_factor(self, k: int, f: _Factor, sel: np.ndarray, scene: BatchScene,
                     status: BatchTaskStatus
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Plan factor ``f`` in worlds ``sel``. Returns which of them were planned here,
        the object column each moves, and pick / place (len(sel), 4)."""
        s = len(sel)
        t = f.targets.select(sel)
        live = status.factors[f.name]
        placed = live.placed[sel]
        n, m = placed.shape[1], t.slot_pos.shape[1]
        slot = np.full((s, n), -1) if live.slot is None else live.slot[sel]
        pos, quat = scene.pos[sel][:, f.cols], scene.quat[sel][:, f.cols]  # (s, n, .)
        target = t.target_pos(self.objects)  # (s, n, m, 3)
        dist = np.linalg.norm(pos[:, :, None, :] - target, axis=-1)  # (s, n, m)
        rows = np.arange(s)
        taken = np.zeros((s, m), dtype=bool)
        has = slot >= 0
        taken[np.nonzero(has)[0], slot[has]] = True
        for i in range(n):  # placed without a slot: the nearest allowed free one, in order
            who = placed[:, i] & (slot[:, i] < 0)
            allowed = t.matches[:, i, :] & ~taken
            who &= allowed.any(axis=1)
            j = np.where(allowed, dist[:, i], np.inf).argmin(axis=1)
            taken[rows[who], j[who]] = True
        todo, free = ~placed, ~taken
        cost = np.where(t.matches, dist, _FORBIDDEN)
        fits = todo.sum(axis=1) <= free.sum(axis=1)  # SciPy would transpose otherwise
        col = assign_min_cost(cost, todo & fits[:, None], free & fits[:, None])
        colc = np.maximum(col, 0)
        target_of = target[rows[:, None], np.arange(n)[None, :], colc]  # (s, n, 3)
        with_target = todo & (col >= 0) & np.take_along_axis(t.matches, colc[..., None],
                                                             axis=2)[..., 0]
        why = np.full(s, "", dtype=object)

        def need(cond: np.ndarray, reason: str) -> None:
            why[(why == "") & ~cond] = reason

        need(fits, "more objects to place than free slots")
        need(with_target.any(axis=1), "no free slot")
        # Lowest target (to the mm) first, farthest first on ties, first in order.
        level = np.where(with_target, round_mm(target_of[..., 2]), np.inf)
        lowest = level == level.min(axis=1, keepdims=True)
        far = np.where(lowest & with_target,
                       -np.linalg.norm(pos - target_of, axis=-1), np.inf)
        i_star = far.argmin(axis=1)
        obj = f.cols[i_star]  # scene column of the chosen object
        cur_pos, cur_quat = pos[rows, i_star], quat[rows, i_star]
        j_star = colc[rows, i_star]
        goal_pos = target_of[rows, i_star]
        goal_yaw = yaws(t.slot_quat[rows, j_star])
        need(self._sphere[obj] | (tilts_deg(cur_quat) <= MAX_TILT_DEG), "the object lies tilted")
        spos, squat = scene.pos[sel], scene.quat[sel]  # (s, N, .)
        bottoms, tops = self._z_ranges(spos, squat)
        for reason, hit in self._obstacles(k, f, sel, obj, goal_pos, goal_yaw, placed, scene,
                                           status, bottoms, tops).items():
            need(~hit, reason)
        need(self.attempts[sel, k, obj] + 1 <= MAX_ATTEMPTS_PER_OBJECT, "attempts used up")
        ok = why == ""
        for reason in why[~ok]:
            self.fallback_reasons[str(reason)] += 1
        # Planned here: a placed object's retry budget starts again; one more attempt.
        good = sel[ok]
        cleared = self.attempts[good, k][:, f.cols]
        self.attempts[good[:, None], k, f.cols[None, :]] = np.where(placed[ok], 0, cleared)
        self.attempts[good, k, obj[ok]] += 1
        pick_yaw = yaws(cur_quat)
        place_yaw = yaw_toward(goal_yaw, pick_yaw, self._symmetry[obj])
        # At the top centre, or a receptacle on its rim (the offset turned with the
        # tool: the object ends centred on its target whatever point held it).
        offset = np.zeros((s, 2))
        for c in np.unique(obj[self._rim[obj]]):
            which = obj == c
            offset[which] = rim_offsets(int(c), self._objs, spos[which], squat[which],
                                        tops[which])
        turned = rotate_2d(offset, place_yaw - pick_yaw)
        pick = np.column_stack([cur_pos[:, :2] + offset, tops[rows, obj], pick_yaw])
        place = np.column_stack([goal_pos[:, :2] + turned,
                                 goal_pos[:, 2] + self._half[obj, 2], place_yaw])
        return ok, obj, pick, place

    def _obstacles(self, k: int, f: _Factor, sel: np.ndarray, obj: np.ndarray,
                   goal_pos: np.ndarray, goal_yaw: np.ndarray, placed: np.ndarray,
                   scene: BatchScene, status: BatchTaskStatus, bottoms: np.ndarray,
                   tops: np.ndarray) -> dict[str, np.ndarray]:
        """Worlds (len(sel),) where something rests on the chosen object, occupies its
        target, or lies under its target and a later goal moves it (the scalar
        oracle's ``resting_on``, ``occupying`` and ``beneath``), by reason."""
        s = len(sel)
        rows = np.arange(s)
        pos, quat = scene.pos[sel], scene.quat[sel]  # (s, N, .)
        others = self._obstacle[None, :] & (np.arange(len(self.names))[None, :] != obj[:, None])
        here = footprint_rects(self._half_xy[None], pos[..., :2], yaws(quat))  # (s, N, 4, 2)
        on_top = others & (np.abs(bottoms - tops[rows, obj][:, None]) < REST_EPS)
        on_top = _overlapping(on_top, here[rows, obj], here)
        # A free receptacle also carries what lies in its hollow: that comes out first.
        for c in np.unique(obj[self._rim[obj]]):
            which = obj == c
            o = self._objs[c]
            floor = rest_surfaces(o, pos[which, c])
            held_in = area_contains(placement_areas(o, pos[which, c], quat[which, c]),
                                    pos[which][..., :2])
            b = bottoms[which]
            on_top[which] |= (others[which] & held_in & (floor[:, None] - REST_EPS < b)
                              & (b < tops[which, c][:, None]))
        # Where it goes: footprint shrunk by 2 mm, its bottom and top there.
        lo = goal_pos[:, 2] - self._half[obj, 2]
        hi = goal_pos[:, 2] + self._half[obj, 2]
        mine_goal = footprint_rects(self._half_xy[obj] + _SHRINK, goal_pos[:, :2], goal_yaw)
        kept = np.zeros((s, len(self.names)), dtype=bool)
        kept[:, f.cols] = placed
        z_over = (bottoms < hi[:, None] - REST_EPS) & (tops > lo[:, None] + REST_EPS)
        disks = self._round[obj][:, None] & self._round[None, :]
        gap = np.linalg.norm(goal_pos[:, None, :2] - pos[..., :2], axis=-1)
        near = gap < self._radius[obj][:, None] + self._radius[None, :] + _SHRINK
        occupy = others & ~kept & z_over
        occupy = np.where(disks, occupy & near, _overlapping(occupy & ~disks, mine_goal, here))
        occupy &= ~self._holds(pos, quat, mine_goal, lo)
        later = self._moved_later(k, sel, placed, status) & ~f.meant[sel]
        under = _overlapping(others & later & (tops <= lo[:, None] + REST_EPS), mine_goal, here)
        return {"something rests on the object": on_top.any(axis=1),
                "something stands at the target": occupy.any(axis=1),
                "a later goal's object under the target": under.any(axis=1)}

    def _z_ranges(self, pos: np.ndarray, quat: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Lowest and highest points (s, N) of every object's box (objects in scene order)."""
        ranges = [box_z_range(o, pos[:, c], quat[:, c]) for c, o in enumerate(self._objs)]
        return np.stack([r[0] for r in ranges], axis=1), np.stack([r[1] for r in ranges], axis=1)

    def _holds(self, pos: np.ndarray, quat: np.ndarray, corners: np.ndarray,
               lo: np.ndarray) -> np.ndarray:
        """(s, N): free receptacles whose hollow takes the moved object's footprint at
        its target (inside the walls, above the floor): where it goes, not in the way."""
        s, nn = pos.shape[:2]
        out = np.zeros((s, nn), dtype=bool)
        for c in np.flatnonzero(self._receptacle):
            o = self.objects[self.names[c]]
            inside = area_contains(placement_areas(o, pos[:, c], quat[:, c]), corners)
            out[:, c] = inside.all(axis=1) & (lo >= rest_surfaces(o, pos[:, c]) - REST_EPS)
        return out

    def _moved_later(self, k: int, sel: np.ndarray, placed: np.ndarray,
                     status: BatchTaskStatus) -> np.ndarray:
        """(s, N): objects a goal other than factor ``k``, not satisfied, has still to
        place."""
        out = np.zeros((len(sel), len(self.names)), dtype=bool)
        for j, g in enumerate(self._factors):
            if j == k:
                continue
            open_ = ~status.satisfied[sel, g.column]
            unplaced = ~status.factors[g.name].placed[sel]
            out[:, g.cols] |= open_[:, None] & unplaced
        return out

    # ------------------------------------------------------------ fallback
    def _scalar_plan(self, k: int, scene: BatchScene, status: BatchTaskStatus) -> object:
        """World ``k``'s next action by its scalar oracle, the attempt counts shared."""
        if k not in self._oracles:
            view = WorldView(self.graph, self.objects, self._solved[k])
            self._oracles[k] = (Oracle(cast("FactaskEnv", view), seed=self._seeds[k]), view)
        oracle, view = self._oracles[k]
        held = {n for n, h in zip(self.names, scene.held[k], strict=True) if h}
        reached = {n for n, r in zip(status.factor_names, status.reached[k], strict=True) if r}
        view.refresh(self.names, scene.pos[k], scene.quat[k], held, reached)
        counts = oracle.attempts
        for key in [key for key in counts if key[1] in self.names]:
            del counts[key]
        for fk, c in zip(*np.nonzero(self.attempts[k]), strict=True):
            counts[(self._factors[fk].name, self.names[c])] = int(self.attempts[k, fk, c])
        planned = oracle.plan()
        self.attempts[k] = 0
        rank = {f.name: j for j, f in enumerate(self._factors)}
        column = {n: c for c, n in enumerate(self.names)}
        for (fname, name), count in counts.items():
            if name in column and fname in rank:
                self.attempts[k, rank[fname], column[name]] = count
        return planned


def _overlapping(pairs: np.ndarray, mine: np.ndarray, theirs: np.ndarray) -> np.ndarray:
    """(s, N): where ``pairs`` holds, whether the world's rectangle ``mine`` (s, 4, 2)
    overlaps object k's ``theirs`` (s, N, 4, 2); False elsewhere (only those pairs are
    tested: nearly always a few)."""
    out = np.zeros(pairs.shape, dtype=bool)
    w, k = np.nonzero(pairs)
    if len(w):
        out[w, k] = rects_overlap(mine[w], theirs[w, k])
    return out


def round_mm(z: np.ndarray) -> np.ndarray:
    """Heights rounded to the millimetre exactly as Python's ``round(z, 3)`` rounds
    them (the scalar oracle's key): NumPy's scaled rounding agrees except next to a
    half millimetre, where those few are rounded by Python."""
    out = np.round(z, 3)
    mm = z * 1000.0
    edge = np.flatnonzero(np.abs(mm - np.floor(mm) - 0.5) < _ROUND_GUARD)
    flat = out.reshape(-1)
    for e in edge:
        flat[e] = round(float(z.reshape(-1)[e]), 3)
    return flat.reshape(z.shape)


def yaw_toward(target: np.ndarray, current: np.ndarray, symmetry_deg: np.ndarray) -> np.ndarray:
    """The yaw equivalent to ``target`` (modulo each symmetry) closest to ``current``,
    elementwise (the scalar oracle's rule; symmetry 0 keeps ``current``)."""
    period = np.radians(np.where(symmetry_deg > 0, symmetry_deg, 1.0))
    turned = target + np.rint((current - target) / period) * period
    return np.where(symmetry_deg > 0, np.arctan2(np.sin(turned), np.cos(turned)), current)


__all__ = ["NOT_BATCHED", "LockstepPlan", "LockstepPlanner", "WorldView", "round_mm", "yaw_toward"]
