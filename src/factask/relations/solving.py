"""What relation solving works with: the context, a plan, the solved targets.

A relation's :meth:`~factask.relations.base.RelationBase.solve` proposes a
:class:`Plan` (target slots, what each rests on, which object may take which
slot) from a :class:`SolveContext` (the graph, the scene objects, their current
or already solved poses, the obstacles). :meth:`SolveContext.accept` holds every
plan to the same rules — inside the workspace, under its height, above the table,
free of obstacles and of the factor's other slots — and the solver driver
(:func:`factask.sim.layout.solving.solve_targets`) turns an accepted plan into a
:class:`SolvedFactor`, which the checks, the oracle and the env read.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np

from factask.geometry import Pose
from factask.scene.collision import (
    GIVEN_CLEARANCE,
    MAX_TRIES_PER_OBJECT,
    NO_DEADLINE,
    Deadline,
    Occupancy,
    centre_in_workspace,
    in_workspace,
    on_table,
    table_spots,
)
from factask.scene.objects import (
    GEOMETRY_EPS,
    Area,
    SceneObject,
    bottom_z,
    group_area,
    rest_surface_z,
    top_z,
)
from factask.vocabulary.errors import FactaskError
from factask.vocabulary.tolerances import Z_TOLERANCE
from factask.vocabulary.variables import VariableSet
from factask.vocabulary.world import TABLE_Z, WORKSPACE_Z


class Infeasible(FactaskError):
    """One solving attempt failed; ``retry`` says whether other random choices may help.

    The solver driver turns it into a :class:`~factask.vocabulary.errors.LayoutError`.
    """

    def __init__(self, reason: str, retry: bool = True) -> None:
        super().__init__(reason)
        self.reason, self.retry = reason, retry


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
class SolveContext:
    """What a relation solver sees.

    Attributes:
        graph: The task graph.
        objs: Scene objects by instance name.
        current: Pose of every instance: its start, or its target once solved.
        occ: Obstacles for targets (what stays where it is, and solved targets).
        rng: Random generator (free spots, phases, offsets).
        attempt: Index of this attempt; odd attempts pack by random spots instead of
            a grid.
        deadline: When the whole reset gives up (checked between candidate spots).
        placed: Instances an earlier factor already put at a target (their
            ``current`` pose is that target, not their start).
    """

    graph: VariableSet
    objs: dict[str, SceneObject]
    current: dict[str, Pose]
    occ: Occupancy
    rng: np.random.Generator
    attempt: int = 0
    deadline: Deadline = NO_DEADLINE
    placed: set[str] = field(default_factory=set)

    def inst(self, var: str) -> list[str]:
        """Instance names of variable ``var``."""
        return self.graph.variable(var).instances

    def anchor(self, var: str) -> tuple[Area, float, list[str]]:
        """Area, resting surface and instances of an anchor variable (a group if several)."""
        hosts = self.inst(var)
        hobjs = [self.objs[h] for h in hosts]
        hposes = [self.current[h] for h in hosts]
        area = group_area(hobjs, hposes)
        surface = max(rest_surface_z(o, p) for o, p in zip(hobjs, hposes, strict=True))
        return area, surface, hosts

    def accept(self, movers: list[SceneObject], plan: Plan) -> None:
        """Check a plan against the rules every target obeys.

        Raises:
            Infeasible: an assigned slot leaves the workspace, rises above its height,
                sinks into the table, or collides with an obstacle or another slot.
        """
        # Targets an author gave are facts: used as given, as close to one another as
        # they were put, and accepted wherever the object stands on the table with
        # its centre in the workspace (Ravens' rule); solved targets keep the
        # clearance and their whole footprint in the workspace.
        trial = self.occ.with_clearance(GIVEN_CLEARANCE) if plan.given else self.occ.copy()
        # The movers' own starts stay obstacles for their slots, so no object starts at
        # a target of its own goal (starts of objects other goals move do not count:
        # those objects are moved out of the way). An object an earlier factor already
        # placed may be sent to where it stands (a later goal that lists it again at
        # the same target: it stays): its own slot ignores its own body.
        for obj in movers:
            if obj.collides and obj.name not in self.placed:
                trial.put(f"@start:{obj.name}", obj, self.current[obj.name])
        for i, j in enumerate(plan.assignment):
            obj = movers[i]
            pose = plan.sized(j, obj)
            if plan.given and not (centre_in_workspace(pose) and on_table(obj, pose)):
                raise Infeasible(f"slot {j} for {obj.name} at ({pose.pos[0]:.3f}, "
                                 f"{pose.pos[1]:.3f}) is off the workspace or the table",
                                 retry=False)
            if not plan.given and not in_workspace(obj, pose):
                raise Infeasible(f"slot {j} for {obj.name} at ({pose.pos[0]:.3f}, "
                                 f"{pose.pos[1]:.3f}) leaves the workspace")
            top, bottom = top_z(obj, pose), bottom_z(obj, pose)
            if top > WORKSPACE_Z[1] + GEOMETRY_EPS:
                raise Infeasible(f"slot {j} puts the top of {obj.name} at {top:.3f} m, above "
                                 f"the workspace's {WORKSPACE_Z[1]:.2f} m", retry=False)
            if bottom < TABLE_Z - Z_TOLERANCE:
                raise Infeasible(f"slot {j} puts {obj.name} {TABLE_Z - bottom:.3f} m into "
                                 "the table", retry=False)
            ignore = plan.ignore[j] | ({obj.name} if obj.name in self.placed else set())
            if not trial.free_mask(obj, [pose], ignore)[0]:
                who = trial.blockers(obj, pose, ignore)
                raise Infeasible(f"slot {j} for {obj.name} collides with {who}")
            trial.put(f"@slot{j}", obj, pose)

    def search(self, movers: list[SceneObject], build: Callable[[np.ndarray, float], Plan],
               what: str, spots: list[tuple[np.ndarray, float]] | None = None) -> Plan:
        """Try spots (default: random ones on the table) until ``build(xy, yaw)`` gives
        an acceptable plan.

        Raises:
            Infeasible: no spot gave one (or a reason no spot can change).
        """
        last = "no candidate"
        for xy, yaw in spots if spots is not None else table_spots(self.rng,
                                                                    MAX_TRIES_PER_OBJECT):
            self.deadline.check(what, last)
            plan = build(xy, yaw)
            plan.random = True
            try:
                self.accept(movers, plan)
                return plan
            except Infeasible as exc:
                if not exc.retry:  # no other spot can help (too tall, too long, ...)
                    raise
                last = exc.reason
        raise Infeasible(f"no free spot on the table for {what} ({last})")


@dataclass
class Plan:
    """What a relation solver proposes (checked by :meth:`SolveContext.accept`).

    Attributes:
        slots: Target pose per slot (sized for the object nominally assigned to it).
        surfaces: Per slot, the resting height, or None for an explicit height.
        supports: Per slot, what the object rests on (instance name or ``TABLE``).
        ignore: Per slot, bodies the slot may overlap (its hosts).
        matches: Bool (n_objects, n_slots): which object may take which slot.
        assignment: The nominal slot of each object.
        region: Region/container instances (``in_zone`` / ``inside``).
        check_yaw: Whether yaw is checked.
        chain: Slots form a column: slot k counts only if slot k-1 does.
        support_group: The support instances (``on``, a stack on a base, ...).
        random: Made from random choices: another attempt may differ.
        given: The slots are an author's explicit targets (``at_pose``): see
            :meth:`SolveContext.accept`.
    """

    slots: list[Pose]
    surfaces: list[float | None]
    supports: list[str]
    ignore: list[set[str]]
    matches: np.ndarray
    assignment: list[int]
    region: list[str] = field(default_factory=list)
    check_yaw: bool = True
    chain: bool = False
    support_group: list[str] = field(default_factory=list)
    random: bool = False
    given: bool = False

    def sized(self, j: int, obj: SceneObject) -> Pose:
        """Where the centre of ``obj`` goes in slot ``j``."""
        s = self.surfaces[j]
        base = self.slots[j]
        if s is None:
            return base
        return Pose(np.array([base.pos[0], base.pos[1], s + obj.half[2]]), base.quat)


def make_plan(slots: list[Pose], surfaces: list[float | None], supports: list[str],
              ignore: list[set[str]], matches: np.ndarray, assignment: list[int] | None = None,
              **kw: object) -> Plan:
    """A :class:`Plan`; the nominal assignment defaults to object i -> slot i."""
    chosen = list(assignment) if assignment is not None else list(range(matches.shape[0]))
    return Plan(slots, surfaces, supports, ignore, matches, chosen, **kw)  # type: ignore[arg-type]


def same_variable(objs: list[SceneObject]) -> np.ndarray:
    """Matches of an *ordered* relation: the order is between variables; the identical
    instances of one variable are interchangeable (nobody can tell them apart)."""
    return np.array([[a.variable == b.variable for b in objs] for a in objs], dtype=bool)


def same_size(objs: list[SceneObject]) -> np.ndarray:
    """Matches of an unordered relation: any object may take the slot of one its size."""
    n = len(objs)
    return np.array([[np.allclose(objs[i].size, objs[j].size) for j in range(n)]
                     for i in range(n)], dtype=bool)
