"""The initial-layout sampler: where every object starts (pure numpy).

:func:`sample_layout` gives every object instance an initial pose that honours
its variable's ``initial`` placement, with footprints that never overlap (the
collision rule of :mod:`factask.scene.collision`) except where an object
deliberately rests on or inside another. Every search is bounded
(:data:`~factask.scene.collision.MAX_TRIES_PER_OBJECT` candidates per object,
:data:`MAX_LAYOUT_RESTARTS` whole layouts); failure raises
:class:`~factask.scene.collision.LayoutError` naming what could not be placed
and why.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence

import numpy as np

from factask.geometry import Pose
from factask.graph.taskgraph import TaskGraph
from factask.relations.base import Reserve
from factask.relations.drawer import pose_at
from factask.scene.cabinet import drawer_shown_area, front_reserve
from factask.scene.collision import (
    CLEARANCE,
    MAX_TRIES_PER_OBJECT,
    NO_DEADLINE,
    WORKSPACE_CENTER,
    WORKSPACE_HALF,
    Deadline,
    LayoutError,
    Occupancy,
    area_candidates,
    first_free,
    in_workspace,
    on_table,
    random_yaws,
)
from factask.scene.microwave import swing_reserve
from factask.scene.objects import (
    GEOMETRY_EPS,
    SceneObject,
    floor_thickness,
    objects_by_name,
    placement_area,
    rest_surface_z,
    resting_pose,
    yaw_rotation_2d,
)
from factask.scene.switch import switch_host, switch_pose
from factask.sim.layout.pile import is_pile, layout_area, place_pile
from factask.sim.layout.rope import is_rope, place_rope
from factask.vocabulary.kinds import DRAWER_GAP, drawer_size
from factask.vocabulary.variables import (
    AtFixedPose,
    InCabinet,
    InRegion,
    MountedOn,
    StartInside,
    StartOn,
    drawers_of,
)
from factask.vocabulary.world import TABLE_Z

#: Whole-layout restarts before :func:`sample_layout` gives up.
MAX_LAYOUT_RESTARTS = 8
#: Footprints (grown by the clearance) may cover at most this fraction of the
#: workspace: above it a random layout is hopeless and sampling fails at once.
MAX_FILL_FRACTION = 0.9


class _Placement(Exception):
    """One layout attempt failed at instance ``what``; ``retry``: another may work."""

    def __init__(self, what: str, reason: str, retry: bool = True) -> None:
        super().__init__(reason)
        self.what, self.reason, self.retry = what, reason, retry


def _placement_priority(graph: TaskGraph) -> list[str]:
    """Table-level variables in placement order: fixed poses, fixed objects,
    supports/containers others start on, then larger footprints first."""
    referenced = {r for v in graph.variables for r in v.references()}
    table = [v for v in graph.variables if not v.references()]
    index = {v.name: i for i, v in enumerate(graph.variables)}

    def key(v: object) -> tuple[int, int, int, float, int]:
        assert hasattr(v, "name")
        var = graph.variable(v.name)  # type: ignore[attr-defined]
        return (0 if isinstance(var.initial, AtFixedPose) else 1,
                0 if var.is_fixed else 1,
                0 if var.name in referenced else 1,
                -layout_area(var), index[var.name])

    return [v.name for v in sorted(table, key=key)]


def _fill_check(graph: TaskGraph) -> None:
    area = 0.0
    for v in graph.variables:
        if v.references():
            continue
        ex = v.extents
        area += v.count * (ex[0] + CLEARANCE) * (ex[1] + CLEARANCE)
    ws = 4.0 * float(WORKSPACE_HALF[0] * WORKSPACE_HALF[1])
    if area > MAX_FILL_FRACTION * ws:
        raise LayoutError(
            f"task {graph.name!r}",
            f"the objects on the table cover {area:.3f} m^2 with clearance, more than "
            f"{MAX_FILL_FRACTION:.0%} of the {ws:.2f} m^2 workspace",
            retryable=False, fix="use fewer or smaller objects",
        )


#: Candidate poses are built in batches of growing size (most objects fit among
#: the first few): building all of them up front cost more than the search.
_CANDIDATE_BATCHES = (8, 32)


def _first_free_on_table(occ: Occupancy, obj: SceneObject, placement: object,
                         rng: np.random.Generator, k: int,
                         reserves: Sequence[Reserve] = ()) -> Pose | None:
    """The first of ``k`` random table poses of ``obj`` that is free (as
    :func:`first_free` on all of them, whose random draws it makes all at once),
    with its ``reserves`` free and inside the workspace too."""
    xy, yaw = _table_draws(obj, placement, rng, k)
    start = 0
    for stop in (*(b for b in _CANDIDATE_BATCHES if b < k), k):
        batch = [resting_pose(obj, x, y, TABLE_Z, a)
                 for (x, y), a in zip(xy[start:stop], yaw[start:stop], strict=True)]
        if reserves:
            batch = [p for p in batch
                     if all(first_free(occ, r, [rp]) for r, rp in _reserved(obj, p, reserves))]
        pose = first_free(occ, obj, batch, solid_fixtures=True)
        if pose is not None:
            return pose
        start = stop
    return None


def _reserved(obj: SceneObject, pose: Pose,
              reserves: Sequence[Reserve]) -> list[tuple[SceneObject, Pose]]:
    """The rectangles ``obj`` at ``pose`` keeps clear, as flat boxes with their poses."""
    out = []
    for i, r in enumerate(reserves):
        x, y = pose.pos[:2] + yaw_rotation_2d(pose.yaw) @ np.array([r.x, r.y])
        box = SceneObject(name=f"{obj.name}:reserve{i}", variable=obj.variable, index=0,
                          kind="box", size=(*r.size, 0.001), color="gray", fixed=True,
                          symmetry_deg=180.0, mass=0.0, collides=True)
        out.append((box, Pose.from_xyz_yaw(float(x), float(y), TABLE_Z, pose.yaw)))
    return out


def _layout_reserves(graph: TaskGraph) -> dict[str, list[Reserve]]:
    """Variable -> the table its instances keep clear for the goals anchored to it."""
    variables = {v.name: v for v in graph.variables}
    out: dict[str, list[Reserve]] = {}
    for f in graph.factors:
        for r in f.goal.layout_reserves(variables):
            out.setdefault(r.anchor, []).append(r)
    # A cabinet (a microwave) keeps the table in front of it clear: its drawers slide
    # (its door swings) out there.
    objs = objects_by_name(graph)
    for v in graph.variables:
        drawers = drawers_of(graph.variables, v.name) if v.kind == "cabinet" else []
        if drawers:
            depth = drawer_size(v.extents, len(drawers))[0]
            x, y, size = front_reserve(objs[v.instances[0]], depth)
            out.setdefault(v.name, []).append(Reserve(v.name, x, y, size))
        if v.kind == "microwave":  # its door swings out there
            x, y, size = swing_reserve(objs[v.instances[0]])
            out.setdefault(v.name, []).append(Reserve(v.name, x, y, size))
    return out


def _table_draws(obj: SceneObject, placement: object, rng: np.random.Generator,
                 k: int) -> tuple[np.ndarray, np.ndarray]:
    """``k`` random (x, y) centres and yaws of ``obj`` on the table (its region)."""
    if isinstance(placement, InRegion):
        lo = np.array([placement.x[0], placement.y[0]])
        hi = np.array([placement.x[1], placement.y[1]])
    else:
        inset = float(obj.half_xy.min())
        lo = WORKSPACE_CENTER - WORKSPACE_HALF + inset
        hi = WORKSPACE_CENTER + WORKSPACE_HALF - inset
    xy = rng.uniform(lo, hi, size=(k, 2))  # centres first: the seeded layouts stay
    yaws = random_yaws(rng, k)
    if float(np.hypot(*obj.half_xy)) > float(np.min(WORKSPACE_HALF)):
        # Too big to turn freely on the table (a zone half the table wide): only its
        # right-angle yaws can fit, so draw those rather than miss them at random.
        yaws = rng.integers(0, 4, size=k) * (np.pi / 2)
    return xy, yaws


def sample_layout(graph: TaskGraph, rng: np.random.Generator,
                  max_attempts: int = MAX_TRIES_PER_OBJECT,
                  max_restarts: int = MAX_LAYOUT_RESTARTS,
                  deadline: Deadline = NO_DEADLINE) -> dict[str, Pose]:
    """Sample an initial pose for every object instance of ``graph``.

    Args:
        graph: The task graph.
        rng: Random generator (same seed, same layout).
        max_attempts: Candidate poses tried per object.
        max_restarts: Whole layouts tried.
        deadline: When to give up (checked before each whole layout).

    Returns:
        Instance name -> pose (centre of its box), for fixed and free objects.

    Raises:
        LayoutError: the objects clearly cannot fit (raised before sampling), a
            fixed pose collides, or no layout was found within the bounds; names
            the variable and the reason.
    """
    objs = objects_by_name(graph)
    _fill_check(graph)
    last: _Placement | None = None
    what = graph.name
    for _ in range(max_restarts):
        deadline.check(what, last.reason if last else "")
        try:
            return _sample_once(graph, objs, rng, max_attempts)
        except _Placement as exc:
            last, what = exc, exc.what
            if not exc.retry:
                break
    assert last is not None
    raise LayoutError(what, last.reason, tries=max_restarts,
                      retryable=last.retry, fix="give the objects more room")


def _sample_once(graph: TaskGraph, objs: Mapping[str, SceneObject], rng: np.random.Generator,
                 tries: int) -> dict[str, Pose]:
    occ = Occupancy()
    poses: dict[str, Pose] = {}
    reserves = _layout_reserves(graph)
    for vname in _placement_priority(graph):
        var = graph.variable(vname)
        if is_pile(var) or is_rope(var):
            group = (place_pile if is_pile(var) else place_rope)(var, objs, occ, rng, tries)
            if group is None:
                raise _Placement(var.instances[0], f"no free spot for the {var.kind} "
                                 f"in {tries} tries")
            poses.update(group)
            continue
        for inst in var.instances:
            obj = objs[inst]
            if isinstance(var.initial, AtFixedPose):
                p = var.initial
                pose = resting_pose(obj, p.x, p.y, TABLE_Z, math.radians(p.yaw_deg))
                # A pose the task's author gave is a fact: its centre is in the
                # workspace (validation), and only what cannot physically be — an
                # object hanging off the table — is refused (Ravens accepts the rest).
                if not on_table(obj, pose):
                    raise _Placement(inst, f"its fixed pose ({p.x}, {p.y}) leaves part of it "
                                     "hanging off the table", retry=False)
                blocked = _physical_overlaps(objs, obj, occ.blockers(obj, pose, clearance=0.0))
                if blocked:
                    raise _Placement(inst, f"its fixed pose overlaps {blocked}", retry=False)
            else:
                kept = reserves.get(vname, [])
                pose = _first_free_on_table(occ, obj, var.initial, rng, tries, kept)
                if pose is None:
                    where = "its region" if isinstance(var.initial, InRegion) else "the table"
                    room = " with room in front for its goal" if kept else ""
                    raise _Placement(inst, f"no free spot on {where}{room} in {tries} tries")
                for box, box_pose in _reserved(obj, pose, kept):
                    occ.put(box.name, box, box_pose)
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
            if isinstance(v.initial, MountedOn):  # its place on its host is a fact
                host = switch_host(graph, v.name)
                pose = switch_pose(objs[host], poses[host], 1.0 if v.initial.on else 0.0)
                poses[v.name] = pose
                occ.put(v.name, objs[v.name], pose)
                continue
            if isinstance(v.initial, InCabinet):  # its place in its host is a fact
                host = v.initial.cabinet
                pose = pose_at(graph, objs[v.name], objs[host], poses[host],
                               v.initial.opening)
                poses[v.name] = pose
                occ.put(v.name, objs[v.name], pose)
                continue
            inside = isinstance(v.initial, StartInside)
            if v.initial.offset is not None:  # an author's place: a fact
                _place_given(objs, occ, poses, hosts[0], v.instances[0], v.initial)
                continue
            for inst in v.instances:
                host = hosts[int(rng.integers(len(hosts)))]
                by_host.setdefault(host, []).append((inst, inside))
        for host, members in by_host.items():
            _place_on_host(objs, rng, tries, occ, poses, host, members,
                           _drawer_cabinet(graph, host_var, objs, poses, members))


def _drawer_cabinet(graph: TaskGraph, host_var: str, objs: Mapping[str, SceneObject],
                    poses: Mapping[str, Pose], members: list[tuple[str, bool]]) -> list[str]:
    """The cabinet around drawer ``host_var`` (``[]`` if it is no drawer): what is
    inside a drawer meets its cabinet only above the drawer's rim, where the bay's
    ceiling is (a drawer stands a gap below it), so the cabinet's box is not an
    obstacle to it, even with the drawer shut. (Where in the drawer it may start is
    :func:`~factask.scene.cabinet.drawer_shown_area`.)

    Raises:
        _Placement: a member stands taller than the drawer's rim (it would hit the
            bay's ceiling when the drawer closes): not retried.
    """
    start = graph.variable(host_var).initial
    # A shelf level is open to the sky: the collision rule already lets what stands
    # on it meet the shelf's levels, never its panels.
    if not isinstance(start, InCabinet) or graph.variable(host_var).kind != "drawer":
        return []
    drawer = objs[host_var]
    rim = float(poses[host_var].pos[2]) + drawer.half[2] + DRAWER_GAP
    floor = float(poses[host_var].pos[2]) - drawer.half[2] + floor_thickness(drawer)
    for inst, _ in members:
        if floor + objs[inst].height > rim + GEOMETRY_EPS:
            raise _Placement(inst, f"it is {objs[inst].height * 100:.1f} cm tall, taller "
                             f"than drawer {host_var!r} ({(rim - floor) * 100:.1f} cm to its "
                             "bay's ceiling): it would not close", retry=False)
    return [start.cabinet]


def _physical_overlaps(objs: Mapping[str, SceneObject], obj: SceneObject,
                       blockers: list[str]) -> list[str]:
    """The overlaps at an author-given pose that physics cannot take: two fixed
    bodies may interpenetrate (both are welded to the world; the author's shapes
    are often finer than factask's boxes: kit holes), a movable one may not. The
    ``blockers`` are found with no clearance: an author may put objects closer
    than the gap factask's own sampling keeps (Ravens' free-space test is finer). A
    flat marker (a zone, a line: no collision) is no body either: an author may
    start an object on one."""
    # A reserve (not in objs) is no body: whether its goal still fits is the solver's.
    return [b for b in blockers if b in objs and obj.collides and objs[b].collides
            and not (obj.fixed and objs[b].fixed)]


def _place_given(objs: Mapping[str, SceneObject], occ: Occupancy, poses: dict[str, Pose],
                 host: str, inst: str, placement: StartOn | StartInside) -> None:
    """Put ``inst`` at the place on ``host`` its placement gives (host frame)."""
    assert placement.offset is not None
    hobj, hpose = objs[host], poses[host]
    c, s = math.cos(hpose.yaw), math.sin(hpose.yaw)
    dx, dy = placement.offset
    x, y = hpose.pos[0] + c * dx - s * dy, hpose.pos[1] + s * dx + c * dy
    obj = objs[inst]
    pose = resting_pose(obj, x, y, rest_surface_z(hobj, hpose),
                        hpose.yaw + math.radians(placement.yaw_deg))
    if not placement_area(hobj, hpose).contains(np.array([x, y]))[0]:
        raise _Placement(inst, f"its given place ({dx:+.3f}, {dy:+.3f}) from {host!r}'s "
                         "centre is off that host", retry=False)
    blocked = _physical_overlaps(objs, obj, occ.blockers(obj, pose, ignore=[host],
                                                         clearance=0.0))
    if blocked:
        raise _Placement(inst, f"its given place on {host!r} overlaps {blocked}", retry=False)
    poses[inst] = pose
    occ.put(inst, obj, pose)


def _host_aligned_yaws(rng: np.random.Generator, k: int, host_yaw: float) -> np.ndarray:
    """``k`` candidate yaws for an object put on or inside a host: every other one
    random, the rest square to the host. A box that fits a container only square to
    its walls (a 10.5 cm container in a 15 cm one) is then found at once, not in the
    few random yaws close enough to square."""
    yaws = random_yaws(rng, k)
    yaws[1::2] = host_yaw + rng.integers(0, 4, size=len(yaws[1::2])) * (math.pi / 2)
    return yaws


def _place_on_host(objs: Mapping[str, SceneObject], rng: np.random.Generator, tries: int,
                   occ: Occupancy, poses: dict[str, Pose], host: str,
                   members: list[tuple[str, bool]], around: Iterable[str] = ()) -> None:
    """Put ``members`` (instance, inside?) on or in ``host``, side by side, else
    stacked; ``around``: bodies that enclose the host and are no obstacle to what
    is in it (a drawer's cabinet)."""
    hobj, hpose = objs[host], poses[host]
    # In a drawer, only where the open drawer shows it: the robot reaches it there.
    area = drawer_shown_area(hobj, hpose) if around else placement_area(hobj, hpose)
    surface = rest_surface_z(hobj, hpose)
    placed: list[str] = []
    for inst, _ in members:
        obj = objs[inst]
        pose = first_free(occ, obj, area_candidates(obj, area, surface, rng, tries,
                                                    _host_aligned_yaws(rng, tries, hpose.yaw)),
                          ignore=[host, *around], within=area)
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
        candidates = area_candidates(bottom, area, surface, rng, tries)
    else:  # larger than the top face: centred on it
        candidates = [resting_pose(bottom, *area.center, surface, a)
                      for a in random_yaws(rng, tries)]
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

