"""The task graph: variables, factors, edges — and its validation.

A :class:`TaskGraph` is plain data (pydantic). Constructing one checks each field
on its own (types, patterns, ranges, known kinds and colours); :meth:`TaskGraph.ensure_valid`
checks the graph as a whole (names resolve, weights sum to 1, order is acyclic, ...)
and reports **every** problem at once as one :class:`GraphValidationError`.
:func:`parse_graph` does both for outside input (JSON text, dicts) and turns every
failure into that same typed error.
"""

from __future__ import annotations

import json
import math
from collections import Counter
from collections.abc import Iterable, Mapping
from typing import Any

import networkx as nx
from pydantic import BaseModel, ConfigDict, Field, ValidationError

from factask.graph.factors import SubtaskFactor
from factask.graph.order import (
    cycle_problems,
    dependency_graph,
    mover_problems,
    topological_order,
)
from factask.vocabulary.errors import GraphValidationError, Problem, name_list
from factask.vocabulary.kinds import JOINTED_KINDS, kind_spec, shape_problem
from factask.vocabulary.limits import MAX_FACTORS, MAX_OBJECTS, MAX_VARIABLES, Text, size_problem
from factask.vocabulary.names import TaskName
from factask.vocabulary.variables import (
    InCabinet,
    MountedOn,
    StartInside,
    StateVariable,
    cabinet_problems,
    gates_of,
    switch_problems,
)

#: Weights must sum to 1 within this absolute tolerance.
WEIGHT_SUM_TOLERANCE = 1e-6


class Limits(BaseModel):
    """Episode limits, in simulated units (never wall-clock).

    Attributes:
        max_actions: Pick-and-place actions per episode; default: twice the number
            of movable objects plus four.
        max_sim_seconds_per_action: Simulated seconds one action may take.
    """

    model_config = ConfigDict(extra="forbid")

    max_actions: int | None = Field(None, ge=1, le=1000)
    max_sim_seconds_per_action: float = Field(10.0, gt=0, le=120, allow_inf_nan=False)


class TaskGraph(BaseModel):
    """A manipulation task as a bipartite factor graph.

    Attributes:
        name: Task name (kebab-case, as in GenSim's task list).
        description: What the task is, in language.
        variables: The state variables (one side of the graph).
        factors: The subtask factors (the other side); an edge joins a factor to
            every variable of its scope.
        limits: Episode limits.
    """

    model_config = ConfigDict(extra="forbid")

    name: TaskName
    description: Text = ""
    variables: list[StateVariable] = Field(default_factory=list, max_length=MAX_VARIABLES)
    factors: list[SubtaskFactor] = Field(default_factory=list, max_length=MAX_FACTORS)
    limits: Limits = Field(default_factory=Limits)

    # ------------------------------------------------------------------ access
    def variable(self, name: str) -> StateVariable:
        """The variable called ``name`` (KeyError-free: raises GraphValidationError)."""
        for v in self.variables:
            if v.name == name:
                return v
        raise GraphValidationError(
            [Problem(name, "", "no such variable",
                     f"use one of {name_list(self.variable_names())}")]
        )

    def factor(self, name: str) -> SubtaskFactor:
        """The factor called ``name`` (raises GraphValidationError if missing)."""
        for f in self.factors:
            if f.name == name:
                return f
        raise GraphValidationError(
            [Problem(name, "", "no such factor", f"use one of {name_list(self.factor_names())}")]
        )

    def variable_names(self) -> list[str]:
        return [v.name for v in self.variables]

    def factor_names(self) -> list[str]:
        return [f.name for f in self.factors]

    def movable_object_count(self) -> int:
        """Number of free (pickable) objects in the scene."""
        return sum(v.count for v in self.variables if not v.is_fixed)

    def max_actions(self) -> int:
        """The action budget of an episode."""
        if self.limits.max_actions is not None:
            return self.limits.max_actions
        return 2 * self.movable_object_count() + 4

    # -------------------------------------------------------------- JSON I/O
    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (``None`` fields left out)."""
        return self.model_dump(mode="json", exclude_none=True)

    def to_json(self, indent: int | None = 2) -> str:
        """JSON text that :func:`parse_graph` / ``factask validate`` accept."""
        return json.dumps(self.to_dict(), indent=indent)

    @classmethod
    def from_json(cls, text: str | bytes) -> TaskGraph:
        """Parse and fully validate JSON text (see :func:`parse_graph`)."""
        return parse_graph(text)

    @staticmethod
    def json_schema() -> dict[str, Any]:
        """JSON Schema of a task graph (the LLM's structured-output schema)."""
        return TaskGraph.model_json_schema()

    # ------------------------------------------------------------ graph views
    def to_networkx(self) -> nx.Graph:
        """Bipartite networkx view.

        Variable nodes carry ``bipartite=0`` and ``model=StateVariable``; factor
        nodes ``bipartite=1`` and ``model=SubtaskFactor``; an edge joins each factor
        to every variable of its scope (edges to unknown variables are left out).
        """
        g = nx.Graph(name=self.name)
        for v in self.variables:
            g.add_node(v.name, bipartite=0, kind="variable", model=v)
        for f in self.factors:
            g.add_node(f.name, bipartite=1, kind="factor", model=f)
        known = set(self.variable_names())
        for f in self.factors:
            for name in f.scope_names:
                if name in known:
                    g.add_edge(name, f.name)
        return g

    def dependency_graph(self) -> nx.DiGraph:
        """Directed graph of factor order: an edge A -> B means A comes before B.

        Edges come from B's explicit ``after`` and from implied order: B's goal is
        anchored to (rests on, goes into, aligns with) a variable that A moves
        (see :mod:`factask.graph.order`); a goal anchored to a receptacle that a
        drawer or door gates is anchored to that gate too
        (:func:`~factask.vocabulary.variables.gates_of`).
        """
        return dependency_graph(self.factors, gates_of(self.variables))

    def factor_order(self) -> list[str]:
        """Factors in an order that respects every dependency (declaration order
        breaks ties).

        Raises:
            GraphValidationError: the order has a cycle (naming its factors).
        """
        d = self.dependency_graph()
        try:
            return topological_order(d, self.factor_names())
        except nx.NetworkXUnfeasible:
            raise GraphValidationError(cycle_problems(d)) from None

    def milestones(self) -> list[str]:
        """Names of the milestone factors (they count once achieved, in order)."""
        return [f.name for f in self.factors if f.milestone]

    # ------------------------------------------------------------ validation
    def problems(self) -> list[Problem]:
        """Every whole-graph problem (empty if the graph is valid)."""
        return graph_problems(self)

    def task_problems(self) -> list[Problem]:
        """Why this valid graph is not a task that can run (empty when it can): a task
        needs at least one factor. A graph with none is a valid fragment (the identity
        of :func:`~factask.graph.templates.compose`), not a task: ``factask validate``
        and every command that runs a task read this one rule."""
        if self.factors:
            return []
        return [Problem("", "factors", f"graph {self.name!r} has no factors",
                        "add at least one subtask factor")]

    def ensure_valid(self) -> TaskGraph:
        """Check every field again, then the graph as a whole; return it unchanged if
        valid. Entry points (compile, env, oracle, generation) call it, so a graph
        changed after it was built (``g.variables[0].kind = "nonsense"``) is caught
        where it enters, naming the node and field.

        (Not called ``validate``: that name is pydantic's.)

        Raises:
            GraphValidationError: listing every problem found.
        """
        # None kept: a field set to None after construction must fail as None, not be
        # left out and refilled with its default while the graph itself keeps the None.
        data = self.model_dump(mode="python", warnings=False)
        try:
            TaskGraph.model_validate(data)
        except ValidationError as exc:
            raise GraphValidationError(problems_from_pydantic(exc, data)) from None
        unset = [Problem(v.name, f, f"{f} is None: it was set after the variable was made "
                         "(None means the kind's default only when a variable is made)",
                         f"give a {f}, or make the variable again for its kind's default")
                 for v in self.variables for f in v.unset_defaults()]
        if unset:
            raise GraphValidationError(unset)
        found = self.problems()
        if found:
            raise GraphValidationError(found)
        return self


# ---------------------------------------------------------------------------
def _duplicates(names: Iterable[str]) -> list[str]:
    seen: set[str] = set()
    dup: list[str] = []
    for n in names:
        if n in seen and n not in dup:
            dup.append(n)
        seen.add(n)
    return dup


def graph_problems(graph: TaskGraph) -> list[Problem]:
    """All whole-graph problems of ``graph`` (see :meth:`TaskGraph.ensure_valid`)."""
    out: list[Problem] = []
    var_names = graph.variable_names()
    fac_names = graph.factor_names()
    variables = {v.name: v for v in graph.variables}
    factors = {f.name: f for f in graph.factors}

    for n in _duplicates(var_names):
        out.append(Problem(n, "name", "two variables have this name", "rename one of them"))
    for n in _duplicates(fac_names):
        out.append(Problem(n, "name", "two factors have this name", "rename one of them"))
    for n in sorted(set(var_names) & set(fac_names)):
        out.append(
            Problem(n, "name", "a variable and a factor share this name", "rename one of them")
        )

    # Variables: shapes their kind can have; initial placements refer to existing,
    # suitable variables.
    objects = sum(v.count for v in graph.variables)
    if objects > MAX_OBJECTS:
        out.append(Problem("", "variables", f"the scene has {objects} objects (the sum of the "
                           f"counts), more than {MAX_OBJECTS}",
                           "use fewer or smaller variables, or split the task"))
    for v in graph.variables:
        shape = size_problem(v.extents) or shape_problem(v.kind, v.extents)
        if shape is not None:
            out.append(Problem(v.name, "size", *shape))
        if getattr(v.initial, "offset", None) is not None and v.count > 1:
            out.append(Problem(v.name, "initial.offset", f"one place given for {v.count} "
                               "objects", "give each object its own variable, or drop the "
                               "offset"))
        for ref in v.references():
            if ref == v.name:
                out.append(Problem(v.name, "initial", "starts on/inside itself",
                                   "name another variable"))
            elif ref not in variables:
                out.append(Problem(v.name, "initial", f"starts on/inside unknown variable "
                                   f"{ref!r}", f"use one of {name_list(var_names)}"))
            elif not isinstance(v.initial, InCabinet | MountedOn):  # cabinet/switch_problems
                need = "receptacle" if isinstance(v.initial, StartInside) else "support"
                host = variables[ref]
                if not getattr(kind_spec(host.kind), need):
                    out.append(Problem(v.name, "initial", f"starts {v.initial.type} {ref!r}, "
                                       f"a {host.kind}, which is not a {need}",
                                       "start it on the table or on/inside another variable"))
    out.extend(cabinet_problems(graph.variables))
    out.extend(switch_problems(graph.variables))
    starts = nx.DiGraph()
    for v in graph.variables:
        for ref in v.references():
            if ref in variables and ref != v.name:
                starts.add_edge(ref, v.name)
    if not nx.is_directed_acyclic_graph(starts):
        cyc = nx.find_cycle(starts)
        out.append(Problem(cyc[0][0], "initial", "initial placements form a cycle: "
                           + " -> ".join(a for a, _ in cyc), "start one of them on the table"))

    # Factors.
    for f in graph.factors:
        scope = f.scope_names
        if not scope:
            out.append(Problem(f.name, "scope", "scope is empty",
                               "list the variables the goal uses, or leave scope out"))
        for dup in _duplicates(scope):
            out.append(Problem(f.name, "scope", f"scope lists {dup!r} twice", "list it once"))
        for name in scope:
            if name not in variables:
                out.append(Problem(f.name, "scope", f"scope names missing variable {name!r}",
                                   f"define variable {name!r} or use one of "
                                   f"{name_list(var_names)}"))
        for name in f.goal.variable_names():
            if name not in variables and name not in scope:
                out.append(Problem(f.name, "goal", f"goal uses missing variable {name!r} "
                                   "(and it is not in the scope)",
                                   f"define variable {name!r} or use one of "
                                   f"{name_list(var_names)}"))
            elif name not in scope:
                out.append(Problem(f.name, "goal", f"goal uses variable {name!r} outside the "
                                   f"factor's scope {name_list(scope)}",
                                   f"add {name!r} to the scope"))
        overlap = set(f.goal.objects) & set(f.goal.anchors())
        for name in sorted(overlap):
            out.append(Problem(f.name, "goal", f"variable {name!r} is both moved and an anchor",
                               "a goal cannot be relative to the object it moves"))
        for name in _duplicates(f.goal.objects):
            out.append(Problem(f.name, "goal.objects", f"{name!r} listed twice", "list it once"))
        for name in f.goal.objects:
            v = variables.get(name)
            # A drawer, a door or a switch is fixed (never picked) but moves on its joint
            # in its host: 'open' ('switched_on') moves it. A kind the relation does not
            # move at all is said by the relation (its fix names the right variable).
            moves = f.goal.moves_kinds
            if (v is not None and v.is_fixed and v.kind not in JOINTED_KINDS
                    and (moves is None or v.kind in moves)):
                out.append(Problem(f.name, "goal.objects", f"moves fixed variable {name!r}",
                                   f"set {name!r} fixed=false or move another variable"))
        out.extend(f.goal.problems(f.name, variables))
        host = None if f.after else f.goal.met_at_start(variables)
        if host is not None:  # every reset would be refused: say it once, up front
            message, fix = f.goal.met_at_start_problem(host)
            out.append(Problem(f.name, "goal", message, fix))
        for a in f.after:
            if a == f.name:
                out.append(Problem(f.name, "after", "factor is ordered after itself",
                                   "remove it from 'after'"))
            elif a not in factors:
                out.append(Problem(f.name, "after", f"'after' names unknown factor {a!r}",
                                   f"use one of {name_list(fac_names)}"))
        if not math.isfinite(f.weight) or f.weight <= 0:
            out.append(Problem(f.name, "weight", "weight must be a positive number",
                               "give a weight in (0, 1]"))


    if graph.factors:
        total = sum(f.weight for f in graph.factors)
        if not math.isclose(total, 1.0, abs_tol=WEIGHT_SUM_TOLERANCE):
            out.append(Problem("", "factors.weight", f"factor weights sum to {total:.6g}, not 1",
                               "scale the weights so they add up to 1"))

    d = graph.dependency_graph()
    if not nx.is_directed_acyclic_graph(d):
        out.extend(cycle_problems(d))
    out.extend(mover_problems(graph.factors, d))
    return out


# ---------------------------------------------------------------------------
def _node_name(data: Any, loc: tuple[Any, ...]) -> tuple[str, str]:
    """Map a pydantic error location to (node name, field path)."""
    if len(loc) >= 2 and loc[0] in ("variables", "factors") and isinstance(loc[1], int):
        node = f"{loc[0]}[{loc[1]}]"
        try:
            item = data[loc[0]][loc[1]]
            if isinstance(item, Mapping) and isinstance(item.get("name"), str):
                node = item["name"]
        except (KeyError, IndexError, TypeError):
            pass
        return node, ".".join(str(x) for x in loc[2:])
    return "", ".".join(str(x) for x in loc)


def problems_from_pydantic(error: ValidationError, data: Any) -> list[Problem]:
    """Turn a pydantic ValidationError on graph input into named problems."""
    out = []
    for e in error.errors(include_url=False):
        node, field = _node_name(data, tuple(e.get("loc", ())))
        msg = e.get("msg", "invalid")
        if e.get("type") == "extra_forbidden":
            msg = "unknown field"
            fix = "remove it (see `factask schema`)"
        elif e.get("type") == "missing":
            fix = "add it"
        elif e.get("type") == "union_tag_invalid":
            fix = "use one of the listed types"
        else:
            fix = "see `factask schema` for the allowed values"
        out.append(Problem(node, field, msg, fix))
    return out


class _DuplicateKeys(ValueError):
    def __init__(self, keys: list[str]) -> None:
        super().__init__(keys)
        self.keys = ", ".join(repr(k[:40]) for k in keys[:5])


def _no_duplicate_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """``json.loads``' object hook: an object that gives a key twice is refused (plain
    JSON keeps the last one silently: ``{"name": "a", "name": "b"}`` would read as b)."""
    out = dict(pairs)
    if len(out) != len(pairs):
        counts = Counter(k for k, _ in pairs)
        raise _DuplicateKeys([k for k, n in counts.items() if n > 1])
    return out


def parse_graph(source: str | bytes | Mapping[str, Any] | TaskGraph) -> TaskGraph:
    """Parse outside input into a fully validated :class:`TaskGraph`.

    Args:
        source: JSON text, a dict, or a TaskGraph.

    Returns:
        The graph, valid as a whole.

    Raises:
        GraphValidationError: the input is not JSON, not a graph, or not valid;
            every problem is listed and names its node.
    """
    if isinstance(source, TaskGraph):
        return source.ensure_valid()
    data: Any = source
    if isinstance(source, (str, bytes)):
        if isinstance(source, str):
            source = source.removeprefix("\ufeff")  # as json.loads does for bytes
        try:
            data = json.loads(source, object_pairs_hook=_no_duplicate_keys)
        except _DuplicateKeys as exc:
            raise GraphValidationError(
                [Problem("", "", f"a JSON object repeats the key(s) {exc.keys}: which one "
                         "counts would be a guess", "give each key once")]) from None
        except RecursionError:
            raise GraphValidationError(
                [Problem("", "", "JSON nested too deeply", "send one flat task-graph object")]
            ) from None
        except ValueError as exc:  # JSONDecodeError, bad UTF-8, huge integers
            raise GraphValidationError(
                [Problem("", "", f"not valid JSON: {exc}", "send one JSON object")]
            ) from None
    if not isinstance(data, Mapping):
        raise GraphValidationError(
            [Problem("", "", f"expected a JSON object, got {type(data).__name__}",
                     "send one JSON object with name, variables and factors")]
        )
    # Refuse absurd sizes before validating every item (a million variables).
    too_many = [Problem("", key, f"{len(data[key]):,} {key}, more than {limit}",
                        f"keep at most {limit} {key} in one graph")
                for key, limit in (("variables", MAX_VARIABLES), ("factors", MAX_FACTORS))
                if isinstance(data.get(key), list) and len(data[key]) > limit]
    if too_many:
        raise GraphValidationError(too_many)
    try:
        graph = TaskGraph.model_validate(data)
    except ValidationError as exc:
        found = problems_from_pydantic(exc, data)
        found += _problems_of_valid_parts(data)
        raise GraphValidationError(found) from None
    except RecursionError:
        raise GraphValidationError(
            [Problem("", "", "input nested too deeply", "send one flat task-graph object")]
        ) from None
    found = graph.problems()  # its fields were just validated
    if found:
        raise GraphValidationError(found)
    return graph


def _problems_of_valid_parts(data: Mapping[str, Any]) -> list[Problem]:
    """Whole-graph problems among the variables and factors that are valid on their
    own, when others are not: one round of feedback then lists everything.

    Problems that only exist because an invalid item was left out (a scope naming
    it, an ``after`` naming it, the weight sum) are not reported: its own field
    errors already are.
    """
    def valid(items: Any, model: type[BaseModel]) -> tuple[list[Any], set[str]]:
        ok, bad = [], set()
        for item in items if isinstance(items, list) else []:
            try:
                ok.append(model.model_validate(item))
            except (ValidationError, RecursionError):
                if isinstance(item, Mapping) and isinstance(item.get("name"), str):
                    bad.add(item["name"])
        return ok, bad

    variables, bad_vars = valid(data.get("variables"), StateVariable)
    factors, bad_factors = valid(data.get("factors"), SubtaskFactor)
    try:
        partial = TaskGraph(name="partial", variables=variables, factors=factors)
    except ValidationError:
        return []
    dropped = bad_vars | bad_factors
    keep = []
    for p in graph_problems(partial):
        if p.node == "" and p.field == "factors.weight" and bad_factors:
            continue
        if any(f"{name!r}" in p.message for name in dropped):
            continue
        keep.append(p)
    return keep
