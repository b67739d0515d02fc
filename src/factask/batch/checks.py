"""Vectorised factor checks: every relation's status in every world at once (NumPy).

One function per relation kind, registered in :data:`BATCH_CHECKS` under the
relation's ``type`` — the batched twin of each unit's scalar ``check``/``status``
in :mod:`factask.relations` (they should move next to the scalar checks, into the
relation units, once those files are free to edit; then each unit owns both).
A batched check gives, per world, the numbers the scalar one gives on the same
state: progress, satisfied and which objects are placed
(``tests/test_batch_checks.py`` compares them on random states for every kind).
It does not write the words (``detail``) nor the next free slot of each object:
those stay with the scalar status, for the one world a person looks at.

Slot relations match objects to slots one per slot, as the scalar check does with
``linear_sum_assignment``; a world where each object fits at most one slot and
each slot at most one object (nearly always) needs no solver, the others run the
same solver call as the scalar check, one world at a time.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from factask.batch.geometry import (
    box_z_range,
    footprint_points_batch,
    in_disk,
    in_rect,
    rotate_2d,
    rotation_matrices,
    to_local_2d,
    upright_tilts_deg,
    yaw_errors_deg,
    yaws,
)
from factask.batch.scene import BatchScene
from factask.batch.targets import BatchTargets
from factask.relations.base import RelationBase
from factask.relations.drawer import DOOR_KIND, ArticulatedRelation
from factask.relations.pile_in_zone import PileInZone, block_side
from factask.relations.region import RegionRelation
from factask.relations.rope import RopeAlong, segment_scores
from factask.relations.status import MAX_TILT_DEG
from factask.relations.switch import SwitchRelation
from factask.scene.objects import (
    GEOMETRY_EPS,
    SceneObject,
    floor_thickness,
    inner_half_xy,
)
from factask.vocabulary.errors import InvalidValueError
from factask.vocabulary.kinds import (
    DOOR_RANGE,
    drawer_closed_offset,
    drawer_travel,
    switch_off_offset,
    switch_travel,
)
from factask.vocabulary.world import TABLE_Z


@dataclass(frozen=True)
class BatchFactorStatus:
    """One factor's status in every world.

    Attributes:
        progress: Progress in [0, 1] per world (W,).
        satisfied: Every object placed (or, for piles, the share reached) (W,).
        placed: Which of the factor's objects are placed (W, n), in relation order.
        slot: The slot each placed object occupies (W, n), -1 elsewhere; None for the
            relations whose check matches no slots (regions, ``on``, piles).
    """

    progress: np.ndarray
    satisfied: np.ndarray
    placed: np.ndarray
    slot: np.ndarray | None = None


#: A batched check: (goal, the factor's stacked targets, the scene) -> status.
BatchCheck = Callable[[RelationBase, BatchTargets, BatchScene], BatchFactorStatus]


def _from_placed(placed: np.ndarray, slot: np.ndarray | None = None) -> BatchFactorStatus:
    n = placed.shape[1]
    count = placed.sum(axis=1)
    progress = count / n if n else np.ones(placed.shape[0])
    return BatchFactorStatus(progress.astype(float), count == n, placed, slot)


# ------------------------------------------------------------------ slots
def slot_fits(goal: RelationBase, t: BatchTargets, scene: BatchScene) -> np.ndarray:
    """Which object fits which allowed slot (W, n, m): within ``xy`` in XY, within
    ``z`` of its height there, upright, within ``yaw_deg`` modulo its symmetry (see
    :func:`~factask.relations.status.slot_error`); held objects fit nowhere."""
    tol = goal.tolerances
    cols = scene.columns(t.objects)
    pos, quat = scene.pos[:, cols], scene.quat[:, cols]  # (W, n, 3), (W, n, 4)
    target = t.target_pos(scene.objects)  # (W, n, m, 3)
    dxy = np.linalg.norm(pos[:, :, None, :2] - target[..., :2], axis=-1)
    dz = pos[:, :, None, 2] - target[..., 2]
    ok = t.matches & ~scene.held[:, cols][:, :, None]
    ok &= (dxy <= tol.xy) & (np.abs(dz) <= tol.z)
    objs = [scene.objects[o] for o in t.objects]
    tilt = np.stack([upright_tilts_deg(o, quat[:, i]) for i, o in enumerate(objs)], axis=1)
    ok &= (tilt <= MAX_TILT_DEG)[:, :, None]
    if t.check_yaw:
        obj_yaw = yaws(quat)  # (W, n)
        slot_yaw = yaws(t.slot_quat)  # (W, m)
        dyaw = np.stack([yaw_errors_deg(obj_yaw[:, i, None], slot_yaw, o.symmetry_deg)
                         for i, o in enumerate(objs)], axis=1)
        ok &= dyaw <= tol.yaw_deg
    return ok


def assign_slots(ok: np.ndarray, chain: bool) -> np.ndarray:
    """The slot each object is placed in (W, n), -1 where none: one object per slot,
    as many as can be (the scalar check's ``linear_sum_assignment``), in a chain only
    from the bottom slot up without gaps."""
    w, n, m = ok.shape
    slot = np.full((w, n), -1, dtype=int)
    simple = (ok.sum(axis=2) <= 1).all(axis=1) & (ok.sum(axis=1) <= 1).all(axis=1)
    has = ok.any(axis=2)
    first = ok.argmax(axis=2)
    slot[simple] = np.where(has[simple], first[simple], -1)
    for k in np.flatnonzero(~simple):
        rows, cols = linear_sum_assignment(-ok[k].astype(float))
        for r, c in zip(rows, cols, strict=True):
            if ok[k, r, c]:
                slot[k, r] = c
    if chain:
        filled = np.zeros((w, m), dtype=bool)
        wi, oi = np.nonzero(slot >= 0)
        filled[wi, slot[wi, oi]] = True
        upto = np.cumprod(filled, axis=1).sum(axis=1)  # slots 0 .. upto-1 filled
        slot = np.where(slot < upto[:, None], slot, -1)
    return slot


def check_slots_batch(goal: RelationBase, t: BatchTargets, scene: BatchScene
                      ) -> BatchFactorStatus:
    """Slot relations (``at_pose``, ``stack``, ``row``, ``circle``, ``aligned``)."""
    slot = assign_slots(slot_fits(goal, t, scene), t.chain)
    return _from_placed(slot >= 0, slot)


# ------------------------------------------------------------------ areas
def placement_areas(obj: SceneObject, pos: np.ndarray, quat: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:
    """The area things go into (see :func:`~factask.scene.objects.placement_area`),
    per world: centre (W, 2), yaw (W,), half extents (W, 2), round."""
    w = pos.shape[0]
    centre, yaw = pos[:, :2], yaws(quat)
    if obj.is_receptacle:
        half = inner_half_xy(obj)
        if obj.is_round:
            return centre, yaw, np.full((w, 2), float(half.min())), True
        return centre, yaw, np.broadcast_to(half, (w, 2)), False
    return centre, yaw, np.broadcast_to(obj.half_xy, (w, 2)), False


def area_contains(area: tuple[np.ndarray, np.ndarray, np.ndarray, bool],
              points: np.ndarray) -> np.ndarray:
    centre, yaw, half, rnd = area
    if rnd:
        return in_disk(points, centre, half[:, 0])
    return in_rect(points, centre, yaw, half)


def rest_surfaces(obj: SceneObject, pos: np.ndarray) -> np.ndarray:
    """Height (W,) things put on / in ``obj`` rest at (see
    :func:`~factask.scene.objects.rest_surface_z`)."""
    if not obj.collides:
        return np.full(pos.shape[0], TABLE_Z, dtype=float)
    if obj.is_receptacle:
        return pos[:, 2] - obj.half[2] + floor_thickness(obj)
    return pos[:, 2] + obj.half[2]


def check_region_batch(goal: RelationBase, t: BatchTargets, scene: BatchScene
                       ) -> BatchFactorStatus:
    """``in_zone`` and ``inside``: enough of the footprint in a region's area (and,
    for ``inside``, the bottom between the receptacle's floor and rim)."""
    assert isinstance(goal, RegionRelation)
    tol = goal.tolerances
    regions = []
    for r in t.regions:
        c = scene.columns([r])[0]
        robj, rpos, rquat = scene.objects[r], scene.pos[:, c], scene.quat[:, c]
        rim = box_z_range(robj, rpos, rquat)[1]
        floor = rpos[:, 2] - robj.half[2] + floor_thickness(robj)
        regions.append((placement_areas(robj, rpos, rquat), floor, rim))
    cols = scene.columns(t.objects)
    placed = np.zeros((scene.num_worlds, len(t.objects)), dtype=bool)
    for i, name in enumerate(t.objects):
        obj, pos, quat = scene.objects[name], scene.pos[:, cols[i]], scene.quat[:, cols[i]]
        pts = footprint_points_batch(obj, pos, quat)
        bottom = box_z_range(obj, pos, quat)[0]
        for area, floor, rim in regions:
            frac = area_contains(area, pts).mean(axis=-1)
            ok = frac + 1e-12 >= tol.region_fraction
            if goal.between_floor_and_rim:
                ok &= ~((bottom < floor - tol.z) | (bottom >= rim))
            placed[:, i] |= ok
    placed &= ~scene.held[:, cols]
    return _from_placed(placed)


def group_areas(objs: list[SceneObject], pos: np.ndarray, quat: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:
    """The rectangle covering a group of objects per world (see
    :func:`~factask.scene.objects.group_area`).

    Args:
        objs: The group (h objects).
        pos: Their positions (W, h, 3).
        quat: Their orientations (W, h, 4).
    """
    if len(objs) == 1:
        return placement_areas(objs[0], pos[:, 0], quat[:, 0])
    centres = pos[:, :, :2]
    mean = centres.mean(axis=1)  # (W, 2)
    _, _, vt = np.linalg.svd(centres - mean[:, None], full_matrices=False)
    d = vt[:, 0]  # (W, 2)
    flip = (d[:, 0] < -GEOMETRY_EPS) | ((np.abs(d[:, 0]) <= GEOMETRY_EPS) & (d[:, 1] < 0))
    d = np.where(flip[:, None], -d, d)
    yaw = np.arctan2(d[:, 1], d[:, 0])
    local_corners = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], dtype=float)
    corners = []
    for k, o in enumerate(objs):
        oyaw = yaws(quat[:, k])
        c = rotate_2d(local_corners[None] * o.half_xy, oyaw[:, None])  # (W, 4, 2)
        corners.append(c + centres[:, k, None, :])
    allc = np.concatenate(corners, axis=1)  # (W, 4h, 2)
    local = to_local_2d(allc - mean[:, None], yaw[:, None])
    lo, hi = local.min(axis=1), local.max(axis=1)
    centre = mean + rotate_2d((lo + hi) / 2.0, yaw)
    return centre, yaw, (hi - lo) / 2.0, False


def check_on_batch(goal: RelationBase, t: BatchTargets, scene: BatchScene) -> BatchFactorStatus:
    """``on``: centre over the support's top (or the group's), bottom within ``z`` of
    that top, upright; held objects never."""
    tol = goal.tolerances
    hcols = scene.columns(t.support_group)
    hobjs = [scene.objects[h] for h in t.support_group]
    area = group_areas(hobjs, scene.pos[:, hcols], scene.quat[:, hcols])
    surface = np.max(np.stack([rest_surfaces(o, scene.pos[:, c])
                               for o, c in zip(hobjs, hcols, strict=True)]), axis=0)
    cols = scene.columns(t.objects)
    placed = np.zeros((scene.num_worlds, len(t.objects)), dtype=bool)
    for i, name in enumerate(t.objects):
        obj, pos, quat = scene.objects[name], scene.pos[:, cols[i]], scene.quat[:, cols[i]]
        over = area_contains(area, pos[:, None, :2])[:, 0]
        bottom = box_z_range(obj, pos, quat)[0]
        placed[:, i] = (over & (np.abs(bottom - surface) <= tol.z)
                        & (upright_tilts_deg(obj, quat) <= MAX_TILT_DEG))
    placed &= ~scene.held[:, cols]
    return _from_placed(placed)


# ------------------------------------------------------------- piles, ropes
def blocks_inside(area: tuple[np.ndarray, np.ndarray, np.ndarray, bool], xy: np.ndarray,
                  side: float) -> np.ndarray:
    """Fraction (W, k) of each block's square inside the area, continuous (see
    :func:`~factask.relations.pile_in_zone.block_inside`)."""
    centre, yaw, half, rnd = area
    if rnd:
        d = np.linalg.norm(xy - centre[:, None], axis=-1)
        return np.clip((half[:, None, 0] + side / 2 + GEOMETRY_EPS - d) / side, 0.0, 1.0)
    local = np.abs(to_local_2d(xy - centre[:, None], yaw[:, None]))
    per_axis = np.clip((half[:, None, :] + side / 2 + GEOMETRY_EPS - local) / side, 0.0, 1.0)
    return per_axis.prod(axis=-1)


def check_pile_batch(goal: RelationBase, t: BatchTargets, scene: BatchScene
                     ) -> BatchFactorStatus:
    """``pile_in_zone``: the blocks' mean share inside over ``fraction`` (capped at 1);
    a block is placed when half its square or more is inside."""
    assert isinstance(goal, PileInZone)
    areas = [placement_areas(scene.objects[r], scene.pos[:, c], scene.quat[:, c])
             for r, c in zip(t.regions, scene.columns(t.regions), strict=True)]
    cols = scene.columns(t.objects)
    frac = np.zeros((scene.num_worlds, len(t.objects)))
    for i, name in enumerate(t.objects):
        xy = scene.pos[:, cols[i], None, :2]
        side = block_side(scene.objects[name])
        frac[:, i] = np.max(np.stack([blocks_inside(a, xy, side)[:, 0] for a in areas]), axis=0)
    frac[scene.held[:, cols]] = 0.0
    share = frac.mean(axis=1) if len(t.objects) else np.ones(scene.num_worlds)
    ok = share + 1e-12 >= goal.fraction
    progress = np.where(ok, 1.0, share / goal.fraction)
    return BatchFactorStatus(progress, ok, frac >= 0.5)


def check_rope_batch(goal: RelationBase, t: BatchTargets, scene: BatchScene
                     ) -> BatchFactorStatus:
    """``rope_along``: each segment scored by its distance to its slot in the better
    direction; satisfied when every segment is within ``xy``."""
    assert isinstance(goal, RopeAlong)
    tol = goal.tolerances.xy
    n = len(t.objects)
    cols = scene.columns(t.objects)
    xy = scene.pos[:, cols, :2]  # (W, n, 2)
    target = t.target_pos(scene.objects)  # (W, n, m, 3)
    idx = np.arange(n)
    fwd = target[:, idx, idx, :2]  # object k at slot k
    held = scene.held[:, cols]
    dist = np.linalg.norm(xy - fwd, axis=-1)
    back = np.linalg.norm(xy - fwd[:, ::-1], axis=-1)
    dist[held] = np.inf
    back[held] = np.inf

    def key(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return segment_scores(d, tol).sum(axis=1), -np.where(np.isfinite(d), d, 0.0).sum(axis=1)

    (sb, fb), (sd, fd) = key(back), key(dist)
    rev = (sb > sd) | ((sb == sd) & (fb > fd))
    best = np.where(rev[:, None], back, dist)
    placed = best <= tol
    ok = placed.all(axis=1)
    score = segment_scores(best, tol).mean(axis=1) if n else np.ones(scene.num_worlds)
    return BatchFactorStatus(np.where(ok, 1.0, score), ok, placed)


# ------------------------------------------------------------------ drawers
def drawer_openings(cabinet: SceneObject, cabinet_pos: np.ndarray, cabinet_quat: np.ndarray,
                    drawer: SceneObject, pos: np.ndarray) -> np.ndarray:
    """How far a drawer is pulled out in every world (W,), a fraction of its travel:
    the batched twin of :func:`factask.scene.cabinet.drawer_opening` (its slide along
    the cabinet's -x axis, 0 closed, not clipped)."""
    local_x = np.einsum("wi,wi->w", rotation_matrices(cabinet_quat)[:, :, 0],
                        pos - cabinet_pos)
    closed_x = drawer_closed_offset(cabinet.size, 1, 0)[0]  # the same for every bay
    return (closed_x - local_x) / drawer_travel(drawer.size)


def door_openings(microwave_quat: np.ndarray, quat: np.ndarray) -> np.ndarray:
    """How far a door has swung out in every world (W,), a fraction of its range: the
    batched twin of :func:`factask.scene.microwave.door_opening` (its yaw relative to
    its microwave's, wrapped to (-pi, pi], not clipped)."""
    turn = yaws(quat) - yaws(microwave_quat)
    return np.arctan2(np.sin(turn), np.cos(turn)) / DOOR_RANGE


def check_drawer_batch(goal: RelationBase, t: BatchTargets, scene: BatchScene
                       ) -> BatchFactorStatus:
    """``open`` / ``closed``: each drawer's (door's) opening against the relation's
    threshold (its own ``holds``, applied to the array); a held part never counts."""
    assert isinstance(goal, ArticulatedRelation)
    cols = scene.columns(t.objects)
    placed = np.zeros((scene.num_worlds, len(t.objects)), dtype=bool)
    for i, name in enumerate(t.objects):
        cabinet = t.supports[i]
        (c,) = scene.columns([cabinet])
        if scene.objects[name].kind == DOOR_KIND:
            opening = door_openings(scene.quat[:, c], scene.quat[:, cols[i]])
        else:
            opening = drawer_openings(scene.objects[cabinet], scene.pos[:, c],
                                      scene.quat[:, c], scene.objects[name],
                                      scene.pos[:, cols[i]])
        placed[:, i] = np.asarray(goal.holds(opening), dtype=bool)  # type: ignore[arg-type]
    placed &= ~scene.held[:, cols]
    return _from_placed(placed)


# ----------------------------------------------------------------- switches
def switch_presses(host: SceneObject, host_pos: np.ndarray, host_quat: np.ndarray,
                   pos: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """How far a switch is pressed down in every world (W,), a fraction of its travel,
    and how far it stands off its mount sideways (W,), metres: the batched twin of
    :func:`factask.scene.switch.switch_pressed` (its slide along the host's -z axis,
    0 off, not clipped).

    Args:
        host: The switchable fixture.
        host_pos: Its position in every world (W, 3).
        host_quat: Its orientation in every world (W, 4).
        pos: The switch's position in every world (W, 3).
    """
    local = np.einsum("wij,wi->wj", rotation_matrices(host_quat), pos - host_pos)
    off = switch_off_offset(host.kind, host.size)
    lateral = np.hypot(local[:, 0] - off[0], local[:, 1] - off[1])
    return (off[2] - local[:, 2]) / switch_travel(), lateral


def check_switch_batch(goal: RelationBase, t: BatchTargets, scene: BatchScene
                       ) -> BatchFactorStatus:
    """``switched_on`` / ``switched_off``: each switch on its mount, its press against
    the relation's threshold (its own ``holds``, applied to the array); a held switch
    never counts.

    Args:
        goal: A ``switched_on`` / ``switched_off`` goal.
        t: Its targets (``supports``: each switch's host).
        scene: Every world's poses.

    Returns:
        The factor's status in every world.
    """
    assert isinstance(goal, SwitchRelation)
    cols = scene.columns(t.objects)
    placed = np.zeros((scene.num_worlds, len(t.objects)), dtype=bool)
    for i in range(len(t.objects)):
        host = t.supports[i]
        (c,) = scene.columns([host])
        pressed, off_mount = switch_presses(scene.objects[host], scene.pos[:, c],
                                            scene.quat[:, c], scene.pos[:, cols[i]])
        placed[:, i] = np.asarray(goal.holds(pressed), dtype=bool) & (
            off_mount <= goal.tolerances.xy)
    placed &= ~scene.held[:, cols]
    return _from_placed(placed)


#: Relation kind -> its batched check.
BATCH_CHECKS: dict[str, BatchCheck] = {
    "at_pose": check_slots_batch,
    "stack": check_slots_batch,
    "row": check_slots_batch,
    "circle": check_slots_batch,
    "aligned": check_slots_batch,
    "in_zone": check_region_batch,
    "inside": check_region_batch,
    "on": check_on_batch,
    "pile_in_zone": check_pile_batch,
    "rope_along": check_rope_batch,
    "open": check_drawer_batch,
    "closed": check_drawer_batch,
    "switched_on": check_switch_batch,
    "switched_off": check_switch_batch,
}


def check_factor_batch(goal: RelationBase, targets: BatchTargets,
                       scene: BatchScene) -> BatchFactorStatus:
    """One factor's status in every world.

    Args:
        goal: The factor's relation.
        targets: Its solved targets in every world.
        scene: Every world's poses.

    Returns:
        Progress, satisfied and placed objects per world.

    Raises:
        InvalidValueError: no batched check for this relation kind, or the targets
            and the scene disagree on the number of worlds.
        CheckError: the scene lacks an instance the factor needs.
    """
    fn = BATCH_CHECKS.get(goal.kind())
    if fn is None:
        raise InvalidValueError(f"relation {goal.kind()!r} has no batched check; add one to "
                                "factask.batch.checks.BATCH_CHECKS")
    if targets.num_worlds != scene.num_worlds:
        raise InvalidValueError(f"targets of {targets.num_worlds} world(s) for a scene of "
                                f"{scene.num_worlds}")
    return fn(goal, targets, scene)


__all__ = [
    "BATCH_CHECKS",
    "BatchCheck",
    "BatchFactorStatus",
    "area_contains",
    "assign_slots",
    "check_drawer_batch",
    "check_factor_batch",
    "check_on_batch",
    "check_pile_batch",
    "check_region_batch",
    "check_rope_batch",
    "check_slots_batch",
    "check_switch_batch",
    "drawer_openings",
    "group_areas",
    "placement_areas",
    "rest_surfaces",
    "slot_fits",
    "switch_presses",
]
