"""Initial layouts and relation solving (pure numpy/scipy; never imports MuJoCo).

* :func:`sample_layout` gives every object instance an initial pose that honours
  its variable's ``initial`` placement, with footprints that never overlap (a
  separating-axis test on oriented boxes, :data:`CLEARANCE` apart) except where
  an object deliberately rests on or inside another.
* :func:`solve_targets` turns every factor's goal relation into concrete target
  slots (:class:`SolvedFactor`), in :meth:`TaskGraph.factor_order`, each slot
  collision-free, supported and inside the workspace; a factor anchored to a
  variable moved earlier uses that variable's *solved* pose.
* :func:`reset_layout` does both, resampling until the initial layout satisfies
  none of the goals.

Collision rule (the same for layout and targets): two objects collide when their
footprints (grown by half the clearance each) overlap in XY **and** their height
intervals overlap; an object whose footprint lies inside a receptacle's inner
area only meets the receptacle's floor. Flat markers (zones, lines, corners) have
a height interval too, so nothing starts on top of them.

Conventions (see docs/relations.md): a row runs along its yaw, first object at
the -x end; a stack's first object is at the bottom; the corner marker frame is
described in :mod:`factask.sim.objects`.

Every search is bounded (:data:`MAX_TRIES_PER_OBJECT`, :data:`MAX_LAYOUT_RESTARTS`,
:data:`MAX_SOLVE_ATTEMPTS`, :data:`MAX_RESETS`); failure raises
:class:`LayoutError` naming what could not be placed and why.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import linear_sum_assignment

from factask.geometry import Pose
from factask.model.errors import FactaskError
from factask.model.factors import SubtaskFactor
from factask.model.graph import TaskGraph
from factask.model.relations import Aligned, AtPose, Circle, Inside, InZone, On, Row, Stack
from factask.model.tolerances import Z_TOLERANCE
from factask.model.variables import AtFixedPose, InRegion, StartInside
from factask.model.world import TABLE_Z, WORKSPACE_X, WORKSPACE_Y, WORKSPACE_Z
from factask.sim.objects import (
    GEOMETRY_EPS,
    Area,
    SceneObject,
    bottom_z,
    corner_vertex,
    floor_thickness,
    footprint_corners,
    footprint_corners_batch,
    footprint_points,
    footprint_radius,
    group_area,
    obb_overlaps,
    objects_by_name,
    placement_area,
    principal_yaw,
    rest_surface_z,
    resting_pose,
    top_z,
    yaw_rotation_2d,
)

#: Gap kept between footprints (metres): objects never start or land touching.
CLEARANCE = 0.01
#: Extra gap in a row with no explicit spacing: widest object + this (metres).
ROW_GAP = 0.01
#: Extra chord (m) between neighbours on a ring, over the clearance.
RING_SLACK = 0.001
#: Distance (m) a packed grid keeps from the edge of its area when it can.
EDGE_MARGIN = 0.004
#: Candidate poses tried per object (or per column/row/circle) before giving up.
MAX_TRIES_PER_OBJECT = 200
#: Whole-layout restarts before :func:`sample_layout` gives up.
MAX_LAYOUT_RESTARTS = 8
#: Attempts (other random choices) per factor before :func:`solve_targets` gives up.
MAX_SOLVE_ATTEMPTS = 20
#: Initial layouts tried by :func:`reset_layout`.
MAX_RESETS = 10
#: Footprints (grown by the clearance) may cover at most this fraction of the
#: workspace: above it a random layout is hopeless and sampling fails at once.
MAX_FILL_FRACTION = 0.9
#: Height intervals overlapping by less than this (metres) do not collide (resting).
Z_CONTACT_EPS = 1e-4
#: Candidates tested together (vectorised) before looking at the next ones.
_CHUNK = 25
#: Support name used for slots resting directly on the table.
TABLE = "table"

_WORKSPACE_CENTER = np.array([(WORKSPACE_X[0] + WORKSPACE_X[1]) / 2,
                              (WORKSPACE_Y[0] + WORKSPACE_Y[1]) / 2])
_WORKSPACE_HALF = np.array([(WORKSPACE_X[1] - WORKSPACE_X[0]) / 2,
                            (WORKSPACE_Y[1] - WORKSPACE_Y[0]) / 2])
WORKSPACE_AREA = Area(_WORKSPACE_CENTER, 0.0, _WORKSPACE_HALF)


class LayoutError(FactaskError):
    """No layout or no target poses could be found.

    Attributes:
        what: The variable, instance or factor that could not be placed.
        reason: Why.
        tries: How many attempts were made.
        retryable: Another initial layout might succeed.
    """

    def __init__(self, what: str, reason: str, tries: int = 0, retryable: bool = True,
                 fix: str = "") -> None:
        self.what, self.reason, self.tries, self.retryable = what, reason, tries, retryable
        text = f"cannot place {what}: {reason}"
        if tries:
            text += f" (after {tries} attempt(s))"
        if fix:
            text += f"; fix: {fix}"
        super().__init__(text)


class _Infeasible(Exception):
    """One attempt failed; ``retry`` says whether other random choices may help."""

    def __init__(self, reason: str, retry: bool = True) -> None:
        super().__init__(reason)
        self.reason, self.retry = reason, retry


# ============================================================== occupancy
@dataclass
class _Body:
    obj: SceneObject
    pose: Pose
    raw: np.ndarray  # footprint sample points (k, 2): what must fit in a receptacle
    grown: np.ndarray  # footprint corners grown by half the clearance
    z0: float
    z1: float


def _body(obj: SceneObject, pose: Pose, clearance: float) -> _Body:
    z = float(pose.pos[2])
    return _Body(obj, pose, footprint_points(obj, pose), footprint_corners(obj, pose,
                 clearance / 2), z - obj.half[2], z + obj.half[2])


class Occupancy:
    """The objects in the scene as obstacles, with the collision rule of this module.

    Args:
        clearance: Gap kept between footprints, metres.
    """

    def __init__(self, clearance: float = CLEARANCE) -> None:
        self.clearance = clearance
        self._bodies: dict[str, _Body] = {}
        self._cache: tuple[list[str], np.ndarray, np.ndarray, np.ndarray] | None = None

    def copy(self) -> Occupancy:
        other = Occupancy(self.clearance)
        other._bodies = dict(self._bodies)
        return other

    def put(self, name: str, obj: SceneObject, pose: Pose) -> None:
        """Add (or move) body ``name``."""
        self._bodies[name] = _body(obj, pose, self.clearance)
        self._cache = None

    def remove(self, name: str) -> None:
        self._bodies.pop(name, None)
        self._cache = None

    def names(self) -> list[str]:
        return list(self._bodies)

    def body(self, name: str) -> _Body:
        return self._bodies[name]

    def _arrays(self) -> tuple[list[str], np.ndarray, np.ndarray, np.ndarray]:
        if self._cache is None:
            names = list(self._bodies)
            grown = np.array([self._bodies[n].grown for n in names]).reshape(-1, 4, 2)
            z0 = np.array([self._bodies[n].z0 for n in names])
            z1 = np.array([self._bodies[n].z1 for n in names])
            self._cache = (names, grown, z0, z1)
        return self._cache

    def free_mask(self, obj: SceneObject, poses: list[Pose],
                  ignore: Iterable[str] = ()) -> np.ndarray:
        """Bool (k,): which candidate poses of ``obj`` collide with no body.

        Args:
            obj: The object to place.
            poses: Candidate poses.
            ignore: Body names not to test against (e.g. the support it rests on).
        """
        k = len(poses)
        if k == 0:
            return np.zeros(0, dtype=bool)
        names, grown, z0, z1 = self._arrays()
        if not names:
            return np.ones(k, dtype=bool)
        ignored = set(ignore)
        skip = np.array([n in ignored for n in names])
        cand = footprint_corners_batch(obj, np.array([p.pos[:2] for p in poses]),
                                       np.array([p.yaw for p in poses]), self.clearance / 2)
        xy = obb_overlaps(cand, grown) & ~skip[None, :]
        cz = np.array([float(p.pos[2]) for p in poses])
        c0, c1 = cz - obj.half[2], cz + obj.half[2]
        zover = (np.minimum(c1[:, None], z1[None, :])
                 - np.maximum(c0[:, None], z0[None, :])) > Z_CONTACT_EPS
        hit = xy & zover
        # Receptacle pairs: an object inside the inner area only meets the floor.
        for ki, pi in zip(*np.nonzero(hit), strict=True):
            if not self._pair_collides(obj, poses[ki], self._bodies[names[pi]]):
                hit[ki, pi] = False
        return ~hit.any(axis=1)

    def _pair_collides(self, obj: SceneObject, pose: Pose, other: _Body) -> bool:
        mine = _body(obj, pose, self.clearance)
        if obj.is_round and other.obj.is_round:  # disks: exact, boxes are too coarse
            gap = float(np.linalg.norm(pose.pos[:2] - other.pose.pos[:2]))
            if gap >= footprint_radius(obj) + footprint_radius(other.obj) + self.clearance:
                return False
        if other.obj.is_receptacle:
            return _receptacle_pair(other, mine)
        if obj.is_receptacle:
            return _receptacle_pair(mine, other)
        return True

    def blockers(self, obj: SceneObject, pose: Pose, ignore: Iterable[str] = ()) -> list[str]:
        """Names of the bodies ``obj`` at ``pose`` collides with."""
        ignored = set(ignore)
        out = []
        for name, b in self._bodies.items():
            if name in ignored:
                continue
            alone = Occupancy(self.clearance)
            alone._bodies = {name: b}
            if not bool(alone.free_mask(obj, [pose])[0]):
                out.append(name)
        return out


def _receptacle_pair(rec: _Body, other: _Body) -> bool:
    """Collision of a receptacle with another body (which may sit inside it)."""
    area = placement_area(rec.obj, rec.pose)
    if bool(area.contains(other.raw).all()):
        floor_top = rec.z0 + floor_thickness(rec.obj)
        return (min(other.z1, floor_top) - max(other.z0, rec.z0)) > Z_CONTACT_EPS
    return True


def in_workspace(obj: SceneObject, pose: Pose) -> bool:
    """True if the object's footprint lies inside the workspace."""
    return bool(WORKSPACE_AREA.contains(footprint_corners(obj, pose)).all())


# ============================================================ sampling
def _placement_priority(graph: TaskGraph) -> list[str]:
    """Table-level variables in placement order: fixed poses, fixed objects,
    supports/containers others start on, then larger footprints first."""
    referenced = {r for v in graph.variables for r in v.references()}
    table = [v for v in graph.variables if not v.references()]
    index = {v.name: i for i, v in enumerate(graph.variables)}

    def key(v: object) -> tuple[int, int, int, float, int]:
        assert hasattr(v, "name")
        var = graph.variable(v.name)  # type: ignore[attr-defined]
        ex = var.extents
        return (0 if isinstance(var.initial, AtFixedPose) else 1,
                0 if var.is_fixed else 1,
                0 if var.name in referenced else 1,
                -ex[0] * ex[1], index[var.name])

    return [v.name for v in sorted(table, key=key)]


def _fill_check(graph: TaskGraph) -> None:
    area = 0.0
    for v in graph.variables:
        if v.references():
            continue
        ex = v.extents
        area += v.count * (ex[0] + CLEARANCE) * (ex[1] + CLEARANCE)
    ws = 4.0 * float(_WORKSPACE_HALF[0] * _WORKSPACE_HALF[1])
    if area > MAX_FILL_FRACTION * ws:
        raise LayoutError(
            f"task {graph.name!r}",
            f"the objects on the table cover {area:.3f} m^2 with clearance, more than "
            f"{MAX_FILL_FRACTION:.0%} of the {ws:.2f} m^2 workspace",
            retryable=False, fix="use fewer or smaller objects",
        )


def _random_yaws(rng: np.random.Generator, k: int) -> np.ndarray:
    return rng.uniform(-math.pi, math.pi, size=k)


def _first_free(occ: Occupancy, obj: SceneObject, poses: list[Pose],
                ignore: Iterable[str] = (), within: Area | None = None) -> Pose | None:
    """The first candidate inside the workspace (and ``within``) that is free."""
    if not poses:
        return None
    corners = footprint_corners_batch(obj, np.array([p.pos[:2] for p in poses]),
                                      np.array([p.yaw for p in poses]))
    ok = WORKSPACE_AREA.contains(corners.reshape(-1, 2)).reshape(len(poses), 4).all(axis=1)
    for start in range(0, len(poses), _CHUNK):  # chunks: most objects fit early
        idx = [i for i in range(start, min(start + _CHUNK, len(poses))) if ok[i]]
        if within is not None:
            idx = [i for i in idx if bool(within.contains(footprint_points(obj, poses[i])).all())]
        if not idx:
            continue
        free = occ.free_mask(obj, [poses[i] for i in idx], ignore)
        hits = np.flatnonzero(free)
        if len(hits):
            return poses[idx[int(hits[0])]]
    return None


def _table_candidates(obj: SceneObject, placement: object, rng: np.random.Generator,
                      k: int) -> list[Pose]:
    if isinstance(placement, InRegion):
        lo = np.array([placement.x[0], placement.y[0]])
        hi = np.array([placement.x[1], placement.y[1]])
    else:
        inset = float(obj.half_xy.min())
        lo = _WORKSPACE_CENTER - _WORKSPACE_HALF + inset
        hi = _WORKSPACE_CENTER + _WORKSPACE_HALF - inset
    xy = rng.uniform(lo, hi, size=(k, 2))
    yaw = _random_yaws(rng, k)
    return [resting_pose(obj, x, y, TABLE_Z, a) for (x, y), a in zip(xy, yaw, strict=True)]


def _area_candidates(obj: SceneObject, area: Area, surface: float, rng: np.random.Generator,
                     k: int, yaws: np.ndarray | None = None) -> list[Pose]:
    local = rng.uniform(-1.0, 1.0, size=(k, 2)) * area.half
    xy = area.center + local @ yaw_rotation_2d(area.yaw).T
    yaw = _random_yaws(rng, k) if yaws is None else yaws
    return [resting_pose(obj, x, y, surface, a) for (x, y), a in zip(xy, yaw, strict=True)]


def sample_layout(graph: TaskGraph, rng: np.random.Generator,
                  max_attempts: int = MAX_TRIES_PER_OBJECT,
                  max_restarts: int = MAX_LAYOUT_RESTARTS) -> dict[str, Pose]:
    """Sample an initial pose for every object instance of ``graph``.

    Args:
        graph: The task graph.
        rng: Random generator (same seed, same layout).
        max_attempts: Candidate poses tried per object.
        max_restarts: Whole layouts tried.

    Returns:
        Instance name -> pose (centre of its box), for fixed and free objects.

    Raises:
        LayoutError: the objects clearly cannot fit (raised before sampling), a
            fixed pose collides, or no layout was found within the bounds; names
            the variable and the reason.
    """
    objs = objects_by_name(graph)
    _fill_check(graph)
    last: _Infeasible | None = None
    what = graph.name
    for _ in range(max_restarts):
        try:
            return _sample_once(graph, objs, rng, max_attempts)
        except _Placement as exc:
            last, what = exc, exc.what
            if not exc.retry:
                break
    assert last is not None
    raise LayoutError(what, last.reason, tries=max_restarts,
                      retryable=last.retry, fix="give the objects more room")


class _Placement(_Infeasible):
    def __init__(self, what: str, reason: str, retry: bool = True) -> None:
        super().__init__(reason, retry)
        self.what = what


def _sample_once(graph: TaskGraph, objs: Mapping[str, SceneObject], rng: np.random.Generator,
                 tries: int) -> dict[str, Pose]:
    occ = Occupancy()
    poses: dict[str, Pose] = {}
    for vname in _placement_priority(graph):
        var = graph.variable(vname)
        for inst in var.instances:
            obj = objs[inst]
            if isinstance(var.initial, AtFixedPose):
                p = var.initial
                pose = resting_pose(obj, p.x, p.y, TABLE_Z, math.radians(p.yaw_deg))
                if not in_workspace(obj, pose):
                    raise _Placement(inst, f"its fixed pose ({p.x}, {p.y}) puts it partly "
                                     "outside the workspace", retry=False)
                blocked = occ.blockers(obj, pose)
                if blocked:
                    raise _Placement(inst, f"its fixed pose overlaps {blocked}", retry=False)
            else:
                pose = _first_free(occ, obj, _table_candidates(obj, var.initial, rng, tries))
                if pose is None:
                    where = "its region" if isinstance(var.initial, InRegion) else "the table"
                    raise _Placement(inst, f"no free spot on {where} in {tries} tries")
            poses[inst] = pose
            occ.put(inst, obj, pose)
    _place_dependents(graph, objs, rng, tries, occ, poses)
    return poses


def _place_dependents(graph: TaskGraph, objs: Mapping[str, SceneObject],
                      rng: np.random.Generator, tries: int, occ: Occupancy,
                      poses: dict[str, Pose]) -> None:
    """Place objects that start on / inside another, hosts first."""
    pending = [v for v in graph.variables if v.references()]
    while pending:
        ready = {v.references()[0] for v in pending
                 if all(i in poses for i in graph.variable(v.references()[0]).instances)}
        if not ready:  # validation forbids cycles; guard against an endless loop anyway
            raise _Placement(pending[0].name, "its initial placement refers in a cycle",
                             retry=False)
        host_var = next(h for h in (v.references()[0] for v in pending) if h in ready)
        group = [v for v in pending if v.references()[0] == host_var]
        pending = [v for v in pending if v.references()[0] != host_var]
        hosts = graph.variable(host_var).instances
        by_host: dict[str, list[tuple[str, bool]]] = {}
        for v in group:
            inside = isinstance(v.initial, StartInside)
            for inst in v.instances:
                host = hosts[int(rng.integers(len(hosts)))]
                by_host.setdefault(host, []).append((inst, inside))
        for host, members in by_host.items():
            _place_on_host(objs, rng, tries, occ, poses, host, members)


def _place_on_host(objs: Mapping[str, SceneObject], rng: np.random.Generator, tries: int,
                   occ: Occupancy, poses: dict[str, Pose], host: str,
                   members: list[tuple[str, bool]]) -> None:
    hobj, hpose = objs[host], poses[host]
    area = placement_area(hobj, hpose)
    surface = rest_surface_z(hobj, hpose)
    placed: list[str] = []
    for inst, _ in members:
        obj = objs[inst]
        pose = _first_free(occ, obj, _area_candidates(obj, area, surface, rng, tries),
                           ignore=[host], within=area)
        if pose is None:
            break
        poses[inst] = pose
        occ.put(inst, obj, pose)
        placed.append(inst)
    if len(placed) == len(members):
        return
    if any(inside for _, inside in members):
        raise _Placement(members[len(placed)][0], f"does not fit inside {host!r} next to "
                         f"{placed or 'nothing'} in {tries} tries")
    # Side by side failed: stack every member on the host in listed order.
    for inst in placed:
        occ.remove(inst)
        del poses[inst]
    _stack_on_host(objs, rng, tries, occ, poses, host, [m for m, _ in members])


def _stack_on_host(objs: Mapping[str, SceneObject], rng: np.random.Generator, tries: int,
                   occ: Occupancy, poses: dict[str, Pose], host: str,
                   members: list[str]) -> None:
    hobj, hpose = objs[host], poses[host]
    area = placement_area(hobj, hpose)
    surface = rest_surface_z(hobj, hpose)
    bottom = objs[members[0]]
    fits = bool(np.all(bottom.half_xy <= area.packing_half() + GEOMETRY_EPS))
    if fits:
        candidates = _area_candidates(bottom, area, surface, rng, tries)
    else:  # larger than the top face: centred on it
        candidates = [resting_pose(bottom, *area.center, surface, a)
                      for a in _random_yaws(rng, tries)]
    for cand in candidates:
        column = _column(objs, members, cand.pos[:2], cand.yaw, surface)
        trial = occ.copy()
        ok = True
        for inst, pose in column:
            obj = objs[inst]
            if not in_workspace(obj, pose) or not trial.free_mask(obj, [pose], [host])[0]:
                ok = False
                break
            trial.put(inst, obj, pose)
        if ok:
            for inst, pose in column:
                poses[inst] = pose
                occ.put(inst, objs[inst], pose)
            return
    raise _Placement(members[0], f"no room for a stack of {members} on {host!r} "
                     f"in {tries} tries")


def _column(objs: Mapping[str, SceneObject], members: list[str], xy: np.ndarray, yaw: float,
            surface: float) -> list[tuple[str, Pose]]:
    out = []
    z = surface
    for inst in members:
        obj = objs[inst]
        out.append((inst, resting_pose(obj, float(xy[0]), float(xy[1]), z, yaw)))
        z += obj.height
    return out


# ============================================================== solving
@dataclass
class SolvedFactor:
    """The concrete targets of one factor.

    Attributes:
        factor: Factor name.
        relation: Relation type (``stack``, ``row``, ...).
        objects: Instances the factor moves, in relation order.
        slots: Target pose of an object centre per slot (sized for the nominal
            object of the slot, see ``assignment``).
        matches: Bool (n_objects, n_slots): which object may take which slot.
        region: Region/container instance for ``in_zone`` / ``inside`` (the first
            if several), else None.
        regions: Every region/container instance (``in_zone``/``inside``).
        supports: Per slot, what the object rests on: an instance name or
            :data:`TABLE`.
        surfaces: Per slot, the height of the surface the object rests on (the
            target centre of object i is ``surface + its half height``), or None
            where the slot height is given explicitly (``at_pose`` with z).
        assignment: The solver's nominal slot of each object (a valid matching);
            checks re-assign objects freely within ``matches``.
        check_yaw: Whether yaw is checked (``at_pose`` may switch it off).
        chain: Slots form a column (``stack``): slot k counts only if k-1 does.
        support_group: ``on``: the support instances.
    """

    factor: str
    relation: str
    objects: list[str]
    slots: list[Pose]
    matches: np.ndarray
    region: str | None = None
    regions: list[str] = field(default_factory=list)
    supports: list[str] = field(default_factory=list)
    surfaces: list[float | None] = field(default_factory=list)
    assignment: list[int] = field(default_factory=list)
    check_yaw: bool = True
    chain: bool = False
    support_group: list[str] = field(default_factory=list)

    def target_pose(self, obj: SceneObject, slot: int) -> Pose:
        """Where the centre of ``obj`` goes when it takes ``slot``."""
        base = self.slots[slot]
        surface = self.surfaces[slot] if self.surfaces else None
        if surface is None:
            return base
        return Pose(np.array([base.pos[0], base.pos[1], surface + obj.half[2]]), base.quat)

    def targets(self, objects: Mapping[str, SceneObject]) -> dict[str, Pose]:
        """Instance -> target pose under the nominal ``assignment``."""
        return {name: self.target_pose(objects[name], j)
                for name, j in zip(self.objects, self.assignment, strict=True)}


@dataclass
class _Ctx:
    graph: TaskGraph
    objs: dict[str, SceneObject]
    current: dict[str, Pose]
    occ: Occupancy
    rng: np.random.Generator
    attempt: int = 0  # odd attempts pack by random spots instead of a grid

    def inst(self, var: str) -> list[str]:
        return self.graph.variable(var).instances


@dataclass
class _Plan:
    """What a relation solver proposes (checked by :func:`_accept`)."""

    slots: list[Pose]
    surfaces: list[float | None]
    supports: list[str]
    nominal: list[int]  # object index sized into each slot (-1: none)
    ignore: list[set[str]]  # per slot: bodies it may overlap (its hosts)
    matches: np.ndarray
    assignment: list[int]
    region: list[str] = field(default_factory=list)
    check_yaw: bool = True
    chain: bool = False
    support_group: list[str] = field(default_factory=list)
    random: bool = False  # made from random choices: another attempt may differ


def _same_variable(objs: list[SceneObject]) -> np.ndarray:
    """Matches of an *ordered* relation: the order is between variables; the identical
    instances of one variable are interchangeable (nobody can tell them apart)."""
    return np.array([[a.variable == b.variable for b in objs] for a in objs], dtype=bool)


def _same_size(objs: list[SceneObject]) -> np.ndarray:
    n = len(objs)
    return np.array([[np.allclose(objs[i].size, objs[j].size) for j in range(n)]
                     for i in range(n)], dtype=bool)


def _accept(ctx: _Ctx, movers: list[SceneObject], plan: _Plan) -> None:
    """Raise :class:`_Infeasible` unless every assigned slot is inside the workspace and
    free of obstacles and of the factor's other slots."""
    trial = ctx.occ.copy()
    # The movers' own starts stay obstacles for their slots, so no object starts at
    # a target of its own goal (starts of objects other goals move do not count:
    # those objects are moved out of the way).
    for obj in movers:
        if obj.collides:
            trial.put(f"@start:{obj.name}", obj, ctx.current[obj.name])
    for i, j in enumerate(plan.assignment):
        obj = movers[i]
        pose = _sized(plan, j, obj)
        if not in_workspace(obj, pose):
            raise _Infeasible(f"slot {j} for {obj.name} at ({pose.pos[0]:.3f}, "
                              f"{pose.pos[1]:.3f}) leaves the workspace")
        top, bottom = top_z(obj, pose), bottom_z(obj, pose)
        if top > WORKSPACE_Z[1] + GEOMETRY_EPS:
            raise _Infeasible(f"slot {j} puts the top of {obj.name} at {top:.3f} m, above "
                              f"the workspace's {WORKSPACE_Z[1]:.2f} m", retry=False)
        if bottom < TABLE_Z - Z_TOLERANCE:
            raise _Infeasible(f"slot {j} puts {obj.name} {TABLE_Z - bottom:.3f} m into "
                              "the table", retry=False)
        if not trial.free_mask(obj, [pose], plan.ignore[j])[0]:
            who = trial.blockers(obj, pose, plan.ignore[j])
            raise _Infeasible(f"slot {j} for {obj.name} collides with {who}")
        trial.put(f"@slot{j}", obj, pose)


def _sized(plan: _Plan, j: int, obj: SceneObject) -> Pose:
    s = plan.surfaces[j]
    base = plan.slots[j]
    if s is None:
        return base
    return Pose(np.array([base.pos[0], base.pos[1], s + obj.half[2]]), base.quat)


def solve_targets(graph: TaskGraph, layout: Mapping[str, Pose], rng: np.random.Generator,
                  max_attempts: int = MAX_SOLVE_ATTEMPTS) -> dict[str, SolvedFactor]:
    """Turn every factor's relation into concrete target slots.

    Args:
        graph: The task graph.
        layout: Initial pose of every instance (from :func:`sample_layout`).
        rng: Random generator (free spots, phases, offsets).
        max_attempts: Attempts per factor with other random choices.

    Returns:
        Factor name -> :class:`SolvedFactor`, in ``graph.factor_order()``.

    Raises:
        LayoutError: a factor has no feasible targets (names the factor and why).
    """
    objs = objects_by_name(graph)
    missing = [n for n in objs if n not in layout]
    if missing:
        raise LayoutError(f"layout of {graph.name!r}", f"no initial pose for {missing}",
                          retryable=False, fix="pass the dict sample_layout returns")
    ctx = _Ctx(graph, objs, dict(layout), Occupancy(), rng)
    # Obstacles for targets: what will still stand where it started. Flat markers
    # do not collide, and an object some factor moves vacates its start (the
    # oracle moves it out of the way first if a target needs the spot); its own
    # target becomes an obstacle once solved.
    moved = {i for f in graph.factors for v in f.goal.objects for i in ctx.inst(v)}
    for name, pose in layout.items():
        if name in objs and objs[name].collides and name not in moved:
            ctx.occ.put(name, objs[name], pose)
    out: dict[str, SolvedFactor] = {}
    for fname in graph.factor_order():
        f = graph.factor(fname)
        movers = [objs[i] for v in f.goal.objects for i in ctx.inst(v)]
        last: _Infeasible | None = None
        plan = None
        tries = 0
        for attempt in range(max_attempts):
            tries += 1
            ctx.attempt = attempt
            plan = None
            try:
                plan = _SOLVERS[f.goal.type](ctx, f, movers)
                _accept(ctx, movers, plan)
                break
            except _Infeasible as exc:
                last, made = exc, plan
                plan = None
                # Anchored, deterministic targets come out the same every attempt.
                if not exc.retry or (made is not None and not made.random):
                    break
        if plan is None:
            assert last is not None
            # retry=False marks reasons no initial layout can change (capacity, shape).
            raise LayoutError(f"factor {fname!r} ({f.goal.type})", last.reason, tries=tries,
                              retryable=last.retry)
        solved = SolvedFactor(
            factor=fname, relation=f.goal.type, objects=[o.name for o in movers],
            slots=plan.slots, matches=plan.matches.astype(bool),
            region=plan.region[0] if plan.region else None, regions=list(plan.region),
            supports=plan.supports, surfaces=plan.surfaces, assignment=plan.assignment,
            check_yaw=plan.check_yaw, chain=plan.chain, support_group=plan.support_group,
        )
        for name, pose in solved.targets(objs).items():
            ctx.current[name] = pose
            ctx.occ.put(name, objs[name], pose)
        out[fname] = solved
    return out


# ------------------------------------------------------------ per relation
def _plan(slots: list[Pose], surfaces: list[float | None], supports: list[str],
          ignore: list[set[str]], matches: np.ndarray, assignment: list[int] | None = None,
          **kw: object) -> _Plan:
    """A :class:`_Plan`; the nominal assignment defaults to object i -> slot i."""
    chosen = list(assignment) if assignment is not None else list(range(matches.shape[0]))
    return _Plan(slots, surfaces, supports, chosen, ignore, matches, chosen,
                 **kw)  # type: ignore[arg-type]


def _solve_at_pose(ctx: _Ctx, f: SubtaskFactor, movers: list[SceneObject]) -> _Plan:
    goal = f.goal
    assert isinstance(goal, AtPose)
    n, m = len(movers), len(goal.poses)
    matches = (np.array(goal.matches, dtype=bool) if goal.matches is not None
               else np.ones((n, m), dtype=bool))
    if matches.shape != (n, m):
        raise _Infeasible(f"matches is {matches.shape}, expected ({n}, {m})", retry=False)
    frame = ctx.current[ctx.inst(goal.frame)[0]] if goal.frame else None
    xy_list, yaws, zs = [], [], []
    for tp in goal.poses:
        xy = np.array([tp.x, tp.y])
        yaw = math.radians(tp.yaw_deg)
        z = tp.z
        if frame is not None:
            xy = frame.pos[:2] + yaw_rotation_2d(frame.yaw) @ xy
            yaw += frame.yaw
            z = None if z is None else float(frame.pos[2] + z)
        xy_list.append(xy)
        yaws.append(yaw)
        zs.append(z)
    start = np.array([ctx.current[o.name].pos[:2] for o in movers])
    dist = np.linalg.norm(start[:, None, :] - np.array(xy_list)[None, :, :], axis=-1)
    rows, cols = linear_sum_assignment(np.where(matches, dist, 1e6))
    if np.any(~matches[rows, cols]):
        raise _Infeasible("matches leave some object without a pose of its own", retry=False)
    assignment = [0] * n
    for r, c in zip(rows, cols, strict=True):
        assignment[int(r)] = int(c)
    slots, surfaces, supports, ignore = [], [], [], []
    moving = {o.name for o in movers}
    for j in range(m):
        who = [i for i in range(n) if assignment[i] == j]
        obj = movers[who[0]] if who else movers[int(np.argmax(matches[:, j]))]
        if zs[j] is not None:
            surface, host = None, TABLE
            slots.append(Pose.from_xyz_yaw(*xy_list[j], zs[j], yaws[j]))
        else:
            surface, host = _surface_under(ctx, xy_list[j], exclude=moving)
            slots.append(resting_pose(obj, *xy_list[j], surface, yaws[j]))
        surfaces.append(surface)
        supports.append(host)
        ignore.append(set() if host == TABLE else {host})
    return _plan(slots, surfaces, supports, ignore, matches, assignment=assignment,
                 check_yaw=goal.check_yaw)


def _surface_under(ctx: _Ctx, xy: np.ndarray, exclude: set[str]) -> tuple[float, str]:
    """Highest resting surface under point ``xy`` and what provides it."""
    best, host = TABLE_Z, TABLE
    for name in ctx.occ.names():
        if name in exclude or name not in ctx.objs:
            continue
        obj = ctx.objs[name]
        if not obj.collides or not (obj.spec.support or obj.is_receptacle):
            continue
        pose = ctx.current[name]
        if not bool(placement_area(obj, pose).contains(xy[None, :])[0]):
            continue
        s = rest_surface_z(obj, pose)
        if s > best:
            best, host = s, name
    return best, host


def _grid(movers: list[SceneObject], area: Area, rng: np.random.Generator,
          what: str) -> tuple[list[np.ndarray], float]:
    """Centres (and yaw) of a grid of the objects inside ``area`` with a random offset.

    Raises:
        _Infeasible: the grid does not fit (not retryable).
    """
    n = len(movers)
    if area.round:
        ring = _ring_in_disk(movers, area, rng)
        if ring is not None:
            return ring, area.yaw
    half = area.packing_half()
    size = np.array([[o.size[0], o.size[1]] for o in movers]).max(axis=0)
    best = None
    # Keep the outer objects EDGE_MARGIN off the area's edge (a wall, a zone's
    # border) so physics jitter cannot push them partly outside; only a grid that
    # fits no other way touches the edge.
    for margin in (EDGE_MARGIN, 0.0):
        length = 2 * half - 2 * margin
        for turn in (0.0, math.pi / 2):
            cell = (size if turn == 0.0 else size[::-1]) + CLEARANCE
            cap = np.floor((length + CLEARANCE) / cell + GEOMETRY_EPS).astype(int)
            if cap[0] * cap[1] >= n and cap.min() >= 1:
                best = (turn, cell, cap)
                break
        if best is not None:
            break
    if best is None:
        raise _Infeasible(f"{n} object(s) of up to {size[0]:.3f} x {size[1]:.3f} m do not fit "
                          f"in {what} ({length[0]:.3f} x {length[1]:.3f} m usable)",
                          retry=False)
    turn, cell, cap = best
    cols = int(min(cap[0], n))
    rows = math.ceil(n / cols)
    used = np.array([cols * cell[0] - CLEARANCE, rows * cell[1] - CLEARANCE])
    slack = np.maximum(length - used, 0.0)
    offset = rng.uniform(-slack / 2, slack / 2)
    centres = []
    rot = yaw_rotation_2d(area.yaw)
    for k in range(n):
        r, c = divmod(k, cols)
        local = np.array([(c - (cols - 1) / 2) * cell[0], (r - (rows - 1) / 2) * cell[1]])
        centres.append(area.center + rot @ (local + offset))
    return centres, area.yaw + turn


def _clear_radius(obj: SceneObject) -> float:
    """Half the centre distance at which two such objects keep the clearance whatever
    their yaw (a box's grown corner reaches clearance/2 * sqrt(2) further)."""
    grow = CLEARANCE / 2 * (1.0 if obj.is_round else math.sqrt(2.0))
    return footprint_radius(obj) + grow


def _ring_in_disk(movers: list[SceneObject], area: Area,
                  rng: np.random.Generator) -> list[np.ndarray] | None:
    """Centres of the objects on a ring inside a disk area (None if they do not fit)."""
    n = len(movers)
    rad = max(footprint_radius(o) for o in movers)
    ring = max(_clear_radius(o) for o in movers) / math.sin(math.pi / n) if n > 1 else 0.0
    if ring + rad > area.half[0] + GEOMETRY_EPS:
        return None
    phase = float(rng.uniform(0.0, 2 * math.pi))
    return [area.center + ring * np.array([math.cos(phase + 2 * math.pi * k / n),
                                           math.sin(phase + 2 * math.pi * k / n)])
            for k in range(n)]


def _pack_plan(ctx: _Ctx, movers: list[SceneObject], groups: list[tuple[str, list[int]]],
               attempt_sampling: bool) -> tuple[list[Pose], list[float | None], list[str]]:
    """Slots for objects packed into the area of each host (grid, or random spots)."""
    n = len(movers)
    slots: list[Pose | None] = [None] * n
    surfaces: list[float | None] = [None] * n
    supports = [TABLE] * n
    for host, members in groups:
        hobj, hpose = ctx.objs[host], ctx.current[host]
        area = placement_area(hobj, hpose)
        surface = rest_surface_z(hobj, hpose)
        mobjs = [movers[i] for i in members]
        if attempt_sampling:
            trial = ctx.occ.copy()
            for i, obj in zip(members, mobjs, strict=True):
                yaws = area.yaw + (math.pi / 2) * ctx.rng.integers(0, 2, MAX_TRIES_PER_OBJECT)
                pose = _first_free(trial, obj, _area_candidates(
                    obj, area, surface, ctx.rng, MAX_TRIES_PER_OBJECT, yaws), [host], area)
                if pose is None:
                    raise _Infeasible(f"no free spot for {obj.name} in {host!r}")
                trial.put(f"@{obj.name}", obj, pose)
                slots[i] = pose
        else:
            centres, yaw = _grid(mobjs, area, ctx.rng, repr(host))
            for i, obj, c in zip(members, mobjs, centres, strict=True):
                slots[i] = resting_pose(obj, float(c[0]), float(c[1]), surface, yaw)
        for i in members:
            surfaces[i] = surface
            supports[i] = host
    return [s for s in slots if s is not None], surfaces, supports


def _solve_region(ctx: _Ctx, f: SubtaskFactor, movers: list[SceneObject]) -> _Plan:
    goal = f.goal
    assert isinstance(goal, (InZone, Inside))
    var = goal.zone if isinstance(goal, InZone) else goal.container
    hosts = ctx.inst(var)
    n = len(movers)
    groups = [(h, [i for i in range(n) if i % len(hosts) == k]) for k, h in enumerate(hosts)]
    groups = [(h, m) for h, m in groups if m]
    # Alternate: a grid (tight, reliable) on even attempts, random spots (which
    # work around objects already resting in the region) on odd ones.
    slots, surfaces, supports = _pack_plan(ctx, movers, groups, ctx.attempt % 2 == 1)
    ignore = [{s} for s in supports]
    return _plan(slots, surfaces, supports, ignore, np.ones((n, n), dtype=bool),
                 region=list(hosts), random=True)


def _solve_on(ctx: _Ctx, f: SubtaskFactor, movers: list[SceneObject]) -> _Plan:
    goal = f.goal
    assert isinstance(goal, On)
    hosts = ctx.inst(goal.support)
    n = len(movers)
    ones = np.ones((n, n), dtype=bool)
    if len(hosts) == 1:
        host = hosts[0]
        hobj, hpose = ctx.objs[host], ctx.current[host]
        area = placement_area(hobj, hpose)
        fits = all(np.all(o.half_xy <= area.packing_half() + GEOMETRY_EPS) for o in movers)
        if n == 1 and not fits:  # bigger than the top face: centred on it
            surface = rest_surface_z(hobj, hpose)
            slot = resting_pose(movers[0], *area.center, surface, area.yaw)
            return _plan([slot], [surface], [host], [{host}], ones, support_group=hosts)
        slots, surfaces, supports = _pack_plan(ctx, movers, [(host, list(range(n)))],
                                               ctx.attempt % 2 == 1)
        return _plan(slots, surfaces, supports, [{host}] * n, ones, support_group=hosts,
                     random=True)
    hobjs = [ctx.objs[h] for h in hosts]
    hposes = [ctx.current[h] for h in hosts]
    area = group_area(hobjs, hposes)
    surface = max(rest_surface_z(o, p) for o, p in zip(hobjs, hposes, strict=True))
    width = max(o.size[1] for o in movers) + CLEARANCE
    normal = yaw_rotation_2d(area.yaw) @ np.array([0.0, 1.0])
    slots = [resting_pose(o, *(area.center + (k - (n - 1) / 2) * width * normal), surface,
                          area.yaw) for k, o in enumerate(movers)]
    return _plan(slots, [surface] * n, [hosts[0]] * n, [set(hosts)] * n, ones,
                 support_group=hosts)


def _anchor(ctx: _Ctx, var: str) -> tuple[Area, float, list[str]]:
    """Area, resting surface and instances of an anchor variable (a group if several)."""
    hosts = ctx.inst(var)
    hobjs = [ctx.objs[h] for h in hosts]
    hposes = [ctx.current[h] for h in hosts]
    area = group_area(hobjs, hposes)
    surface = max(rest_surface_z(o, p) for o, p in zip(hobjs, hposes, strict=True))
    return area, surface, hosts


def _free_spots(ctx: _Ctx, k: int) -> list[tuple[np.ndarray, float]]:
    xy = ctx.rng.uniform(_WORKSPACE_CENTER - _WORKSPACE_HALF,
                         _WORKSPACE_CENTER + _WORKSPACE_HALF, size=(k, 2))
    yaw = ctx.rng.uniform(-math.pi / 2, math.pi / 2, size=k)
    return list(zip(xy, yaw, strict=True))


def _search(ctx: _Ctx, movers: list[SceneObject], build: object, what: str,
            spots: list[tuple[np.ndarray, float]] | None = None) -> _Plan:
    """Try spots (default: random ones on the table) until ``build(xy, yaw)`` gives
    an acceptable plan."""
    assert callable(build)
    last = "no candidate"
    for xy, yaw in spots if spots is not None else _free_spots(ctx, MAX_TRIES_PER_OBJECT):
        plan = build(xy, yaw)
        plan.random = True
        try:
            _accept(ctx, movers, plan)
            return plan
        except _Infeasible as exc:
            if not exc.retry:  # no other spot can help (too tall, too long, ...)
                raise
            last = exc.reason
    raise _Infeasible(f"no free spot on the table for {what} ({last})")


def _solve_stack(ctx: _Ctx, f: SubtaskFactor, movers: list[SceneObject]) -> _Plan:
    goal = f.goal
    assert isinstance(goal, Stack)
    n = len(movers)
    matches = _same_variable(movers) if goal.ordered else _same_size(movers)

    def build(xy: np.ndarray, yaw: float, surface: float = TABLE_Z,
              hosts: list[str] | None = None) -> _Plan:
        slots, surfaces, supports = [], [], []
        z = surface
        for k, o in enumerate(movers):
            slots.append(resting_pose(o, float(xy[0]), float(xy[1]), z, yaw))
            surfaces.append(z)
            supports.append(movers[k - 1].name if k else (hosts[0] if hosts else TABLE))
            z += o.height
        return _plan(slots, list(surfaces), supports, [set(hosts or [])] * n, matches,
                     chain=True, support_group=list(hosts or []))

    if goal.base:
        area, surface, hosts = _anchor(ctx, goal.base)
        fits = bool(np.all(movers[0].half_xy <= area.packing_half() + GEOMETRY_EPS))
        if len(hosts) > 1 or not fits:
            return build(area.center, area.yaw, surface, hosts)
        # Centred on the base if free there, else another spot of its top face.
        room = np.maximum(area.packing_half() - movers[0].half_xy, 0.0)
        local = ctx.rng.uniform(-room, room, size=(MAX_TRIES_PER_OBJECT, 2))
        local[0] = 0.0
        spots = [(area.center + yaw_rotation_2d(area.yaw) @ p, area.yaw) for p in local]
        return _search(ctx, movers, lambda xy, yaw: build(xy, yaw, surface, hosts),
                       f"a stack of {n} on {goal.base!r}", spots)
    return _search(ctx, movers, build, f"a stack of {n}")


def _solve_row(ctx: _Ctx, f: SubtaskFactor, movers: list[SceneObject]) -> _Plan:
    goal = f.goal
    assert isinstance(goal, Row)
    n = len(movers)
    matches = _same_variable(movers) if goal.ordered else np.ones((n, n), dtype=bool)
    spacing = goal.spacing or (max(o.size[0] for o in movers) + ROW_GAP)

    def line(centre: np.ndarray, yaw: float, surface: float, hosts: list[str]) -> _Plan:
        d = yaw_rotation_2d(yaw) @ np.array([1.0, 0.0])
        slots = [resting_pose(o, *(centre + (k - (n - 1) / 2) * spacing * d), surface, yaw)
                 for k, o in enumerate(movers)]
        return _plan(slots, [surface] * n, [hosts[0] if hosts else TABLE] * n,
                     [set(hosts)] * n, matches)

    if goal.on:
        below = ctx.inst(goal.on)
        bobjs = [ctx.objs[b] for b in below]
        bposes = [ctx.current[b] for b in below]
        centres = np.array([p.pos[:2] for p in bposes])
        yaw = principal_yaw(centres) if len(below) > 1 else bposes[0].yaw
        d = yaw_rotation_2d(yaw) @ np.array([1.0, 0.0])
        order = list(np.argsort(centres @ d, kind="stable"))
        tops = [rest_surface_z(bobjs[i], bposes[i]) for i in order]
        names = [below[i] for i in order]
        pts = [centres[i] for i in order]
        if len(below) == n:
            spots = list(zip(pts, tops, [[b] for b in names], strict=True))
        elif len(below) == n + 1:
            spots = [((pts[k] + pts[k + 1]) / 2, max(tops[k], tops[k + 1]),
                      [names[k], names[k + 1]]) for k in range(n)]
        else:
            plan = line(centres.mean(axis=0), yaw, max(tops), names)
            areas = [placement_area(bobjs[i], bposes[i]) for i in range(len(below))]
            for o, slot in zip(movers, plan.slots, strict=True):
                if not any(bool(a.contains(slot.pos[:2]).all()) for a in areas):
                    raise _Infeasible(f"a row of {n} on the {len(below)} object(s) of "
                                      f"{goal.on!r} leaves {o.name} unsupported (use as "
                                      "many objects as below, or one fewer)", retry=False)
            return plan
        slots = [resting_pose(o, *c, s, yaw) for o, (c, s, _) in zip(movers, spots,
                                                                      strict=True)]
        return _plan(slots, [s for _, s, _ in spots], [h[0] for _, _, h in spots],
                     [set(h) for _, _, h in spots], matches)
    if goal.along:
        host = ctx.inst(goal.along)[0]
        hobj, hpose = ctx.objs[host], ctx.current[host]
        yaw = hpose.yaw if hobj.size[0] >= hobj.size[1] else hpose.yaw + math.pi / 2
        # A line looks the same turned half a turn: take the direction pointing to
        # +x (as principal_yaw does), so "first object" means the same end always.
        yaw = math.atan2(math.sin(yaw), math.cos(yaw))
        if yaw > math.pi / 2 + GEOMETRY_EPS:
            yaw -= math.pi
        elif yaw <= -math.pi / 2 + GEOMETRY_EPS:
            yaw += math.pi
        plan = line(hpose.pos[:2], yaw, rest_surface_z(hobj, hpose), [host])
        area = placement_area(hobj, hpose)
        for slot in plan.slots:
            if not bool(area.contains(slot.pos[:2]).all()):
                raise _Infeasible(f"a row of {n} spaced {spacing:.3f} m is longer than "
                                  f"{goal.along!r}", retry=False)
        return plan
    return _search(ctx, movers, lambda xy, yaw: line(xy, yaw, TABLE_Z, []),
                   f"a row of {n}")


def _solve_circle(ctx: _Ctx, f: SubtaskFactor, movers: list[SceneObject]) -> _Plan:
    goal = f.goal
    assert isinstance(goal, Circle)
    n = len(movers)
    diag = 2 * max(_clear_radius(o) for o in movers)
    # RING_SLACK: neighbours exactly at the clearance fail the collision test by
    # rounding, for some phases only (a slow, random search otherwise).
    radius = (diag + RING_SLACK) / (2 * math.sin(math.pi / n)) if n > 1 else 0.0
    ones = np.ones((n, n), dtype=bool)
    phase = float(ctx.rng.uniform(0, 2 * math.pi / max(n, 1)))

    def ring(centre: np.ndarray, r: float, surface: float, hosts: list[str]) -> _Plan:
        slots = []
        for k, o in enumerate(movers):
            a = phase + 2 * math.pi * k / n
            xy = centre + r * np.array([math.cos(a), math.sin(a)])
            slots.append(resting_pose(o, *xy, surface, a + math.pi))
        return _plan(slots, [surface] * n, [hosts[0] if hosts else TABLE] * n,
                     [set(hosts)] * n, ones)

    if goal.center:
        hosts = ctx.inst(goal.center)
        hobjs = [ctx.objs[h] for h in hosts]
        area, _, _ = _anchor(ctx, goal.center)
        first = hobjs[0]
        if first.is_receptacle or not first.collides:
            surface = TABLE_Z
            if first.is_receptacle:  # around it on the table: clear its footprint
                outer = float(np.linalg.norm(area.half)) + diag / 2
                radius = max(radius, outer)
        else:
            surface = max(rest_surface_z(o, ctx.current[h])
                          for o, h in zip(hobjs, hosts, strict=True))
        r = goal.radius or radius
        plan = ring(area.center, r, surface, [] if first.is_receptacle else hosts)
        plan.random = True  # the phase is random
        if first.collides and not first.is_receptacle:
            fits_on_top = all(bool(area.contains(footprint_corners(o, slot)).all())
                              for o, slot in zip(movers, plan.slots, strict=True))
            if not fits_on_top:
                # Too small to carry the ring (a block among others): the ring goes
                # *around* it on the table, clear of its footprint.
                outer = float(np.linalg.norm(area.half)) + diag / 2 + CLEARANCE
                r = max(goal.radius or 0.0, radius, outer)
                plan = ring(area.center, r, TABLE_Z, [])
                plan.random = True
        return plan
    r = goal.radius or radius
    return _search(ctx, movers, lambda xy, _yaw: ring(xy, r, TABLE_Z, []),
                   f"a circle of {n}")


def _solve_aligned(ctx: _Ctx, f: SubtaskFactor, movers: list[SceneObject]) -> _Plan:
    goal = f.goal
    assert isinstance(goal, Aligned)
    refs = ctx.inst(goal.reference)
    n, m = len(movers), len(refs)
    if n > m:
        raise _Infeasible(f"{n} object(s) but only {m} instance(s) of reference "
                          f"{goal.reference!r}", retry=False)
    slots, surfaces, supports, ignore = [], [], [], []
    for j, ref in enumerate(refs):
        robj, rpose = ctx.objs[ref], ctx.current[ref]
        obj = movers[j if j < n else 0]
        surface = rest_surface_z(robj, rpose)
        if goal.mode == "corner":
            v = corner_vertex(robj, rpose)
            c = v + yaw_rotation_2d(rpose.yaw) @ obj.half_xy
        else:
            c = rpose.pos[:2]
        slots.append(resting_pose(obj, float(c[0]), float(c[1]), surface, rpose.yaw))
        surfaces.append(surface)
        supports.append(ref if robj.collides else TABLE)
        ignore.append({ref})
    nominal = [movers[j if j < n else 0] for j in range(m)]
    matches = np.array([[np.allclose(o.size, nominal[j].size) for j in range(m)]
                        for o in movers], dtype=bool)
    return _plan(slots, surfaces, supports, ignore, matches)


_SOLVERS = {
    "at_pose": _solve_at_pose,
    "in_zone": _solve_region,
    "inside": _solve_region,
    "on": _solve_on,
    "stack": _solve_stack,
    "row": _solve_row,
    "circle": _solve_circle,
    "aligned": _solve_aligned,
}


# ============================================================== reset
def moving_factors(graph: TaskGraph) -> list[str]:
    """Factors whose goal moves at least one object (every factor, by the schema)."""
    return [f.name for f in graph.factors if f.goal.objects]


def reset_layout(graph: TaskGraph, rng: np.random.Generator,
                 max_resets: int = MAX_RESETS
                 ) -> tuple[dict[str, Pose], dict[str, SolvedFactor]]:
    """Sample an initial layout and solve every factor's targets.

    The layout is resampled (at most ``max_resets`` times) when the targets cannot
    be solved from it, or when it already satisfies a goal.

    Args:
        graph: The task graph.
        rng: Random generator (same seed, same result).
        max_resets: Initial layouts tried.

    Returns:
        (initial poses, solved factors).

    Raises:
        LayoutError: no layout worked; the message has the last reason.
    """
    from factask.sim.checks import check_task  # checks imports this module

    objs = objects_by_name(graph)
    last: LayoutError | None = None
    for _ in range(max_resets):
        try:
            layout = sample_layout(graph, rng)
            solved = solve_targets(graph, layout, rng)
        except LayoutError as exc:
            last = exc
            if not exc.retryable:
                raise
            continue
        status = check_task(graph, solved, layout, objects=objs)
        done = [n for n in moving_factors(graph) if status.factors[n].satisfied]
        if done:
            last = LayoutError(f"factor(s) {done}", "every sampled initial layout already "
                               "satisfies them", tries=max_resets,
                               fix="start the objects somewhere else")
            continue
        return layout, solved
    assert last is not None
    raise LayoutError(last.what, last.reason, tries=max_resets, retryable=False)
