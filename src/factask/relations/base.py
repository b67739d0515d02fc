"""The relation unit: one goal relation's schema, solving and checking in one class.

Every relation kind is one module of this package with one subclass of
:class:`RelationBase` (modelled on mink's ``tasks/``: one task type per file, a
small base class with the few methods every task implements):

* its **schema** — pydantic fields, pure data, the ``type`` literal that is its
  kind, and :attr:`RelationBase.anchor_fields` (which fields name the variables
  the goal is relative to, and what those variables must be able to do);
* :meth:`RelationBase.problems` — what validation checks beyond the schema;
* :meth:`RelationBase.solve` — target slots from the scene (a
  :class:`~factask.relations.solving.Plan`);
* :meth:`RelationBase.check` — which objects are placed, on which slot, and why
  the others are not (a :class:`~factask.relations.status.Verdict`);
  :meth:`RelationBase.status` turns it into the factor's
  :class:`~factask.relations.status.FactorStatus`, which is all the oracle needs.

Register a new kind in :mod:`factask.relations` (one line). A relation's
docstring is shown to LLMs verbatim in the prompts: keep it exact and short.
"""

from __future__ import annotations

import abc
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar, Literal

from pydantic import BaseModel, ConfigDict, Field

from factask.relations.solving import Plan, SolveContext, SolvedFactor
from factask.relations.status import CheckScene, FactorStatus, Verdict, factor_status
from factask.scene.objects import SceneObject
from factask.vocabulary.errors import Problem
from factask.vocabulary.kinds import kind_spec
from factask.vocabulary.names import Name
from factask.vocabulary.tolerances import Tolerances

if TYPE_CHECKING:  # the graph model sits above the relations (it imports their schemas)
    from factask.vocabulary.variables import StateVariable


def _or_kinds(kinds: Mapping[str, tuple[str, ...]], field: str) -> str:
    """", or a corner" for the kinds ``field`` accepts beyond its capabilities."""
    extra = kinds.get(field, ())
    return f", or a {' or '.join(extra)}" if extra else ""


@dataclass(frozen=True)
class Reserve:
    """Table an anchor keeps clear of other objects' starts: a rectangle in the frame
    of each instance of variable ``anchor`` (centre ``x``, ``y``; full extents
    ``size``), which must also lie inside the workspace. The layout sampler keeps it
    (:mod:`factask.sim.layout.sampling`) where a goal's slot has one place only, fixed by
    the anchor (in front of a box's hole), so random starts do not make it
    infeasible.
    """

    anchor: str
    x: float
    y: float
    size: tuple[float, float]


class RelationBase(BaseModel, abc.ABC):
    """A goal relation: the objects it moves, the anchors it is relative to, its
    tolerances, and how it is solved and checked."""

    model_config = ConfigDict(extra="forbid")

    #: Anchor field -> the kind capabilities (:class:`~factask.vocabulary.kinds.KindSpec`
    #: flags) its variable needs, any one of them; ``()`` accepts every kind.
    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {}
    #: Anchor field -> kinds it accepts besides those with its capabilities (a
    #: ``row`` runs along a corner marker's arm, though a corner is not a region).
    anchor_kinds: ClassVar[Mapping[str, tuple[str, ...]]] = {}

    #: The anchor field such that an object starting on or in its variable already
    #: meets the goal (``on``'s support, ``inside``'s container, ``in_zone``'s zone);
    #: None: no start placement meets it by itself.
    met_by_starting_in: ClassVar[str | None] = None

    #: The kinds of the variables this relation moves, when it moves only some kinds
    #: (``pile_in_zone`` pushes piles, ``open`` slides drawers); None: any movable
    #: kind that no relation claims. Validation and the reading both read it.
    moves_kinds: ClassVar[frozenset[str] | None] = None
    #: What to do instead when an object is not of :attr:`moves_kinds` (the fix).
    other_kinds_fix: ClassVar[str] = "choose another relation"
    #: Where a goal anchored to a variable this relation moves goes in the factor
    #: order (:mod:`factask.graph.order`): ``"after"`` it (it rests on where this goal
    #: leaves the variable), or ``"before"`` it (``closed``: what goes into a drawer
    #: goes in before it is shut).
    anchored_goals: ClassVar[Literal["after", "before"]] = "after"

    objects: list[Name] = Field(
        min_length=1, description="Variables this goal moves (all instances of each)."
    )
    tolerances: Tolerances = Field(default_factory=Tolerances)

    @classmethod
    def kind(cls) -> str:
        """The relation's kind: the value of its ``type`` field."""
        return str(cls.model_fields["type"].default)

    def anchor_names(self, field: str) -> list[str]:
        """The variables anchor field ``field`` names: none, one, or (a field that
        takes a list, such as ``row``'s ``on``) several.

        Args:
            field: One of :attr:`anchor_fields`.

        Returns:
            The names, in the order given.
        """
        value = getattr(self, field)
        if not value:
            return []
        return [value] if isinstance(value, str) else list(value)

    def anchors(self) -> list[str]:
        """Variables the goal is relative to (never moved by this goal)."""
        return list(dict.fromkeys(n for f in self.anchor_fields for n in self.anchor_names(f)))

    def variable_names(self) -> list[str]:
        """Every variable the relation mentions: objects first, then anchors."""
        seen: dict[str, None] = dict.fromkeys(self.objects)
        seen.update(dict.fromkeys(self.anchors()))
        return list(seen)

    def problems(self, factor: str, variables: Mapping[str, StateVariable]) -> list[Problem]:
        """What is wrong with this goal in a graph with these ``variables`` (beyond its
        schema): by default, anchors whose kind cannot serve their field.

        Args:
            factor: Name of the factor whose goal this is (the problems' node).
            variables: The graph's variables by name.
        """
        out = self._mover_kind_problems(factor, variables)
        for fname, caps in self.anchor_fields.items():
            for name in self.anchor_names(fname):
                if not caps or name not in variables:
                    continue
                v = variables[name]
                if v.kind in self.anchor_kinds.get(fname, ()):
                    continue
                spec = kind_spec(v.kind)
                if not any(getattr(spec, c) for c in caps):
                    out.append(Problem(factor, f"goal.{fname}",
                                       f"{name!r} is a {v.kind}, which cannot serve as {fname} "
                                       f"of '{self.kind()}' (needs a kind that is "
                                       f"{' or '.join(caps)}{_or_kinds(self.anchor_kinds, fname)})",
                                       "choose another variable or relation"))
        return out

    def _mover_kind_problems(self, factor: str,
                             variables: Mapping[str, StateVariable]) -> list[Problem]:
        """Objects whose kind this relation does not move (see :attr:`moves_kinds`)."""
        if self.moves_kinds is None:
            return []
        wanted = " or ".join(sorted(self.moves_kinds))
        return [Problem(factor, "goal.objects",
                        f"{name!r} is a {v.kind}; '{self.kind()}' moves only {wanted}",
                        self.other_kinds_fix)
                for name in self.objects
                if (v := variables.get(name)) is not None and v.kind not in self.moves_kinds]

    def met_at_start(self, variables: Mapping[str, StateVariable]) -> str | None:
        """The host every object of the goal starts on or in, when that start alone
        meets the goal (see :attr:`met_by_starting_in`); else None.

        Args:
            variables: The graph's variables by name.
        """
        if self.met_by_starting_in is None:
            return None
        anchors = set(self.anchor_names(self.met_by_starting_in))
        hosts = {_start_host(variables.get(o)) for o in self.objects}
        if len(hosts) == 1 and (host := hosts.pop()) in anchors:
            return host
        return None

    def met_at_start_problem(self, host: str) -> tuple[str, str]:
        """What validation says when :meth:`met_at_start` found ``host``: (message,
        fix). Relations whose start state is not a placement (a switch that starts
        on) say it in their own words.

        Args:
            host: What :meth:`met_at_start` returned.

        Returns:
            The problem's message and its fix.
        """
        return (f"met at the start: every object it moves starts on or in {host!r}, where "
                "the goal puts it",
                "start them elsewhere (initial: table), or choose another goal")

    def layout_reserves(self, variables: Mapping[str, StateVariable]) -> list[Reserve]:
        """Table the goal's anchors must keep clear at reset (see :class:`Reserve`);
        none by default: most slots are chosen among many spots.

        Args:
            variables: The graph's variables by name.
        """
        return []

    @classmethod
    @abc.abstractmethod
    def example(cls) -> tuple[list[dict[str, Any]], RelationBase]:
        """A small scene and goal that use this relation: (variable dicts, goal).

        Docs and the test that walks every registered relation through solve ->
        place -> check use it; it must solve from any seed's initial layout.
        """

    @abc.abstractmethod
    def solve(self, ctx: SolveContext, movers: list[SceneObject]) -> Plan:
        """Target slots for ``movers`` (the instances of :attr:`objects`, in order).

        Raises:
            Infeasible: no slots from these choices (``retry`` says if others may help).
        """

    @abc.abstractmethod
    def check(self, solved: SolvedFactor, scene: CheckScene) -> Verdict:
        """Which objects are placed (on which slot), and why the others are not."""

    def status(self, solved: SolvedFactor, scene: CheckScene) -> FactorStatus:
        """The factor's status from the current scene (see :func:`factor_status`).

        Raises:
            CheckError: a needed pose is missing or not finite.
        """
        return factor_status(solved, scene, self.check(solved, scene))


def _start_host(v: StateVariable | None) -> str | None:
    """The variable ``v`` starts on (``StartOn``) or in (``StartInside``), if any."""
    initial = getattr(v, "initial", None)
    return getattr(initial, "support", None) or getattr(initial, "container", None)
