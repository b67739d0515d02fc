"""LIBERO's articulated fixtures → factask's jointed kinds: a cabinet's drawers, a
microwave's hinged door, a stove's switch (:class:`ArticulatedParts`, the part of
the importer that reads them).

* Drawers: a cabinet type with drawer regions (:attr:`LiberoKind.drawers`) gets one
  ``drawer`` variable per region (``<cabinet>_<level>_drawer``, ``in_cabinet``, pulled
  out where ``:init`` says ``Open``); ``Open`` / ``Close`` of a drawer region are
  ``open`` / ``closed``; ``In`` / ``On`` a drawer region is ``inside`` the drawer.
* Doors: a ``microwave`` fixture gets a fixed ``microwave`` variable and a ``door``
  variable ``<microwave>_door`` (``in_cabinet`` of it, swung open where ``:init``
  says ``(Open microwave_1)``); ``(Open microwave_1)`` / ``(Close microwave_1)``
  are ``open`` / ``closed`` of the door (the predicate names the fixture, which maps
  to its door); ``In`` its ``heating_region`` is ``inside`` the microwave. A file
  that names none of these keeps the plain stand-in (:attr:`LiberoKind.plain`, a
  fixed box whose top is a support): factask's microwave has no roof, so "on top of
  the microwave" is a goal only there.
* Switches: a fixture of a switchable kind (a ``flat_stove`` → ``stove``) gets a
  ``switch`` variable ``<stove>_switch`` (``mounted_on`` it, on where ``:init`` says
  ``Turnon``); ``Turnon`` / ``Turnoff`` of the fixture are ``switched_on`` /
  ``switched_off`` of its switch.
* Shelf levels (not articulated, but parts of a fixture like a cabinet's drawers): a
  shelf type with level regions (:attr:`LiberoKind.levels`) gets one ``shelf_level``
  variable per level (``<shelf>_level_<k>``, ``in_cabinet`` of the stepped shelf);
  ``On`` / ``In`` a level region is ``on`` the level, in ``:init`` a start on it.
* A put into a drawer or microwave whose gate (the drawer, the door:
  :func:`~factask.vocabulary.variables.gates_of`) starts shut gets an ``open``
  milestone first (:meth:`ArticulatedParts.open_before_putting_inside`).

Every other moving part (a fridge's door, a slide cabinet's sliding door, a
window's sash, a faucet's handle: :attr:`LiberoKind.articulation`) is refused with
a :class:`LiberoUnsupported` naming what factask lacks.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from factask.compat.libero.kinds import LiberoKind, LiberoUnsupported, region_role
from factask.compat.libero.model import BddlProblem, Predicate
from factask.vocabulary.kinds import (
    DOOR_THICKNESS,
    HANDLE_DEPTH,
    SWITCH_HOSTS,
    door_size,
    drawer_size,
    drawer_travel,
    shelf_level_size,
    switch_size,
)
from factask.vocabulary.names import unique_name
from factask.vocabulary.variables import StateVariable, gates_of
from factask.vocabulary.world import WORKSPACE_X

#: Predicates of articulated fixtures.
ARTICULATION = frozenset({"open", "close", "turnon", "turnoff"})
#: ``Open`` / ``Close`` of a drawer or door → factask's relation.
OPEN_CLOSE = {"open": "open", "close": "closed"}
#: ``Turnon`` / ``Turnoff`` of a switchable fixture → factask's relation.
ON_OFF = {"turnon": "switched_on", "turnoff": "switched_off"}
#: Room (m) left between a drawer pulled all the way out (a door swung all the way
#: open) and the workspace's near edge.
DRAWER_ROOM = 0.005
#: What factask's jointed kinds model, for refusals.
WHAT_FACTASK_MODELS = ("factask models a cabinet's drawers (Open / Close), a microwave's "
                       "hinged door (Open / Close) and a stove's or lamp's push-button "
                       "switch (Turnon / Turnoff)")


class ArticulatedParts:
    """The importer's reading of drawers, doors and switches (a mixin of the
    importer: it uses the importer's problem, stand-ins and names)."""

    p: BddlProblem
    specs: dict[str, LiberoKind]
    types: dict[str, str]
    names: dict[str, str]
    taken_names: set[str]
    warnings: list[str]

    @property
    def where(self) -> str:
        """The file's name, for messages."""
        return Path(self.p.source).name

    def refuse(self, pred: Predicate | str, why: str) -> LiberoUnsupported:
        """A refusal naming the file and the predicate."""
        return LiberoUnsupported(f"{self.where}: {pred}: {why}")

    # ---- which stand-in, which parts ------------------------------------------------
    def target_of(self, arg: str) -> str:
        """The object or fixture a predicate's argument names (a region: its target)."""
        region = self.p.regions_by_full_name.get(arg)
        return region.target if region is not None else arg

    def uses_parts(self, libero: str) -> bool:
        """The file names ``libero``'s moving part: ``Open`` / ``Close`` / ``Turnon``
        / ``Turnoff`` of it, or one of its ``inside`` regions (a heating region)."""
        spec = self.specs[libero]
        for pred in (*self.p.init, *self.p.goal):
            for arg in (str(a) for a in pred.args):
                if pred.name in ARTICULATION and self.target_of(arg) == libero:
                    return True
                region = self.p.regions_by_full_name.get(arg)
                if region is not None and region.target == libero \
                        and region_role(spec, region.name) == "inside":
                    return True
        return False

    def plain_where_unused(self) -> None:
        """A fixture whose moving part the file never names keeps its plain stand-in
        (:attr:`LiberoKind.plain`)."""
        for libero, spec in list(self.specs.items()):
            if spec.plain is not None and not self.uses_parts(libero):
                self.specs[libero] = spec.plain

    def setup_parts(self) -> None:
        """Name the drawer, door and switch variables (after :attr:`names`)."""
        #: A cabinet's drawer region (full name) → (drawer variable, cabinet, level).
        self.drawers: dict[str, tuple[str, str, int]] = {}
        #: A shelf's level region (full name) → (level variable, shelf, level).
        self.levels: dict[str, tuple[str, str, int]] = {}
        #: A microwave (LIBERO name) → its door variable.
        self.doors: dict[str, str] = {}
        #: A switchable fixture (LIBERO name) → its switch variable.
        self.switches: dict[str, str] = {}
        #: Drawer or door variable → how far it starts open (``Open`` in ``:init``).
        self.openings: dict[str, float] = {}
        #: Switch variable → starts on (``Turnon`` in ``:init``).
        self.switched: dict[str, bool] = {}
        for libero, spec in self.specs.items():
            for level, region in enumerate(spec.drawers):
                word = region.removesuffix("_region")
                var = unique_name(f"{self.names[libero]}_{word}_drawer", self.taken_names)
                self.drawers[f"{libero}_{region}"] = (var, libero, level)
            level_vars = [unique_name(f"{self.names[libero]}_level_{k}", self.taken_names)
                          for k in range(spec.level_count)]
            for region, k in spec.levels:
                self.levels[f"{libero}_{region}"] = (level_vars[k], libero, k)
            if spec.levels:
                self.warnings.append(
                    f"{libero}: LIBERO's {self.types[libero]} stacks its levels under "
                    f"boards a top-down suction cup cannot reach under; it is factask's "
                    f"stepped shelf of {spec.level_count} levels rising away from the "
                    "robot, each open from above (level 0, the lowest, in front: "
                    + ", ".join(f"{r} is level {k}" for r, k in spec.levels) + ")")
            if spec.kind == "microwave":
                self.doors[libero] = unique_name(f"{self.names[libero]}_door",
                                                 self.taken_names)
            if spec.kind in SWITCH_HOSTS:
                self.switches[libero] = unique_name(f"{self.names[libero]}_switch",
                                                    self.taken_names)

    def faces_robot(self, libero: str) -> bool:
        """A fixture whose moving part is on its -x side (drawers, a door, a switch's
        control strip) or a stepped shelf (its lowest level at its -x side): turned to
        face the robot whatever LIBERO's yaw."""
        spec = self.specs[libero]
        return (bool(spec.drawers) or bool(spec.levels) or libero in self.doors
                or libero in self.switches)

    def room_in_front(self, obj: str, size: tuple[float, float, float], x: float) -> float:
        """A cabinet's or microwave's x moved away from the robot, where needed, so that
        its drawers pulled all the way out (its door swung all the way open) stay on
        the workspace: they move towards -x."""
        drawers = self.specs[obj].drawers
        if drawers:
            reach = size[0] / 2 + HANDLE_DEPTH + drawer_travel(drawer_size(size, len(drawers)))
        elif obj in self.doors:  # the door swung a quarter turn out about its -y edge
            reach = size[0] / 2 + DOOR_THICKNESS + door_size(size)[1]
        else:
            return x
        least = WORKSPACE_X[0] + reach + DRAWER_ROOM
        if x >= least:
            return x
        what = "drawers pulled out stay" if drawers else "door swung open stays"
        self.warnings.append(f"{obj}: moved from x {x:.3f} to {least:.3f} m so that its "
                             f"{what} on the workspace")
        return min(least, WORKSPACE_X[1] - size[0] / 2)

    # ---- init and goal --------------------------------------------------------------
    def read_part_init(self, pred: Predicate) -> bool:
        """``Open`` / ``Close`` / ``Turnon`` / ``Turnoff`` in ``:init``: the drawer's or
        door's opening, the switch's start. False when ``pred`` is no such predicate.

        Raises:
            LiberoUnsupported: a part factask does not model, or the predicate does
                not fit the fixture (a stove said to start open).
        """
        if pred.name not in ARTICULATION:
            return False
        arg = str(pred.args[0]) if len(pred.args) == 1 else ""
        target = self.target_of(arg)
        if pred.name in OPEN_CLOSE and arg in self.drawers:
            self.openings[self.drawers[arg][0]] = 1.0 if pred.name == "open" else 0.0
        elif pred.name in OPEN_CLOSE and target in self.doors:
            self.openings[self.doors[target]] = 1.0 if pred.name == "open" else 0.0
        elif pred.name in ON_OFF and target in self.switches:
            self.switched[self.switches[target]] = pred.name == "turnon"
        else:
            self.start_state_not_modelled(pred)
        return True

    def start_state_not_modelled(self, pred: Predicate) -> None:
        """``(Open short_fridge_1)`` in ``:init`` of a fixture whose moving part factask
        does not model (:attr:`LiberoKind.articulation`): the stand-in (a fixed box)
        has no such state; a goal that needs it is refused, a start state alone only
        warns (the task may not touch that fixture).

        Raises:
            LiberoUnsupported: the fixture has no such moving part (a cabinet said to
                start open, a stove said to start open).
        """
        target = self.target_of(str(pred.args[0]) if len(pred.args) == 1 else "")
        spec = self.specs.get(target)
        if spec is None or not spec.articulation:
            raise self.refuse_articulation(pred)
        self.warnings.append(f"{pred}: the {self.types[target]}'s {spec.articulation} is "
                             "not modelled; its stand-in ignores this start state")

    def part_goal(self, pred: Predicate, taken: set[str]) -> dict[str, Any] | None:
        """The factor of an ``Open`` / ``Close`` / ``Turnon`` / ``Turnoff`` goal; None
        when ``pred`` is none of these.

        Raises:
            LiberoUnsupported: a part factask does not model, or a switch that starts
                as the goal asks (nothing to do).
        """
        if pred.name not in ARTICULATION:
            return None
        arg = str(pred.args[0]) if len(pred.args) == 1 else ""
        target = self.target_of(arg)
        if pred.name in OPEN_CLOSE and (arg in self.drawers or target in self.doors):
            part = self.drawers[arg][0] if arg in self.drawers else self.doors[target]
            relation = OPEN_CLOSE[pred.name]
        elif pred.name in ON_OFF and target in self.switches:
            part, relation = self.switches[target], ON_OFF[pred.name]
            if self.switched.get(part, False) == (pred.name == "turnon"):
                state = "on" if pred.name == "turnon" else "off"
                raise self.refuse(pred, f"{target} starts switched {state} (its :init): the "
                                  "goal holds before the robot acts")
        else:
            raise self.refuse_articulation(pred)
        word = {"open": "open", "closed": "close", "switched_on": "switch_on",
                "switched_off": "switch_off"}[relation]
        return {"name": unique_name(f"{word}_{part}", taken),
                "description": f"LIBERO goal {pred}",
                "goal": {"type": relation, "objects": [part]}}

    def refuse_articulation(self, pred: Predicate) -> LiberoUnsupported:
        """``Open``, ``Close``, ``Turnon``, ``Turnoff`` of what factask does not model:
        the message names the fixture's moving part and what factask models."""
        target = self.target_of(str(pred.args[0]) if pred.args else "")
        spec = self.specs.get(target)
        if spec is not None and spec.articulation:
            what = f"the {self.types[target]}'s {spec.articulation} is not modelled"
        elif spec is not None:
            what = f"the {self.types[target]} ({target}) has no part {pred.name} moves"
        else:
            what = f"{target!r} is no declared fixture"
        return self.refuse(pred, f"{pred.name}: {what}; {WHAT_FACTASK_MODELS}")

    def open_before_putting_inside(self, factors: list[dict[str, Any]], taken: set[str]
                                   ) -> None:
        """A goal that puts something into a drawer or microwave whose gate (the drawer
        itself, the microwave's door: :func:`~factask.vocabulary.variables.gates_of`)
        starts shut needs it opened first: LIBERO's goal names only the end (``In bowl
        top_region``), its language the steps ("open the top drawer and put the bowl
        inside"). Such a gate gets an ``open`` milestone before the put (a ``Close``
        goal of it then comes after the put), unless a goal opens it already."""
        gates = gates_of([StateVariable.model_validate(v) for v in self.part_variables()])
        for f in list(factors):
            goal = f["goal"]
            if goal["type"] != "inside":
                continue
            for gate in gates.get(goal["container"], []):
                if self.openings.get(gate, 0.0) > 0.0 or any(
                        g["goal"]["type"] == "open" and gate in g["goal"]["objects"]
                        for g in factors):
                    continue
                name = unique_name(f"open_{gate}", taken)
                factors.insert(factors.index(f), {
                    "name": name, "milestone": True,
                    "description": f"open {gate} first (it starts shut)",
                    "goal": {"type": "open", "objects": [gate]}})
                self.warnings.append(f"{gate}: starts shut and a goal puts something in "
                                     f"{goal['container']}: an 'open' milestone ({name}) "
                                     "comes first")
                for g in factors:
                    if g["goal"]["type"] == "closed" and gate in g["goal"]["objects"]:
                        g.setdefault("after", []).append(f["name"])

    # ---- the variables --------------------------------------------------------------
    def part_variables(self) -> list[dict[str, Any]]:
        """The drawer, shelf level, door and switch variables."""
        out: list[dict[str, Any]] = []
        for var, libero, level in self.drawers.values():
            spec = self.specs[libero]
            assert spec.size is not None
            out.append({
                "name": var, "kind": "drawer", "color": spec.color,
                "size": list(drawer_size(spec.size, len(spec.drawers))),
                "initial": {"type": "in_cabinet", "cabinet": self.names[libero],
                            "level": level, "opening": self.openings.get(var, 0.0)},
                "description": f"drawer {level} (bottom 0) of {libero}: LIBERO region "
                               f"{spec.drawers[level]}"})
        seen: set[str] = set()
        for var, libero, level in self.levels.values():
            spec = self.specs[libero]
            assert spec.size is not None
            if var in seen:
                continue
            seen.add(var)
            regions = [r for r, k in spec.levels if k == level]
            out.append({
                "name": var, "kind": "shelf_level", "color": spec.color,
                "size": list(shelf_level_size(spec.size, spec.level_count, level)),
                "initial": {"type": "in_cabinet", "cabinet": self.names[libero],
                            "level": level},
                "description": f"level {level} (lowest 0) of the stepped shelf {libero}: "
                               f"LIBERO region {' and '.join(regions)}"})
        for libero, var in self.doors.items():
            spec = self.specs[libero]
            assert spec.size is not None
            out.append({
                "name": var, "kind": "door", "color": spec.color,
                "size": list(door_size(spec.size)),
                "initial": {"type": "in_cabinet", "cabinet": self.names[libero],
                            "level": 0, "opening": self.openings.get(var, 0.0)},
                "description": f"the hinged door of {libero} (LIBERO Open / Close {libero})"})
        for libero, var in self.switches.items():
            spec = self.specs[libero]
            assert spec.kind is not None
            out.append({
                "name": var, "kind": "switch", "color": "red",
                "size": list(switch_size(spec.kind)),
                "initial": {"type": "mounted_on", "host": self.names[libero],
                            "on": self.switched.get(var, False)},
                "description": f"the switch of {libero} (LIBERO Turnon / Turnoff {libero})"})
        return out
