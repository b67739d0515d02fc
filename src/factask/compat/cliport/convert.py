"""Turn what a CLIPort task recorded (objects, goals) into a factask TaskGraph.

Rules (documented in docs/compat.md):

* one state variable per object id, named ``<kind>_<colour>_<index>``;
* ``category='fixed'`` -> a fixed variable; a goal's object is always movable;
* the recorded start pose -> ``AtFixedPose`` (x, y, yaw), or ``StartOn`` /
  ``StartInside`` when the object starts above the table on another object;
* one factor per ``add_goal``: ``pose`` -> ``AtPose`` (targets, ``matches``,
  ``rotations=False`` -> ``check_yaw=False``), ``zone`` -> ``InZone`` on the
  recorded region nearest to the zone pose (or a new fixed zone), with the
  author's own target for each object as its ``poses`` when every object has one
  inside the zone (a packing plan); goals are read by
  :mod:`factask.compat.cliport.goals`;
* a pushing task's zone goal over small blocks only -> a ``pile`` variable per colour and
  a ``PileInZone`` factor (:mod:`factask.compat.cliport.piles`);
* multibodies linked in a chain by constraints -> one ``rope`` variable, and a
  pose goal over its beads -> a ``RopeAlong`` on the beads' targets
  (:mod:`factask.compat.cliport.ropes`);
* weights = ``step_max_reward``, rescaled to sum to 1;
* the goals keep Ravens' queue: each factor comes ``after`` the one before it; a
  goal whose objects a later goal moves again is a **milestone** (it counts once
  achieved, as Ravens counts a popped goal), an object's last goal is a final
  factor that must hold at the end.
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

from factask.compat.cliport.errors import CliportImportError, NoGoals, Unsupported
from factask.compat.cliport.goals import (
    TARGET_DECIMALS,
    RecordedGoal,
    half_xy,
    read_goals,
    resting_heights,
    target_pose,
    zone_poses,
)
from factask.compat.cliport.grippers import Spatula
from factask.compat.cliport.lying import lay_down_cylinders
from factask.compat.cliport.piles import RAVENS_PILE_FRACTION, find_piles, pile_variables
from factask.compat.cliport.recorder import RecordedObject, Session
from factask.compat.cliport.ropes import find_ropes, rope_goal
from factask.compat.cliport.scoring import RavensGoal
from factask.compat.cliport.sharing import separate_targets, share_targets, zone_parts
from factask.compat.cliport.starts import (
    inside_footprint,
    on_table_as_given,
    placement,
    scatter_added_at_targets,
    separate_starts,
    settle,
)
from factask.compat.cliport.transforms import yaw_of_xyzw
from factask.graph.factors import SubtaskFactor
from factask.graph.taskgraph import Limits, TaskGraph
from factask.relations import AtPose, InZone, PileInZone, TargetPose
from factask.vocabulary.errors import GraphValidationError
from factask.vocabulary.kinds import WALL_THICKNESS, kind_spec
from factask.vocabulary.limits import MAX_OBJECTS
from factask.vocabulary.names import slugify, unique_name
from factask.vocabulary.tolerances import XY_TOLERANCE, YAW_TOLERANCE_DEG, Tolerances
from factask.vocabulary.variables import AtFixedPose, StateVariable
from factask.vocabulary.world import WORKSPACE_X, WORKSPACE_Y

#: Weights are rescaled silently when they sum to 1 within this; beyond it, with a warning.
WEIGHT_WARN_TOLERANCE = 1e-3
#: Receptacles with walls that the author's placements must clear.
WALLED_KINDS = ("container",)
#: Room left between a placement and a wall, metres.
WALL_CLEARANCE = 0.003
#: Longest factor name (the graph model allows 64 characters).
MAX_NAME = 48
#: How far (a fraction of the author's position tolerance) a target may be moved off
#: another it overlaps (:func:`separate_targets`); the rest stays the tolerance.
SEPARATE_LIMIT = 0.75
#: Colour of a zone variable created from a zone goal's params.
GOAL_ZONE_COLOR = "gray"



def kebab(class_name: str) -> str:
    """``StackBoxesColumn`` -> ``stack-boxes-column`` (GenSim's task names)."""
    words = re.sub(r"(?<=[a-z0-9])(?=[A-Z])|(?<=[A-Z])(?=[A-Z][a-z])", "-", class_name)
    name = re.sub(r"[^a-z0-9-]+", "-", words.lower()).strip("-")
    return name or "cliport-task"



# -------------------------------------------------------------- variables
def object_names(objects: list[RecordedObject]) -> dict[int, str]:
    counts: dict[str, int] = {}
    names = {}
    for o in objects:
        base = f"{o.kind}_{o.color}"
        names[o.obj_id] = f"{base}_{counts.get(base, 0)}"
        counts[base] = counts.get(base, 0) + 1
    return names


def _make_room(host: RecordedObject, goal: RecordedGoal, poses: list[Any],
               names: dict[int, str], warn: Any) -> None:
    """Grow a walled receptacle (centre kept) until the author's placements in it
    clear its walls.

    Ravens' container template has thin walls and its packing tasks fill it to 1 cm
    of its outer edge; factask's walls are :data:`WALL_THICKNESS` thick, so those
    placements would sit on the walls. The placements are facts; the walls move out.
    """
    yaw = yaw_of_xyzw(host.quat)
    c, s = math.cos(yaw), math.sin(yaw)
    need = np.array(host.size[:2], dtype=float) / 2
    for o, pose in zip(goal.objs, poses, strict=True):
        dx, dy = pose.x - float(host.pos[0]), pose.y - float(host.pos[1])
        local = np.abs([c * dx + s * dy, -s * dx + c * dy])
        half = np.array(half_xy(o.size, math.radians(pose.yaw_deg) - yaw))
        need = np.maximum(need, local + half + WALL_THICKNESS + WALL_CLEARANCE)
    grown = (float(2 * need[0]), float(2 * need[1]), host.size[2])
    if grown[:2] != host.size[:2]:
        warn(f"{names[host.obj_id]}: the author's placements reach its "
             f"{WALL_THICKNESS * 100:.0f} cm walls; grown from {host.size[0]:.3f} x "
             f"{host.size[1]:.3f} to {grown[0]:.3f} x {grown[1]:.3f} m (centre kept)")
        host.size = grown


def _zone_variable(goal: RecordedGoal, objects: list[RecordedObject], names: dict[int, str],
                   extra: list[StateVariable], warn: Any) -> str:
    zpos, zquat, (sx, sy) = goal.zones[0]
    if len(goal.zones) > 1:
        warn(f"goal {goal.index}: {len(goal.zones)} zones given; factask uses the first")
    moving = {o.obj_id for o in goal.objs}
    regions = [o for o in objects if kind_spec(o.kind).region and o.obj_id not in moving]
    if regions:
        near = min(regions, key=lambda o: float(np.linalg.norm(o.pos[:2] - zpos[:2])))
        if float(np.linalg.norm(near.pos[:2] - zpos[:2])) <= max(sx, sy) / 2:
            _check_region_size(near, (sx, sy), names, warn)
            return names[near.obj_id]
    taken = set(names.values()) | {v.name for v in extra}
    name = unique_name(f"zone_goal_{goal.index}", taken, MAX_NAME)
    x = float(np.clip(zpos[0], *WORKSPACE_X))
    y = float(np.clip(zpos[1], *WORKSPACE_Y))
    extra.append(StateVariable(
        name=name, description=f"zone of goal {goal.index} (from add_goal params)",
        kind="zone", size=(sx, sy, 0.001), color=GOAL_ZONE_COLOR, fixed=True,
        initial=AtFixedPose(x=x, y=y, yaw_deg=math.degrees(yaw_of_xyzw(zquat)))))
    warn(f"goal {goal.index}: no recorded zone at {tuple(round(float(c), 3) for c in zpos[:2])}; "
         f"added fixed zone variable {name!r} of size {sx:.3f} x {sy:.3f}")
    return name


def _check_region_size(region: RecordedObject, size: tuple[float, float],
                       names: dict[int, str], warn: Any) -> None:
    """Give a marker region (a zone: visual only in Ravens) the size of the zone goal
    that names it.

    Ravens draws ``zone/zone.urdf`` at 0.12 m whatever the task says, and checks the
    goal against the ``zone_size`` in its params (two 7 cm boxes fit a 15 cm zone,
    not the drawn 12 cm one). factask's zone is both drawing and check, so it takes
    the checked size. A region with walls or a top (a pallet, a container) keeps its
    size: there the object is the check. Two goals that check one marker with
    different sizes get the larger (a warning says so).
    """
    if kind_spec(region.kind).collides:
        return
    wanted = (float(size[0]), float(size[1]))
    resized = region.checked_size
    if resized is not None:
        if resized != wanted:
            wanted = (max(resized[0], wanted[0]), max(resized[1], wanted[1]))
            warn(f"{names[region.obj_id]}: zone goals check it at different sizes; "
                 f"using the larger, {wanted[0]:.3f} x {wanted[1]:.3f} m")
    elif any(abs(a - b) > 1e-4 for a, b in zip(wanted, region.size[:2], strict=True)):
        warn(f"{names[region.obj_id]}: drawn {region.size[0]:.3f} x {region.size[1]:.3f} m, "
             f"checked by its zone goal at {wanted[0]:.3f} x {wanted[1]:.3f} m (Ravens' "
             "zone_size); factask's zone is drawn and checked at the checked size")
    region.checked_size = wanted
    region.size = (wanted[0], wanted[1], region.size[2])


def _in_fixture_frame(poses: list[TargetPose], objects: list[RecordedObject],
                      names: dict[int, str], moved: set[int]
                      ) -> tuple[list[TargetPose], str | None]:
    """A pose goal whose every target lies in one fixture ("insert the block into the
    fixture"): its targets in that fixture's frame, and the fixture's name.

    The goal is then relative to the fixture, as the author meant, so the fixture's
    hollow is shaped for what goes into it (a block: square; was an ell, which a
    block cannot enter: it came to rest tilted on the hollow's edge). Targets in no
    fixture, or in several, stay in world coordinates.
    """
    fixtures = [o for o in objects if o.kind == "fixture" and o.obj_id not in moved]
    hosts = {next((f.obj_id for f in fixtures
                   if inside_footprint(np.array([p.x, p.y]), f)), None) for p in poses}
    if len(hosts) != 1 or None in hosts:
        return poses, None
    host = next(f for f in fixtures if f.obj_id in hosts)
    yaw = yaw_of_xyzw(host.quat)
    c, s = math.cos(yaw), math.sin(yaw)
    out = []
    for p in poses:
        dx, dy = p.x - float(host.pos[0]), p.y - float(host.pos[1])
        out.append(TargetPose(x=round(c * dx + s * dy, TARGET_DECIMALS),
                              y=round(-s * dx + c * dy, TARGET_DECIMALS),
                              z=None if p.z is None else round(p.z - float(host.pos[2]),
                                                               TARGET_DECIMALS),
                              yaw_deg=round((p.yaw_deg - math.degrees(yaw) + 180.0) % 360.0
                                            - 180.0, TARGET_DECIMALS)))
    return out, names[host.obj_id]


def _moved_again(goals: list[RecordedGoal]) -> set[int]:
    """Indices of the goals some of whose objects a later goal moves again."""
    later: set[int] = set()
    out: set[int] = set()
    for g in reversed(goals):
        ids = {o.obj_id for o in g.objs}
        if ids & later:
            out.add(g.index)
        later |= ids
    return out


def build_graph(task: Any, session: Session, class_name: str) -> tuple[TaskGraph,
                                                                       list[RavensGoal]]:
    """The task graph and Ravens goal queue of a task after its ``reset``.

    Args:
        task: The reset task instance.
        session: Its recording session (objects, warnings).
        class_name: The task class's name (gives the graph's name).

    Returns:
        (validated graph, ordered Ravens goals).

    Raises:
        CliportImportError: a goal cannot be expressed or the graph is invalid.
        Unsupported: a goal uses a metric or shape factask lacks.
    """
    warn = session.warn
    objects = list(session.objects.values())
    if not objects:
        raise CliportImportError("reset added no objects (env.add_object was never called)")
    goals = read_goals(task, session)
    if not goals:
        raise NoGoals("reset added no goals (add_goal was never called)")
    logs = lay_down_cylinders(objects, goals, warn)  # before names: they name the kind
    names = object_names(objects)
    scatter_added_at_targets(goals, names, warn)
    found = find_piles(task, goals, names)
    in_piles = {o.obj_id for p in found for o in p.blocks}
    piles = {g: [p.name for p in found if p.goal == g] for g in {p.goal for p in found}}
    ropes = find_ropes(session, names, warn)
    in_ropes = {oid for r in ropes for oid in r.ids}
    # The beads are the ropes' segments: no object of their own, host of nothing.
    objects = [o for o in objects if o.obj_id not in in_ropes]
    solid = sum(o.obj_id not in in_piles for o in objects)
    if solid > MAX_OBJECTS:  # before any goal is read into poses: one clear line
        raise CliportImportError(
            f"the task adds {solid} objects (besides piles and ropes); a factask scene "
            f"holds at most {MAX_OBJECTS} (factask.vocabulary.limits.MAX_OBJECTS): add fewer")
    if getattr(task, "ee", None) is Spatula and not piles:
        warn("the task asks for a spatula but has no pile to push; factask uses its "
             "suction cup")

    ravens = [RavensGoal(
        objects=[names[o.obj_id] for o in g.objs], symmetries=list(g.symmetries),
        matches=g.matches.tolist(),
        targets=[(float(p[0]), float(p[1]), float(p[2]), yaw_of_xyzw(q)) for p, q in g.targets],
        replace=g.replace, rotations=g.rotations, metric=g.metric,
        zones=[(float(p[0]), float(p[1]), float(p[2]), yaw_of_xyzw(q), sx, sy)
               for p, q, (sx, sy) in g.zones],
        max_reward=g.max_reward, language=g.language) for g in goals]

    symmetry: dict[int, float] = {}
    for g in goals:
        for o, sym in zip(g.objs, g.symmetries, strict=True):
            if o.obj_id not in logs:  # an upright cylinder's symmetry, about its axis
                symmetry[o.obj_id] = sym

    # Factors.
    tol = None
    pos_eps = float(getattr(task, "pos_eps", XY_TOLERANCE))
    rot_eps_deg = math.degrees(float(getattr(task, "rot_eps", math.radians(YAW_TOLERANCE_DEG))))
    if not (math.isclose(pos_eps, XY_TOLERANCE) and math.isclose(rot_eps_deg,
                                                                 YAW_TOLERANCE_DEG)):
        tol = Tolerances(xy=pos_eps, yaw_deg=rot_eps_deg)
    extra: list[StateVariable] = []
    taken = set(names.values())
    spacing: dict[int, float] = {}  # goal index -> distance between side-by-side copies
    for g in goals:
        rows = [i for i in range(len(g.objs)) if g.metric != "pose" or g.matches[i].any()]
        if len(rows) < len(g.objs):
            warn(f"goal {g.index}: {len(g.objs) - len(rows)} object(s) may go to no target "
                 "(a zero row of matches); they are left out")
            g.objs = [g.objs[i] for i in rows]
            g.matches = g.matches[rows, :]
        gap = share_targets(g, warn, spread=SEPARATE_LIMIT * pos_eps)
        if gap is not None and gap / 2 < pos_eps:
            spacing[g.index] = gap
            warn(f"goal {g.index}: its copies side by side are {gap * 1000:.1f} mm apart; "
                 f"position tolerance {gap / 2 * 1000:.1f} mm (was {pos_eps * 1000:.1f}), so "
                 "each object is within it of its own copy only")
    shifted = separate_targets([g for g in goals if not in_ropes & {o.obj_id for o in g.objs}],
                               SEPARATE_LIMIT * pos_eps)
    for index, shift in sorted(shifted.items()):
        warn(f"goal {index}: targets overlapping by a little moved apart to touch, by up "
             f"to {shift * 1000:.1f} mm; its position tolerance tightened by as much, to "
             f"{(pos_eps - shift) * 1000:.1f} mm (the check stays within the author's)")
    goal_objects = {o.obj_id for g in goals for o in g.objs}
    settle(objects, names, goal_objects, warn)
    given = [o for k, o in enumerate(objects) if o.obj_id not in in_piles
             and on_table_as_given(o, objects[:k] + objects[k + 1:], goal_objects)]
    separate_starts(given, {o.obj_id for o in given if o.obj_id in goal_objects or (
        o.category != "fixed" and kind_spec(o.kind).movable)}, names, warn)
    rest = resting_heights([g for g in goals if not in_ropes & {o.obj_id for o in g.objs}],
                           objects, goal_objects)
    drafts: list[tuple[RecordedGoal, Any]] = []
    for g in goals:
        if not g.objs:
            warn(f"goal {g.index} ({g.language!r}) has no objects left and is dropped")
            continue
        objs = [names[o.obj_id] for o in g.objs]
        extra_kw = {"tolerances": tol} if tol is not None else {}
        if g.index in shifted or g.index in spacing:
            xy = min(pos_eps - shifted.get(g.index, 0.0), spacing.get(g.index, math.inf) / 2)
            extra_kw = {"tolerances": Tolerances(xy=xy, yaw_deg=rot_eps_deg)}
        rope_rel = rope_goal(g, ropes, extra_kw) if in_ropes else None
        if rope_rel is not None:  # a rope's beads laid on their targets
            rel: Any = rope_rel
        elif g.metric == "pose":
            if len(g.objs) > len(g.targets):
                raise Unsupported(f"goal {g.index}: {len(g.objs)} objects but only "
                                  f"{len(g.targets)} target pose(s); factask gives every "
                                  "object its own target")
            tallest = max(o.size[2] for o in g.objs)
            poses = [target_pose(p, q, tallest, rest.get((g.index, j)),
                                 f"goal {g.index} target {j}", warn)
                     for j, (p, q) in enumerate(g.targets)]
            poses, frame = _in_fixture_frame(poses, objects, names, goal_objects)
            rel = AtPose(objects=objs, poses=poses, frame=frame,
                         matches=g.matches.tolist(), check_yaw=g.rotations, **extra_kw)
        elif g.index in piles:  # small blocks swept with a spatula: a pile per colour
            zone = _zone_variable(g, objects, names, extra, warn)
            taken.add(zone)
            rel = PileInZone(objects=piles[g.index], zone=zone,
                             fraction=RAVENS_PILE_FRACTION)
        else:  # one factor per zone (several zones: sorted by matches)
            for part in zone_parts(g, warn):
                zone = _zone_variable(part, objects, names, extra, warn)
                taken.add(zone)
                poses = zone_poses(part, rest, [e for e in goals if e.index < part.index])
                host = next((o for o in objects if names[o.obj_id] == zone), None)
                if poses and host is not None and host.kind in WALLED_KINDS:
                    _make_room(host, part, poses, names, warn)
                drafts.append((part, InZone(objects=[names[o.obj_id] for o in part.objs],
                                            zone=zone, poses=poses, **extra_kw)))
            continue
        drafts.append((g, rel))
    if not drafts:
        raise CliportImportError("no goal is left to check (every goal lost its objects)")

    weights = [g.max_reward for g, _ in drafts]
    if any(not math.isfinite(w) or w <= 0 for w in weights):
        warn("some step_max_reward values are not positive; every goal gets an equal share")
        weights = [1.0] * len(drafts)
    total = sum(weights)
    if abs(total - 1.0) > WEIGHT_WARN_TOLERANCE:
        why = " (after dropping goals)" if len(drafts) < len(goals) else ""
        warn(f"step_max_reward values sum to {total:.4g}{why}, not 1; rescaled to sum to 1")
    factors: list[SubtaskFactor] = []
    milestones = _moved_again([g for g, _ in drafts])
    for (g, rel), w in zip(drafts, weights, strict=True):
        name = unique_name(slugify(g.language, "_", MAX_NAME, "goal"), taken, MAX_NAME)
        factors.append(SubtaskFactor(name=name, description=g.language, goal=rel,
                                     weight=w / total, milestone=g.index in milestones,
                                     after=[factors[-1].name] if factors else []))
    # Fix rounding so the weights sum to exactly 1.
    drift = 1.0 - sum(f.weight for f in factors)
    factors[-1].weight = factors[-1].weight + drift

    # Variables.
    moved = {o.obj_id for g, _ in drafts for o in g.objs}
    variables = []
    for k, o in enumerate(objects):
        if o.obj_id in in_piles:
            continue
        name = names[o.obj_id]
        spec = kind_spec(o.kind)
        fixed = o.category == "fixed" or not spec.movable
        if o.obj_id in moved and fixed:
            if o.category == "fixed":
                warn(f"{name} was added as 'fixed' but a goal moves it; made movable")
            fixed = False
        sym = symmetry.get(o.obj_id)
        sym_deg = None
        if sym is not None:
            sym_deg = min(360.0, max(0.0, math.degrees(sym)))
        variables.append(StateVariable(
            name=name, description=f"{o.urdf} (CLIPort object {o.obj_id})", kind=o.kind,
            size=o.size, color=o.color, fixed=fixed, symmetry_deg=sym_deg,
            initial=placement(o, objects[:k] + objects[k + 1:], names, moved, warn)))
    variables.extend(pile_variables(found, warn))
    variables.extend(r.variable() for r in ropes)
    variables.extend(extra)

    max_steps = int(getattr(task, "max_steps", 0) or 0)
    limits = Limits(max_actions=min(max(max_steps, 1), 1000)) if max_steps else Limits()
    doc = (type(task).__doc__ or "").strip().splitlines()
    description = str(getattr(task, "lang_template", "") or (doc[0] if doc else ""))
    graph = TaskGraph(name=kebab(class_name), description=description, variables=variables,
                      factors=factors, limits=limits)
    try:
        graph.ensure_valid()
    except GraphValidationError as exc:
        raise CliportImportError(f"the imported graph is not valid:\n{exc}") from exc
    return graph, ravens
