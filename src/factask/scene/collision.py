"""The collision model of a scene and the free-spot searches built on it (pure numpy).

One rule decides whether objects collide, for the initial layout, for solved
targets and for the oracle's parking spots: two objects collide when their
footprints (grown by half the clearance each) overlap in XY **and** their height
intervals overlap; an object whose footprint lies inside a receptacle's inner
area only meets the receptacle's floor. Flat markers (zones, lines, corners) have
a height interval too, so nothing starts on top of them.

* :class:`Occupancy`: the objects in the scene as obstacles.
* :func:`first_free`, :func:`area_candidates`, :func:`table_spots`: bounded
  searches for a free pose (every search tries at most
  :data:`MAX_TRIES_PER_OBJECT` candidates).
* :func:`resting_on`, :func:`occupying`, :func:`parking_spot`: the questions a
  robot asks before it moves an object (what rests on it, what stands where it
  must go, where it can be put out of the way).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass

import numpy as np

from factask.geometry import Pose
from factask.scene.objects import (
    Area,
    SceneObject,
    bottom_z,
    floor_thickness,
    floor_top_z,
    footprint_corners,
    footprint_corners_batch,
    footprint_points,
    footprint_radius,
    obb_overlaps,
    placement_area,
    resting_pose,
    top_z,
    yaw_rotation_2d,
)
from factask.scene.shelf import SHELF_KIND, shelf_inner_area
from factask.vocabulary.errors import FactaskError
from factask.vocabulary.kinds import MAX_SHELF_LEVELS, shelf_level_top
from factask.vocabulary.world import TABLE_X, TABLE_Y, WORKSPACE_X, WORKSPACE_Y

#: Gap kept between footprints (metres): objects never start or land touching.
CLEARANCE = 0.01
#: Clearance for targets an author gave explicitly (``at_pose``): they may sit as
#: close as the author put them, touching, but never inside one another (metres).
GIVEN_CLEARANCE = -0.001
#: Candidate poses tried per object (or per column/row/circle) before giving up.
MAX_TRIES_PER_OBJECT = 200
#: Height intervals overlapping by less than this (metres) do not collide (resting).
Z_CONTACT_EPS = 1e-4
#: Candidates tested together (vectorised) before looking at the next ones.
_CHUNK = 25
#: Support name used for slots resting directly on the table.
TABLE = "table"

WORKSPACE_CENTER = np.array([(WORKSPACE_X[0] + WORKSPACE_X[1]) / 2,
                             (WORKSPACE_Y[0] + WORKSPACE_Y[1]) / 2])
WORKSPACE_HALF = np.array([(WORKSPACE_X[1] - WORKSPACE_X[0]) / 2,
                           (WORKSPACE_Y[1] - WORKSPACE_Y[0]) / 2])
#: The workspace as an area (what every object's footprint must stay inside).
WORKSPACE_AREA = Area(WORKSPACE_CENTER, 0.0, WORKSPACE_HALF)

#: The table top as an area (what a fixed object's footprint must stay on).
TABLE_AREA = Area(np.array([(TABLE_X[0] + TABLE_X[1]) / 2, (TABLE_Y[0] + TABLE_Y[1]) / 2]), 0.0,
                  np.array([(TABLE_X[1] - TABLE_X[0]) / 2, (TABLE_Y[1] - TABLE_Y[0]) / 2]))

#: Vertical slack (m) when deciding that one object rests on another.
REST_EPS = 0.01


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
    return _Body(obj, pose, footprint_points(obj, pose, covering=True), footprint_corners(obj, pose,
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

    def with_clearance(self, clearance: float) -> Occupancy:
        """The same bodies under another clearance."""
        other = Occupancy(clearance)
        for name, b in self._bodies.items():
            other.put(name, b.obj, b.pose)
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

    def free_mask(self, obj: SceneObject, poses: list[Pose], ignore: Iterable[str] = (),
                  solid_fixtures: bool = False) -> np.ndarray:
        """Bool (k,): which candidate poses of ``obj`` collide with no body.

        Args:
            obj: The object to place.
            poses: Candidate poses.
            ignore: Body names not to test against (e.g. the support it rests on).
            solid_fixtures: Nothing may lie inside a fixture's frame (a start on the
                table); otherwise a body inside it meets nothing (a goal's slot).
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
            if not self._pair_collides(obj, poses[ki], self._bodies[names[pi]],
                                       solid_fixtures):
                hit[ki, pi] = False
        return ~hit.any(axis=1)

    def _pair_collides(self, obj: SceneObject, pose: Pose, other: _Body,
                       solid_fixtures: bool = False) -> bool:
        # A shelf's box is mostly its levels, which are bodies of their own: what
        # lies wholly over them (inside its panels, no lower than a level's top can
        # be) meets them, never the shelf. Lower, it meets the shelf: the levels are
        # placed after what starts on the table, so the shelf stands in for them.
        if other.obj.kind == SHELF_KIND:
            return not _over_levels(other, _body(obj, pose, self.clearance))
        if obj.kind == SHELF_KIND:
            return not _over_levels(_body(obj, pose, self.clearance), other)
        if obj.is_round and other.obj.is_round:  # disks: exact, boxes are too coarse
            gap = float(np.linalg.norm(pose.pos[:2] - other.pose.pos[:2]))
            if gap >= footprint_radius(obj) + footprint_radius(other.obj) + self.clearance:
                return False
        elif obj.is_round or other.obj.is_round:
            # A disk and a box: the disk's square meets a turned box's corner where
            # the disk does not (a ring of blocks round a bowl).
            disk, disk_pose, box, box_pose = ((obj, pose, other.obj, other.pose) if obj.is_round
                                              else (other.obj, other.pose, obj, pose))
            gap = _distance_to_box(disk_pose.pos[:2], box, box_pose)
            if gap >= footprint_radius(disk) + self.clearance:
                return False
        # The candidate's footprint only for a receptacle pair (the boxes decided the rest).
        if other.obj.is_receptacle:
            return _receptacle_pair(other, _body(obj, pose, self.clearance), solid_fixtures)
        if obj.is_receptacle:
            return _receptacle_pair(_body(obj, pose, self.clearance), other, solid_fixtures)
        return True

    def blockers(self, obj: SceneObject, pose: Pose, ignore: Iterable[str] = (),
                 clearance: float | None = None) -> list[str]:
        """Names of the bodies ``obj`` at ``pose`` collides with.

        Args:
            obj: The object.
            pose: Its pose.
            ignore: Body names not to test against.
            clearance: The gap to keep instead of this occupancy's (0: only bodies
                that really overlap, e.g. for a pose an author gave).
        """
        ignored = set(ignore)
        out = []
        for name, b in self._bodies.items():
            if name in ignored:
                continue
            alone = Occupancy(self.clearance if clearance is None else clearance)
            if clearance is None:
                alone._bodies = {name: b}
            else:
                alone.put(name, b.obj, b.pose)
            if not bool(alone.free_mask(obj, [pose])[0]):
                out.append(name)
        return out


def _over_levels(shelf: _Body, other: _Body) -> bool:
    """Whether ``other`` lies wholly inside ``shelf``'s panels, no lower than its
    lowest level's top can be (with the most levels a shelf has)."""
    lowest = shelf.z0 + shelf_level_top(shelf.obj.size, MAX_SHELF_LEVELS, 0)
    return other.z0 >= lowest - Z_CONTACT_EPS and bool(
        shelf_inner_area(shelf.obj, shelf.pose).contains(other.raw).all())


def _distance_to_box(point: np.ndarray, box: SceneObject, pose: Pose) -> float:
    """Distance (m) from an XY point to a box's footprint at ``pose`` (0 inside)."""
    local = yaw_rotation_2d(-pose.yaw) @ (np.asarray(point, dtype=float) - pose.pos[:2])
    return float(np.linalg.norm(np.maximum(np.abs(local) - box.half_xy, 0.0)))


def _receptacle_pair(rec: _Body, other: _Body, solid_fixtures: bool = False) -> bool:
    """Collision of a receptacle with another body (which may sit inside it).

    With ``solid_fixtures``, a fixture (a floorless frame) admits nothing: its frame
    is walled up around a hollow shaped for one piece (an ell's hollow leaves most
    of its inner square solid), which only a goal puts there, never a start on the
    table."""
    if solid_fixtures and floor_thickness(rec.obj) == 0.0:
        return True
    area = placement_area(rec.obj, rec.pose)
    if bool(area.contains(other.raw).all()):
        floor_top = rec.z0 + floor_thickness(rec.obj)
        return (min(other.z1, floor_top) - max(other.z0, rec.z0)) > Z_CONTACT_EPS
    return True


def on_table(obj: SceneObject, pose: Pose) -> bool:
    """True if the object's footprint lies on the table top (nothing hangs off it)."""
    return bool(TABLE_AREA.contains(footprint_corners(obj, pose)).all())


def centre_in_workspace(pose: Pose) -> bool:
    """True if the pose's centre lies in the workspace (Ravens' rule for any pose)."""
    return bool(WORKSPACE_AREA.contains(pose.pos[None, :2]).all())


def in_workspace(obj: SceneObject, pose: Pose) -> bool:
    """True if the object's footprint lies inside the workspace."""
    return bool(WORKSPACE_AREA.contains(footprint_corners(obj, pose)).all())


# ============================================================ free-spot search
def random_yaws(rng: np.random.Generator, k: int) -> np.ndarray:
    """``k`` yaws uniform in [-pi, pi)."""
    return rng.uniform(-math.pi, math.pi, size=k)


def first_free(occ: Occupancy, obj: SceneObject, poses: list[Pose],
               ignore: Iterable[str] = (), within: Area | None = None,
               solid_fixtures: bool = False) -> Pose | None:
    """The first candidate inside the workspace (and ``within``) that is free
    (``solid_fixtures``: see :meth:`Occupancy.free_mask`)."""
    if not poses:
        return None
    corners = footprint_corners_batch(obj, np.array([p.pos[:2] for p in poses]),
                                      np.array([p.yaw for p in poses]))
    ok = WORKSPACE_AREA.contains(corners.reshape(-1, 2)).reshape(len(poses), 4).all(axis=1)
    for start in range(0, len(poses), _CHUNK):  # chunks: most objects fit early
        idx = [i for i in range(start, min(start + _CHUNK, len(poses))) if ok[i]]
        if within is not None:
            idx = [i for i in idx
                   if bool(within.contains(footprint_points(obj, poses[i], covering=True)).all())]
        if not idx:
            continue
        free = occ.free_mask(obj, [poses[i] for i in idx], ignore, solid_fixtures)
        hits = np.flatnonzero(free)
        if len(hits):
            return poses[idx[int(hits[0])]]
    return None


def area_candidates(obj: SceneObject, area: Area, surface: float, rng: np.random.Generator,
                    k: int, yaws: np.ndarray | None = None) -> list[Pose]:
    """``k`` random poses of ``obj`` resting at height ``surface`` inside ``area``."""
    local = rng.uniform(-1.0, 1.0, size=(k, 2)) * area.half
    xy = area.center + local @ yaw_rotation_2d(area.yaw).T
    yaw = random_yaws(rng, k) if yaws is None else yaws
    return [resting_pose(obj, x, y, surface, a) for (x, y), a in zip(xy, yaw, strict=True)]



def table_spots(rng: np.random.Generator, k: int) -> list[tuple[np.ndarray, float]]:
    """``k`` random (centre, yaw) spots over the whole workspace, yaw in [-pi/2, pi/2)."""
    xy = rng.uniform(WORKSPACE_CENTER - WORKSPACE_HALF, WORKSPACE_CENTER + WORKSPACE_HALF,
                     size=(k, 2))
    yaw = rng.uniform(-math.pi / 2, math.pi / 2, size=k)
    return list(zip(xy, yaw, strict=True))


# ===================================================== questions before a move
def resting_on(name: str, objects: Mapping[str, SceneObject],
               poses: Mapping[str, Pose]) -> list[str]:
    """Free objects resting directly on top of ``name``, highest first; for a free
    receptacle also what lies inside it (carried along, a loose thing slides and
    tips over under the carry's accelerations: it comes out first)."""
    me = objects[name]
    top = top_z(me, poses[name])
    mine = footprint_corners(me, poses[name])
    hollow = placement_area(me, poses[name]) if me.spec.receptacle and not me.fixed else None
    floor = floor_top_z(me, poses[name])
    out = []
    for other, obj in objects.items():
        if other == name or obj.fixed or not obj.collides:
            continue
        bottom = bottom_z(obj, poses[other])
        on_top = abs(bottom - top) < REST_EPS and bool(obb_overlaps(
            mine, footprint_corners(obj, poses[other]))[0, 0])
        inside = hollow is not None and floor - REST_EPS < bottom < top and bool(
            hollow.contains(poses[other].pos[None, :2])[0])
        if on_top or inside:
            out.append(other)
    return sorted(out, key=lambda o: -poses[o].pos[2])


def occupying(name: str, target: Pose, objects: Mapping[str, SceneObject],
              poses: Mapping[str, Pose], keep: Iterable[str] = ()) -> list[str]:
    """Free objects (other than ``name`` and ``keep``) in the space ``name`` takes at
    ``target``. A free receptacle whose hollow holds that space (inside its walls,
    above its floor) does not occupy it: it is where ``name`` goes."""
    kept = set(keep)
    me = objects[name]
    lo, hi = target.pos[2] - me.half[2], target.pos[2] + me.half[2]
    corners = footprint_corners(me, target, margin=-0.002)
    out = []
    for other, obj in objects.items():
        if other == name or other in kept or obj.fixed or not obj.collides:
            continue
        p = poses[other]
        if obj.spec.receptacle and lo >= floor_top_z(obj, p) - REST_EPS and bool(
                placement_area(obj, p).contains(corners).all()):
            continue
        if not (bottom_z(obj, p) < hi - REST_EPS and top_z(obj, p) > lo + REST_EPS):
            continue
        if me.is_round and obj.is_round:  # two disks: their boxes' corners are air
            if float(np.linalg.norm(target.pos[:2] - p.pos[:2])) < \
                    footprint_radius(me) + footprint_radius(obj) - 0.002:
                out.append(other)
        elif obb_overlaps(corners, footprint_corners(obj, p))[0, 0]:
            out.append(other)
    return out


def beneath(name: str, target: Pose, objects: Mapping[str, SceneObject],
            poses: Mapping[str, Pose]) -> list[str]:
    """Free objects (other than ``name``) under the footprint ``name`` takes at
    ``target``, wholly below it: what it would rest on, or hover over."""
    me = objects[name]
    bottom = target.pos[2] - me.half[2]
    corners = footprint_corners(me, target, margin=-0.002)
    return [other for other, obj in objects.items()
            if other != name and not obj.fixed and obj.collides
            and top_z(obj, poses[other]) <= bottom + REST_EPS
            and bool(obb_overlaps(corners, footprint_corners(obj, poses[other]))[0, 0])]


def parking_spot(name: str, objects: Mapping[str, SceneObject], poses: Mapping[str, Pose],
                 reserved: Iterable[tuple[SceneObject, Pose]], rng: np.random.Generator,
                 clearance: float, samples: int) -> Pose | None:
    """A free table spot for ``name``, ``clearance`` away from every object and every
    ``reserved`` (object, pose) footprint (e.g. targets), off every flat marker.

    Args:
        name: The object to put out of the way.
        objects: Every scene object by instance name.
        poses: Current pose of every instance.
        reserved: Footprints to keep clear of besides the objects (targets).
        rng: Random generator for the candidates.
        clearance: Gap kept to everything, metres.
        samples: Candidates tried at most.

    Returns:
        The pose (same yaw, resting on the table), or None if none was free.
    """
    obj = objects[name]
    others = [footprint_corners(o, poses[n], clearance)
              for n, o in objects.items() if n != name and o.collides]
    others += [footprint_corners(o, p, clearance) for o, p in reserved]
    # Regions (zones, lines) are not collisions but parking there would count.
    occupied = np.array(others + [footprint_corners(o, poses[n]) for n, o in objects.items()
                                  if not o.collides]).reshape(-1, 4, 2)
    margin = float(np.linalg.norm(obj.half_xy)) + 0.01
    for _ in range(samples):
        x = rng.uniform(WORKSPACE_X[0] + margin, WORKSPACE_X[1] - margin)
        y = rng.uniform(WORKSPACE_Y[0] + margin, WORKSPACE_Y[1] - margin)
        pose = Pose.from_xyz_yaw(x, y, obj.half[2], poses[name].yaw)
        if not obb_overlaps(footprint_corners(obj, pose), occupied).any():
            return pose
    return None


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


@dataclass(frozen=True)
class Deadline:
    """A time budget for a search (a reset must end in bounded time): wall-clock
    by default; a check that must give the same answer on a busy machine counts
    its thread's CPU time instead (``clock=time.thread_time``).

    Attributes:
        at: ``clock()`` value after which the search gives up.
        budget: The budget it was made with, seconds (for messages).
        clock: The clock (``time.monotonic``: wall).
    """

    at: float
    budget: float
    clock: Callable[[], float] = time.monotonic

    @classmethod
    def after(cls, seconds: float, clock: Callable[[], float] = time.monotonic) -> Deadline:
        """A deadline ``seconds`` from now on ``clock`` (``math.inf``: never)."""
        return cls(clock() + seconds, seconds, clock)

    @property
    def passed(self) -> bool:
        """Whether the budget is spent."""
        return self.clock() > self.at

    def check(self, what: str, last: str = "") -> None:
        """Raise if the budget is spent.

        Raises:
            LayoutError: naming ``what``, the budget and the last reason (not
                retryable: another layout would cost the same time again).
        """
        if self.passed:
            why = f"; last problem: {last}" if last else ""
            raise LayoutError(what, f"no layout within the {self.budget:g} s budget{why}",
                              retryable=False, fix="use fewer or smaller objects, or "
                              "give them more room")


#: A deadline that never passes.
NO_DEADLINE = Deadline(math.inf, math.inf)
