"""The reader-only "model": every answer is the first choice the step's schema allows.

With a grounded (local, constrained) model, the proposal reader
(:mod:`factask.gen.reading`) decides which objects a step's schema names and which
goal shapes it offers; the model only picks among them. ``local/reader`` picks
nothing: it answers each step with the schema's first choice (the first branch of
every ``anyOf``, the first value of every ``enum``, the fewest items an array may
have, the middle of a number's range). Run through the same pipeline as any model
(litellm over HTTP to a loopback server), it measures what the reading alone is
worth, so a benchmark table shows what each real model adds over it.

The answer is deterministic: a repair gets the same answer again, which the step
runner stops at once as a repeat.
"""

from __future__ import annotations

import json
import re
import string
from collections.abc import Iterator, Mapping
from typing import Any

from factask.vocabulary.errors import FactaskError

#: The model name that selects the reader-only answers (``--model local/reader``).
READER_MODEL = "local/reader"

#: Deepest schema nesting followed (``$ref`` cycles end here, with an error).
_MAX_DEPTH = 64


class FirstChoiceError(FactaskError):
    """A schema with no instance to pick (``not``, an unresolvable ``$ref``, a cycle)."""


def first_choice(schema: Mapping[str, Any]) -> Any:
    """The first instance ``schema`` allows, choice by choice.

    Args:
        schema: A JSON Schema (the subset factask's step schemas use: ``$ref`` into
            ``$defs``, ``anyOf`` / ``oneOf``, ``const``, ``enum``, objects,
            arrays with ``prefixItems``, strings, numbers, booleans, null).

    Returns:
        The instance: a node's ``default`` where it has one; required properties only,
        ``minItems`` items, numbers at the middle of their range, strings of
        ``minLength`` letters (a pattern's first short match, distinct in the answer).

    Raises:
        FirstChoiceError: the schema has no instance this can build.
    """
    return _Picker(schema).pick(schema, 0)


class _Picker:
    """One answer's picks: strings with a pattern are distinct within the answer (a
    name the schema leaves free is a new name each time it is asked for)."""

    def __init__(self, root: Mapping[str, Any]) -> None:
        self.root = root
        self.used: set[str] = set()

    def pick(self, node: Any, depth: int) -> Any:
        if depth > _MAX_DEPTH:
            raise FirstChoiceError("the schema nests deeper than 64 levels (a $ref cycle?)")
        if node is True or node == {}:
            return None
        if not isinstance(node, Mapping):
            raise FirstChoiceError(f"no instance of schema node {str(node)[:80]}")
        if "$ref" in node:
            return self.pick(resolve_ref(node["$ref"], self.root), depth + 1)
        for key in ("anyOf", "oneOf"):
            if node.get(key):
                return self.pick(node[key][0], depth + 1)
        if node.get("allOf"):
            merged: dict[str, Any] = {}
            for part in node["allOf"]:
                merged.update(resolve_ref(part["$ref"], self.root) if "$ref" in part else part)
            return self.pick(merged, depth + 1)
        if "const" in node:
            return node["const"]
        if "default" in node:  # the schema's own choice where it has one
            return node["default"]
        if "enum" in node:
            if not node["enum"]:
                raise FirstChoiceError("an empty enum has no instance")
            return node["enum"][0]
        kind = node.get("type")
        if isinstance(kind, list):
            kind = kind[0] if kind else None
        if kind == "object" or (kind is None and "properties" in node):
            props = node.get("properties", {})
            required = node.get("required", list(props))
            return {k: self.pick(props[k], depth + 1) for k in required if k in props}
        if kind == "array" or (kind is None and ("items" in node or "prefixItems" in node)):
            prefix = [self.pick(item, depth + 1) for item in node.get("prefixItems", [])]
            more = max(0, int(node.get("minItems", 0)) - len(prefix))
            items = node.get("items")
            if more and (items is None or items is False):
                raise FirstChoiceError("an array needs more items than its schema allows")
            return prefix + [self.pick(items, depth + 1) for _ in range(more)]
        if kind == "string":
            return self.string(node)
        if kind in ("number", "integer"):
            low = node.get("minimum", node.get("exclusiveMinimum"))
            high = node.get("maximum", node.get("exclusiveMaximum"))
            value = ((low + high) / 2 if low is not None and high is not None
                     else low if low is not None else high if high is not None else 0)
            return round(value) if kind == "integer" else value
        if kind == "boolean":
            return False
        if kind == "null":
            return None
        raise FirstChoiceError(f"no instance of schema node {json.dumps(node)[:80]}")

    def string(self, node: Mapping[str, Any]) -> str:
        low, high = int(node.get("minLength", 0)), node.get("maxLength")
        pattern = node.get("pattern")
        if pattern is None:
            return "x" * low
        for candidate in _candidates():
            if (candidate not in self.used and len(candidate) >= low
                    and (high is None or len(candidate) <= high)
                    and re.search(pattern, candidate)):
                self.used.add(candidate)
                return candidate
        raise FirstChoiceError(f"no short string matches the pattern {pattern[:80]!r}")


def _candidates() -> Iterator[str]:
    """Short lower-case names, then the same with digits and underscores: what a
    free name's pattern in factask's schemas accepts (``^[a-z][a-z0-9_]*$`` …)."""
    letters = string.ascii_lowercase
    yield from letters
    yield from (a + b for a in letters for b in letters)
    yield from (f"{a}{n}" for n in range(10) for a in letters)
    yield from (f"{a}_{b}" for a in letters for b in letters)


def resolve_ref(ref: str, root: Mapping[str, Any]) -> Any:
    """The node a local ``$ref`` (``#/$defs/...``) points at in ``root``.

    Raises:
        FirstChoiceError: not a local reference, or nothing there.
    """
    if not ref.startswith("#/"):
        raise FirstChoiceError(f"cannot resolve {ref!r}: only local references")
    node: Any = root
    for part in ref[2:].split("/"):
        if not isinstance(node, Mapping) or part not in node:
            raise FirstChoiceError(f"cannot resolve {ref!r}")
        node = node[part]
    return node


class FirstChoiceResponder:
    """A loopback responder (:mod:`factask.gen.loopback`) answering every request
    with the first choice of the schema it sends (``response_format``: the
    ``llama_cpp`` form's ``schema`` or the ``json_schema`` form's)."""

    def __call__(self, request: dict[str, Any]) -> str:
        form = request.get("response_format") or {}
        schema = form.get("schema") or (form.get("json_schema") or {}).get("schema")
        if not isinstance(schema, Mapping):
            raise FirstChoiceError("the reader answers only requests that send a schema "
                                   "(structured output: llama_cpp or json_schema)")
        return json.dumps(first_choice(schema))
