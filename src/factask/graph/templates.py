"""Reuse: subtask templates, renaming, composition and extraction.

* A :class:`SubtaskTemplate` is a parametrised fragment: factors whose goals name
  *slots*; :meth:`SubtaskTemplate.instantiate` binds every slot to a task's
  variable (or, for ``many`` slots, a list of variables) and returns a fragment —
  itself a :class:`TaskGraph` — holding the bound variables and the factors.
* :func:`compose` joins graphs/fragments into one task. Variables with the same
  name are *the same variable* and must be defined identically; use ``rename``
  to keep apart or to identify variables explicitly. Weights are rescaled so that
  each input keeps its share (proportional to its number of factors by default).
* :func:`extract_template` turns one factor of a graph, with its scope, back into
  a template; :func:`extract_fragment` into a one-factor graph.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from factask.graph.factors import SubtaskFactor
from factask.graph.taskgraph import Limits, TaskGraph, problems_from_pydantic
from factask.relations import ANCHOR_FIELDS
from factask.vocabulary.errors import CompositionError, GraphValidationError, Problem
from factask.vocabulary.kinds import AssetKind
from factask.vocabulary.names import Name, TaskName
from factask.vocabulary.variables import START_REFERENCE_FIELDS, StateVariable

#: Fields of relations (their anchors) and of start placements that hold a
#: variable name (or, for a list anchor such as ``row``'s ``on``, a list of names):
#: ``cabinet`` is a drawer's ``in_cabinet`` start.
_NAME_FIELDS = tuple(dict.fromkeys((*ANCHOR_FIELDS, *START_REFERENCE_FIELDS)))


def _rename_value(value: Any, mapping: Mapping[str, str]) -> Any:
    """Recursively rename variable/factor references in a dumped model."""
    if isinstance(value, dict):
        out = {}
        for k, v in value.items():
            if k in _NAME_FIELDS and isinstance(v, str):
                out[k] = mapping.get(v, v)
            elif k in (*_NAME_FIELDS, "objects", "scope", "after", "slots_used") and \
                    isinstance(v, list):  # a list anchor (row's ``on``) or a list of names
                out[k] = [mapping.get(x, x) if isinstance(x, str) else x for x in v]
            elif k == "name" and isinstance(v, str):
                out[k] = mapping.get(v, v)
            else:
                out[k] = _rename_value(v, mapping)
        return out
    if isinstance(value, list):
        return [_rename_value(v, mapping) for v in value]
    return value


def rename(graph: TaskGraph, mapping: Mapping[str, str]) -> TaskGraph:
    """Rename variables and/or factors everywhere they are referenced.

    Args:
        graph: The graph (or fragment).
        mapping: old name -> new name (variables and factors share one namespace).

    Returns:
        A new graph; ``graph`` is unchanged.
    """
    data = graph.model_dump(mode="python", exclude_none=True)
    data["variables"] = _rename_value(data["variables"], mapping)
    data["factors"] = _rename_value(data["factors"], mapping)
    return TaskGraph.model_validate(data)


def empty_graph(name: str = "empty") -> TaskGraph:
    """A graph with no variables and no factors (the identity of :func:`compose`)."""
    return TaskGraph(name=name)


def compose(
    *graphs: TaskGraph,
    name: str | None = None,
    description: str | None = None,
    renames: Sequence[Mapping[str, str] | None] | None = None,
    shares: Sequence[float] | None = None,
) -> TaskGraph:
    """Compose graphs (or fragments) into one graph.

    Args:
        graphs: The inputs, in order (their factors keep this order).
        name: Name of the result; default the first input's name.
        description: Description; default the inputs' descriptions joined.
        renames: Per input, an optional old -> new name mapping applied first.
            Variables that end up with the same name are identified (shared).
        shares: Per input, its share of the total reward; default proportional to
            its number of factors (so composing with an empty graph changes
            nothing, and composition is associative).

    Returns:
        The composed graph. It is not validated as a whole (a fragment may still
        lack variables another fragment brings); call ``ensure_valid()`` on the result.

    Raises:
        CompositionError: two inputs define the same variable differently, two
            factors share a name, or the arguments do not line up.
    """
    if not graphs:
        return empty_graph(name or "empty")
    if renames is not None and len(renames) != len(graphs):
        raise CompositionError(f"renames has {len(renames)} entries for {len(graphs)} graphs")
    if shares is not None and len(shares) != len(graphs):
        raise CompositionError(f"shares has {len(shares)} entries for {len(graphs)} graphs")
    inputs = [
        rename(g, renames[i]) if renames is not None and renames[i] else g
        for i, g in enumerate(graphs)
    ]
    n_total = sum(len(g.factors) for g in inputs)
    if shares is None:
        shares = [len(g.factors) / n_total if n_total else 0.0 for g in inputs]
    else:
        total_share = sum(s for g, s in zip(inputs, shares, strict=True) if g.factors)
        if total_share <= 0:
            raise CompositionError("shares of the inputs with factors must add up to > 0")
        shares = [s / total_share for s in shares]

    variables: dict[str, StateVariable] = {}
    origin: dict[str, str] = {}
    factors: list[SubtaskFactor] = []
    factor_origin: dict[str, str] = {}
    for g, share in zip(inputs, shares, strict=True):
        for v in g.variables:
            if v.name in variables and variables[v.name] != v:
                a, b = variables[v.name], v
                diff = [k for k in type(v).model_fields if getattr(a, k) != getattr(b, k)]
                raise CompositionError(
                    f"variable {v.name!r} is defined differently in {origin[v.name]!r} and "
                    f"{g.name!r} (fields: {', '.join(diff)}); rename one of them, or define "
                    "the shared variable identically"
                )
            if v.name not in variables:
                variables[v.name] = v
                origin[v.name] = g.name
        g_total = sum(f.weight for f in g.factors) or 1.0
        scale = share / g_total
        if abs(scale - 1.0) < 1e-9:
            scale = 1.0  # keep weights bit-identical when the share does not change
        for f in g.factors:
            if f.name in factor_origin:
                raise CompositionError(
                    f"factor {f.name!r} exists in both {factor_origin[f.name]!r} and {g.name!r}; "
                    "rename one of them (renames=...)"
                )
            factor_origin[f.name] = g.name
            factors.append(f if scale == 1.0 else f.model_copy(update={"weight": f.weight * scale}))
    # Inputs with nothing in them (the empty graph) do not affect name or limits.
    substantial = [g for g in inputs if g.factors or g.variables] or inputs
    with_factors = [g for g in substantial if g.factors] or substantial
    budgets = [g.limits.max_actions for g in with_factors]
    if len(with_factors) == 1:
        limits = with_factors[0].limits
    else:
        limits = Limits(
            max_actions=None if None in budgets else sum(b for b in budgets if b is not None),
            max_sim_seconds_per_action=max(
                g.limits.max_sim_seconds_per_action for g in with_factors
            ),
        )
    return TaskGraph(
        name=name or substantial[0].name,
        description=description
        if description is not None
        else " ".join(g.description for g in inputs if g.description),
        variables=list(variables.values()),
        factors=factors,
        limits=limits,
    )


class TemplateSlot(BaseModel):
    """A placeholder for a task variable in a :class:`SubtaskTemplate`.

    Attributes:
        name: Slot name, used in the template's goals in place of a variable.
        description: What the slot stands for.
        kinds: Asset kinds that may be bound (None: any kind).
        many: The slot binds an ordered list of variables (e.g. a stack's layers).
        movable: Bound variables must be free (True), fixed (False) or either (None).
    """

    model_config = ConfigDict(extra="forbid")

    name: Name
    description: str = ""
    kinds: list[AssetKind] | None = None
    many: bool = False
    movable: bool | None = None


class SubtaskTemplate(BaseModel):
    """A reusable, parametrised subtask: factors over slots.

    Factor descriptions may use ``{slot}`` placeholders, replaced by the bound
    variables' names in words ("the {objects} in the {zone}" -> "the red block in
    the green zone").
    """

    model_config = ConfigDict(extra="forbid")

    name: Name
    description: str = ""
    slots: list[TemplateSlot] = Field(min_length=1)
    factors: list[SubtaskFactor] = Field(min_length=1)

    def slot(self, name: str) -> TemplateSlot:
        for s in self.slots:
            if s.name == name:
                return s
        raise CompositionError(f"template {self.name!r} has no slot {name!r}; slots: "
                               f"{[s.name for s in self.slots]}")

    def instantiate(
        self,
        prefix: str | None = None,
        after: Sequence[str] = (),
        milestone: bool | None = None,
        **bindings: StateVariable | Sequence[StateVariable],
    ) -> TaskGraph:
        """Bind every slot to task variables and return the fragment.

        Args:
            prefix: Suffix added to factor names to keep instances apart; default
                the name of the first variable bound.
            after: Factor names (of other fragments) this fragment's factors come after.
            milestone: Make every factor a milestone (True) or a final goal (False);
                None keeps the template's own choice.
            **bindings: slot name -> variable (or list of variables for ``many`` slots).

        Returns:
            A fragment graph with the bound variables and the renamed factors
            (weights sum to 1).

        Raises:
            CompositionError: a slot is unbound, unknown, or bound to a variable of
                the wrong kind.
        """
        problems: list[Problem] = []
        slot_names = [s.name for s in self.slots]
        for key in bindings:
            if key not in slot_names:
                problems.append(Problem(self.name, key, "no such slot", f"use {slot_names}"))
        bound: dict[str, list[StateVariable]] = {}
        for s in self.slots:
            if s.name not in bindings:
                problems.append(Problem(self.name, s.name, "slot not bound",
                                        f"pass {s.name}=<StateVariable>"))
                continue
            value = bindings[s.name]
            vs = [value] if isinstance(value, StateVariable) else list(value)
            if not vs or (not s.many and len(vs) != 1):
                problems.append(Problem(self.name, s.name, "needs exactly one variable"
                                        if not s.many else "needs at least one variable",
                                        "bind it accordingly"))
                continue
            for v in vs:
                if not isinstance(v, StateVariable):
                    problems.append(Problem(self.name, s.name, f"bound to {type(v).__name__}",
                                            "bind StateVariable objects"))
                elif s.kinds is not None and v.kind not in s.kinds:
                    problems.append(Problem(self.name, s.name, f"{v.name!r} is a {v.kind}; "
                                            f"slot accepts {s.kinds}", "bind another variable"))
                elif s.movable is not None and (not v.is_fixed) != s.movable:
                    want = "free" if s.movable else "fixed"
                    problems.append(Problem(self.name, s.name, f"{v.name!r} must be {want}",
                                            f"set fixed={not s.movable}"))
            bound[s.name] = vs
        if problems:
            raise CompositionError(str(GraphValidationError(problems, "template binding")))

        first = bound[self.slots[0].name][0].name
        suffix = prefix if prefix is not None else first
        words = {k: " and ".join(v.name.replace("_", " ") for v in vs) for k, vs in bound.items()}

        def expand(names: list[str]) -> list[str]:
            out: list[str] = []
            for n in names:
                out.extend(v.name for v in bound[n]) if n in bound else out.append(n)
            return out

        def one(name: str | None) -> str | None:
            if name is None or name not in bound:
                return name
            return bound[name][0].name

        total = sum(f.weight for f in self.factors)
        local = {f.name: f"{f.name}_{suffix}" if suffix else f.name for f in self.factors}
        factors = []
        for f in self.factors:
            goal = f.goal.model_dump(mode="python", exclude_none=True)
            goal["objects"] = expand(goal["objects"])
            for field in _NAME_FIELDS:
                if isinstance(goal.get(field), str):
                    goal[field] = one(goal[field])
                elif isinstance(goal.get(field), list):  # a list anchor: every bound variable
                    names = expand(goal[field])
                    goal[field] = names[0] if len(names) == 1 else names
            data = f.model_dump(mode="python", exclude_none=True)
            data.update(
                name=local[f.name],
                goal=goal,
                scope=expand(f.scope_names),
                weight=f.weight / total,
                after=[local.get(a, a) for a in f.after] + list(after),
                description=_fill(f.description, words),
                initial_setup=_fill(f.initial_setup, words),
                template=self.name,
            )
            if milestone is not None:
                data["milestone"] = milestone
            try:
                factors.append(SubtaskFactor.model_validate(data))
            except ValidationError as exc:
                raise CompositionError(
                    str(GraphValidationError(problems_from_pydantic(exc, data),
                                             f"instance of template {self.name!r}"))
                ) from None
        variables: dict[str, StateVariable] = {}
        for vs in bound.values():
            for v in vs:
                variables.setdefault(v.name, v)
        return TaskGraph(
            name=self.name.replace("_", "-"),
            description=_fill(self.description, words),
            variables=list(variables.values()),
            factors=factors,
        )


def _fill(text: str, words: Mapping[str, str]) -> str:
    for k, v in words.items():
        text = text.replace("{" + k + "}", v)
    return text


def extract_template(graph: TaskGraph, factor: str, name: str | None = None) -> SubtaskTemplate:
    """Turn one factor of ``graph`` and its scope into a reusable template.

    Each scope variable becomes a slot of the same name that accepts the same kind.

    Raises:
        GraphValidationError: no such factor.
    """
    f = graph.factor(factor)
    slots = []
    for vname in f.scope_names:
        v = graph.variable(vname)
        slots.append(TemplateSlot(name=vname, description=v.description, kinds=[v.kind]))
    return SubtaskTemplate(
        name=name or f.name,
        description=f.description,
        slots=slots,
        factors=[f.model_copy(update={"after": [], "weight": 1.0})],
    )


def extract_fragment(graph: TaskGraph, factor: str, name: TaskName | None = None) -> TaskGraph:
    """One factor of ``graph`` with its scope variables as a standalone fragment.

    Variables the scope variables start on/inside are kept too, so the fragment's
    initial scene stays well defined.
    """
    f = graph.factor(factor)
    keep = list(f.scope_names)
    i = 0
    while i < len(keep):
        for ref in graph.variable(keep[i]).references():
            if ref not in keep:
                keep.append(ref)
        i += 1
    return TaskGraph(
        name=name or f.name.replace("_", "-"),
        description=f.description,
        variables=[v for v in graph.variables if v.name in keep],
        factors=[f.model_copy(update={"after": [], "weight": 1.0})],
        limits=graph.limits,
    )
