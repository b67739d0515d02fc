"""Strict JSON Schemas of exactly the answer each generation step wants.

A grammar-constrained decoder (llama.cpp) or a provider's structured output can
only produce what the schema allows, so the schemas here are strict where the
graph model is lenient: every property is required (an optional one is
``null``-able, never absent), objects allow no other property, kinds, colours and
relation types are enums, the names of variables declared so far are an enum
wherever a step refers to them (restricted to the kinds that can serve the
field), numbers carry the graph model's bounds, and strings are short and hold
no control character, quote or backslash (:data:`TEXT_PATTERN`). Referential
mistakes then cannot be produced; the verification ladder checks the rest.

Bounds are read from the pydantic models (:class:`~factask.vocabulary.variables.StateVariable`,
the relation classes), so a schema never drifts from the model it feeds.
"""

from __future__ import annotations

import re
from collections.abc import Collection, Mapping, Sequence
from typing import Any

from factask.gen.answers.schemas import MAX_FACTORS, MAX_SUBTASKS, MAX_VARIABLES
from factask.graph.factors import SubtaskFactor
from factask.relations import RELATION_TYPES
from factask.vocabulary.kinds import ASSET_KINDS, kind_spec
from factask.vocabulary.limits import MAX_HEIGHT, MAX_HORIZONTAL, MIN_LENGTH
from factask.vocabulary.palette import COLOR_NAMES
from factask.vocabulary.variables import StateVariable

Schema = dict[str, Any]

#: What a step's schema allows (tighter than the plan limits the graph model
#: checks, so an answer always fits its token budget).
STEP_MAX_VARIABLES = min(12, MAX_VARIABLES)
STEP_MAX_FACTORS = min(8, MAX_FACTORS)
STEP_MAX_SUBTASKS = min(8, MAX_SUBTASKS)

#: A name: snake_case, no double underscore, at most 64 characters.
NAME_REGEX = r"^[a-z][a-z0-9]{0,15}(_[a-z0-9]{1,15}){0,3}$"
#: Free text: printable ASCII without quote or backslash (so no escapes, no control
#: characters). The length bound is ``maxLength``: a bounded repetition in the
#: pattern makes llama.cpp's grammar sampling an order of magnitude slower.
TEXT_PATTERN = r"^[ !#-\[\]-~]*$"
#: Longest description / setup text.
MAX_TEXT = 100
#: Fields of a relation no step asks for (their defaults are right for generation).
OMITTED_RELATION_FIELDS = frozenset(["tolerances", "matches"])
OMITTED_PER_RELATION: dict[str, frozenset[str]] = {"in_zone": frozenset(["poses"])}


def text(max_len: int = MAX_TEXT) -> Schema:
    """A short free-text string (no control characters, quotes or backslashes)."""
    return {"type": "string", "pattern": TEXT_PATTERN, "maxLength": max_len}


def name(names: Sequence[str] | None = None, nullable: bool = False) -> Schema:
    """A name: one of ``names`` if given (an enum), else any well-formed name."""
    base: Schema = {"type": "string", "enum": list(names)} if names is not None else \
        {"type": "string", "pattern": NAME_REGEX}
    if nullable:
        return {"anyOf": [base, {"type": "null"}]}
    return base


def obj(properties: Mapping[str, Schema]) -> Schema:
    """An object with exactly these properties, all required."""
    return {"type": "object", "properties": dict(properties),
            "required": list(properties), "additionalProperties": False}


def array(items: Schema, min_items: int = 0, max_items: int | None = None) -> Schema:
    """An array of ``items`` with bounds."""
    out: Schema = {"type": "array", "items": items, "minItems": min_items}
    if max_items is not None:
        out["maxItems"] = max_items
    return out


def _field_schema(model: Any, field: str) -> Schema:
    """A pydantic model's JSON Schema of one field (``$ref``s resolved, nullable unwrapped)."""
    full = model.model_json_schema()
    prop = dict(full["properties"][field])
    if "anyOf" in prop:
        prop = next(p for p in prop["anyOf"] if p.get("type") != "null")
    return _strip(_resolve(prop, full.get("$defs", {})))


def _resolve(node: Any, defs: Mapping[str, Any]) -> Any:
    if isinstance(node, dict):
        if "$ref" in node:
            return _resolve(defs[node["$ref"].split("/")[-1]], defs)
        return {k: _resolve(v, defs) for k, v in node.items()}
    if isinstance(node, list):
        return [_resolve(v, defs) for v in node]
    return node


def _strip(node: Any) -> Any:
    """Drop titles, defaults and descriptions; objects closed and fully required;
    free strings bounded (see :func:`text`); names kept as :func:`name`."""
    if isinstance(node, list):
        return [_strip(v) for v in node]
    if not isinstance(node, dict):
        return node
    out = {k: _strip(v) for k, v in node.items() if k not in ("title", "default",
                                                               "description")}
    if out.get("type") == "object" and "properties" in out:
        out["required"] = list(out["properties"])
        out["additionalProperties"] = False
    if out.get("type") == "string" and "enum" not in out and "const" not in out:
        out = name() if out.get("pattern", "").startswith("^[a-z][a-z0-9_]") else text()
    return out


def _nullable(schema: Schema) -> Schema:
    return {"anyOf": [schema, {"type": "null"}]}


# ------------------------------------------------------------------ variables
def placement_schema(names: Sequence[str] | None = None) -> Schema:
    """A variable's initial placement: ``table``, ``on`` or ``inside`` another variable.

    Args:
        names: Variables it may rest on or inside (None: any name).
    """
    receptacles = None if names is None else list(names)
    # No ``pose`` or ``region``: coordinates are what the library computes, and a
    # grammar cannot hold a number to bounds (llama.cpp ignores minimum/maximum).
    options = [obj({"type": {"const": "table"}})]
    if receptacles is None or receptacles:
        options += [obj({"type": {"const": "on"}, "support": name(receptacles)}),
                    obj({"type": {"const": "inside"}, "container": name(receptacles)})]
    return {"anyOf": options}


def _length(most: float) -> Schema:
    """A length in metres from the model's smallest to ``most``."""
    return {"type": "number", "minimum": MIN_LENGTH, "maximum": most}


def variable_schema(names: Sequence[str] | None = None) -> Schema:
    """One state variable: name, description, kind, size, colour, count, fixed, initial.

    Args:
        names: Other variables an initial placement may refer to (None: any name).
    """
    return obj({
        "name": name(),
        "description": text(),
        "kind": {"type": "string", "enum": list(ASSET_KINDS)},
        # null: the kind's default size (the safe choice for a small model).
        # x, y, z in metres with the graph model's bounds per axis (a height
        # above the workspace's is refused by the model too).
        "size": _nullable({"type": "array", "minItems": 3, "maxItems": 3, "items": False,
                           "prefixItems": [_length(MAX_HORIZONTAL), _length(MAX_HORIZONTAL),
                                           _length(MAX_HEIGHT)]}),
        "color": {"type": "string", "enum": list(COLOR_NAMES)},
        "count": _field_schema(StateVariable, "count"),
        # null: the kind's default (zones and bowls fixed, blocks movable); true pins
        # an object of a movable kind (an obstacle, a fixed stand).
        "fixed": {"anyOf": [{"type": "null"}, {"type": "boolean"}]},
        "initial": placement_schema(names),
    })


def variables_answer(max_variables: int = STEP_MAX_VARIABLES) -> Schema:
    """Approach 1, step 1: ``{"variables": [...]}``."""
    return obj({"variables": array(variable_schema(), 1, max_variables)})


# ------------------------------------------------------------------ relations
def _capable(kind_names: Mapping[str, str], caps: Sequence[str]) -> list[str]:
    return [n for n, k in kind_names.items()
            if not caps or any(getattr(kind_spec(k), c) for c in caps)]


def relation_schema(relation: str, variables: Mapping[str, str] | None = None,
                    moved: Collection[str] = ()) -> Schema | None:
    """One relation type's goal object.

    Args:
        relation: The relation's ``type``.
        variables: Variable name -> kind of the variables the goal may use (None:
            any name). Anchor fields then list only the variables whose kind can
            serve them; ``objects`` only movable ones.
        moved: Variables of a kind fixed by default that are movable here (a bowl
            the task carries).

    Returns:
        The schema, or None if no variable can fill a required field.
    """
    cls = RELATION_TYPES[relation]
    full = cls.model_json_schema()
    defs = full.get("$defs", {})
    omit = OMITTED_RELATION_FIELDS | OMITTED_PER_RELATION.get(relation, frozenset())
    props: dict[str, Schema] = {}
    own = cls.moves_kinds or frozenset()  # a drawer slides, fixed in its cabinet
    movers = None if variables is None else [
        n for n, k in variables.items() if kind_spec(k).movable or n in moved or k in own]
    if movers is not None and not movers:
        return None
    ordered = ["type", *[f for f in full["properties"] if f != "type"]]
    for field in ordered:
        prop = full["properties"][field]
        if field in omit:
            continue
        optional = field not in full.get("required", []) and field != "type"
        if field == "type":
            props[field] = {"const": relation}
        elif field == "objects":
            props[field] = array(name(movers), 1, len(movers) if movers else 8)
        elif field in cls.anchor_fields:
            allowed = None if variables is None else _capable(variables,
                                                               cls.anchor_fields[field])
            if allowed is not None and not allowed:
                if not optional:
                    return None
                props[field] = {"type": "null"}
                continue
            props[field] = name(allowed, nullable=optional)
        else:
            inner = _strip(_resolve(prop, defs))
            if "anyOf" in inner:
                kept = [p for p in inner["anyOf"] if p.get("type") != "null"]
                inner = kept[0] if len(kept) == 1 else {"anyOf": kept}
            props[field] = _nullable(inner) if optional and "default" in prop and \
                prop["default"] is None else inner
    return obj(props)


def goal_schema(variables: Mapping[str, str] | None = None,
                moved: Collection[str] = ()) -> Schema:
    """Any goal relation (one of the relation types), see :func:`relation_schema`."""
    options = [s for r in RELATION_TYPES
               if (s := relation_schema(r, variables, moved)) is not None]
    return {"anyOf": options}


# -------------------------------------------------------------------- factors
def factor_schema(factor_names: Sequence[str] | None = None,
                  variables: Mapping[str, str] | None = None) -> Schema:
    """One subtask factor of a whole graph: name, description, goal, weight, after,
    initial_setup (and ``milestone`` where the factor model has it)."""
    props: dict[str, Schema] = {
        "name": name(),
        "description": text(),
        "goal": goal_schema(variables),
        "weight": {"type": "number", "exclusiveMinimum": 0, "maximum": 1},
        "after": array(name(factor_names), 0, STEP_MAX_FACTORS),
        "initial_setup": text(),
    }
    if "milestone" in SubtaskFactor.model_fields:
        props["milestone"] = {"type": "boolean"}
    return obj(props)


def graph_schema(task_name: str) -> Schema:
    """A whole task graph (one-shot, assembly): the task's name is fixed."""
    return obj({
        "name": {"const": task_name},
        "description": text(),
        "variables": array(variable_schema(), 1, STEP_MAX_VARIABLES),
        "factors": array(factor_schema(), 1, STEP_MAX_FACTORS),
    })


# ------------------------------------------------------------------- subtasks
def subtask_plan(variable_names: Sequence[str],
                 max_subtasks: int = STEP_MAX_SUBTASKS) -> Schema:
    """Approach 1, step 2: subtasks, each naming a subset of the declared variables
    (at most ``max_subtasks``)."""
    return obj({"subtasks": array(obj({
        "name": name(),
        "description": text(),
        "variables": array(name(variable_names), 1, len(variable_names)),
        "initial_setup": text(),
        "after": array(name(), 0, max_subtasks),
    }), 1, max_subtasks)})


def goal_answer(scope: Mapping[str, str], moved: Collection[str] = ()) -> Schema:
    """Approach 1, step 3: one subtask's goal over exactly its planned variables.

    Args:
        scope: Its variables' names -> kinds.
        moved: Those of a kind fixed by default that the task moves (``fixed: false``).
    """
    return obj({"goal": goal_schema(scope, moved), "description": text()})


def subtask_outline() -> Schema:
    """Approach 2, step 1: subtask names and descriptions."""
    return obj({"subtasks": array(obj({"name": name(), "description": text(),
                                       "after": array(name(), 0, STEP_MAX_SUBTASKS)}), 1,
                                  STEP_MAX_SUBTASKS)})


def subtask_design(earlier: Sequence[str] = ()) -> Schema:
    """Approach 2, step 2: a subtask's variables and goal.

    Args:
        earlier: Variables earlier subtasks defined (a new variable's initial
            placement may rest on them; the goal may use them or new ones).
    """
    del earlier  # names declared in the same answer cannot be enumerated up front
    return obj({"variables": array(variable_schema(), 0, STEP_MAX_VARIABLES),
                "goal": goal_schema(), "description": text()})


def with_empty_fields(data: Any, schema: Mapping[str, Any]) -> Any:
    """``data`` with each required property it leaves out that has an empty value
    filled: null where the schema admits null (``size``, ``fixed``), ``[]`` for a
    list that may be empty (``after``). Strict schemas list every property as
    required (a provider's strict mode asks for that), but leaving out a field whose
    absence means "none" is not a mistake worth a repair; anything else missing is
    still reported.

    Args:
        data: The decoded answer (not changed).
        schema: The step's strict schema.

    Returns:
        A copy with the empty fields added (or ``data`` itself where nothing is).
    """
    defs = schema.get("$defs", {})

    def deref(node: Any) -> Any:
        return _resolve(node, defs) if isinstance(node, Mapping) and "$ref" in node else node

    def walk(value: Any, node: Any) -> Any:
        node = deref(node)
        if not isinstance(node, Mapping):
            return value
        branches = [deref(b) for b in node.get("anyOf") or ()]
        if branches and isinstance(value, Mapping):
            tagged = [b for b in branches
                      if deref((b.get("properties") or {}).get("type", {})).get("const")
                      == value.get("type")]
            objects = [b for b in branches if b.get("type") == "object"]
            chosen = tagged or (objects if len(objects) == 1 else [])
            return walk(value, chosen[0]) if chosen else value
        if isinstance(value, list) and node.get("type") == "array":
            return [walk(v, node.get("items", {})) for v in value]
        if not (isinstance(value, Mapping) and node.get("type") == "object"):
            return value
        props = node.get("properties", {})
        out = {k: walk(v, props[k]) if k in props else v for k, v in value.items()}
        for key in node.get("required", ()):
            if key in out or key not in props:
                continue
            prop = deref(props[key])
            if any(deref(b).get("type") == "null" for b in prop.get("anyOf") or ()):
                out[key] = None
            elif prop.get("type") == "array" and not prop.get("minItems"):
                out[key] = []
        return out

    return walk(data, schema)


def schema_problems(data: Any, schema: Mapping[str, Any], limit: int = 12) -> list[str]:
    """Where ``data`` breaks a step schema, one line per problem (path: message).

    Inside an ``anyOf`` of relations, the alternative whose ``type`` the data
    names is the one reported (not "is not valid under any of the schemas").

    Args:
        data: Decoded answer.
        schema: The step's strict schema.
        limit: At most this many lines.

    Returns:
        The problems (empty: the answer follows the schema).
    """

    out: list[str] = []

    def report(error: Any) -> None:
        if error.validator == "anyOf" and error.context:
            chosen = _branch_errors(error)
            if chosen:
                for sub in chosen:
                    report(sub)
                return
        path = ".".join(str(p) for p in error.absolute_path) or "(answer)"
        message = error.message if len(error.message) < 240 else error.message[:237] + "..."
        out.append(f"{path}: {message}")

    for error in _validator()(schema).iter_errors(data):
        report(error)
        if len(out) >= limit:
            break
    return out[:limit]


def _strict_pattern(validator: Any, pattern: str, instance: Any, schema: Any) -> Any:
    """``pattern`` as JSON Schema (ECMA-262) means it: Python's ``$`` also matches
    before a final newline, which let ``"text\\n"`` through a text field."""
    if not validator.is_type(instance, "string"):
        return
    from jsonschema import ValidationError

    found = re.search(pattern, instance)
    anchored = pattern.endswith("$") and not pattern.endswith("\\$")
    if found is None or (anchored and found.end() != len(instance)):
        yield ValidationError(f"{instance!r} does not match {pattern!r}")


def _validator() -> Any:
    """Draft 2020-12 with :func:`_strict_pattern`."""
    from jsonschema import Draft202012Validator, validators

    return validators.extend(Draft202012Validator, {"pattern": _strict_pattern})


def _branch_errors(error: Any) -> list[Any]:
    """The sub-errors of the ``anyOf`` alternative the data meant (by its ``type``)."""
    instance = error.instance
    wanted = instance.get("type") if isinstance(instance, dict) else None
    by_branch: dict[int, list[Any]] = {}
    for sub in error.context:
        by_branch.setdefault(sub.schema_path[0], []).append(sub)
    for i, branch in enumerate(error.schema.get("anyOf", [])):
        const = branch.get("properties", {}).get("type", {}).get("const")
        if wanted is not None and const == wanted:
            return by_branch.get(i, [])
    if len(by_branch) == 1:
        return next(iter(by_branch.values()))
    # A nullable number or name: report the branch of the answer's JSON type
    # ("1 is greater than the maximum of 0.5"), not "valid under none".
    typed = [i for i, branch in enumerate(error.schema.get("anyOf", []))
             if _json_type_matches(instance, branch.get("type"))]
    if len(typed) == 1:
        return by_branch.get(typed[0], [])
    return []


def _json_type_matches(instance: Any, json_type: Any) -> bool:
    """Whether ``instance`` has JSON Schema type ``json_type`` (one name only)."""
    if json_type == "number":
        return isinstance(instance, (int, float)) and not isinstance(instance, bool)
    python_types = {"null": type(None), "string": str, "boolean": bool,
                    "object": dict, "array": list, "integer": int}
    wanted = python_types.get(json_type) if isinstance(json_type, str) else None
    if wanted is None:
        return False
    if wanted is int and isinstance(instance, bool):
        return False
    return isinstance(instance, wanted)


def empty_choices(schema: Any, path: str = "$") -> list[str]:
    """Where a schema offers no choice at all (an empty ``anyOf`` or ``enum``: a goal
    over variables none of which a relation can move). No answer can follow such a
    schema, and llama.cpp's grammar parser fails on it (its server goes down).

    Returns:
        The JSON paths of the empty choices (empty: none).
    """
    if isinstance(schema, list):
        return [p for i, item in enumerate(schema) for p in empty_choices(item, f"{path}[{i}]")]
    if not isinstance(schema, Mapping):
        return []
    found = [f"{path}.{key}" for key in ("anyOf", "enum")
             if isinstance(schema.get(key), list) and not schema[key]]
    for key, value in schema.items():
        if isinstance(value, (Mapping, list)):
            found += empty_choices(value, f"{path}.{key}")
    return found


def all_step_schemas(task_name: str = "demo-task") -> dict[str, Schema]:
    """Every step's schema with sample arguments (for tests and docs)."""
    scope = {"red_block": "block", "green_zone": "zone"}
    return {"one_shot": graph_schema(task_name), "variables": variables_answer(),
            "subtask_plan": subtask_plan(list(scope)), "subtask_goal": goal_answer(scope),
            "subtask_outline": subtask_outline(), "subtask_design": subtask_design(),
            "assembly": graph_schema(task_name)}


__all__ = ["MAX_TEXT", "NAME_REGEX", "TEXT_PATTERN", "all_step_schemas", "empty_choices",
           "factor_schema",
           "goal_answer", "goal_schema", "graph_schema", "name", "placement_schema",
           "relation_schema", "schema_problems", "subtask_design", "subtask_outline",
           "subtask_plan", "text", "variable_schema", "variables_answer", "with_empty_fields"]
