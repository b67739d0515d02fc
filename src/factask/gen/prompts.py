"""Prompt templates (``factask/prompts/*.md``, package data) and the vocabulary they
are filled with.

One template file per step; placeholders are ``{{name}}`` (so JSON braces in a
template need no escaping). Every list the model sees — asset kinds, colours,
relation types with their parameters, initial placements — is rendered from the
code's own definitions (:data:`factask.vocabulary.kinds.ASSET_KINDS`,
:data:`factask.vocabulary.palette.COLOR_NAMES`,
:data:`factask.relations.RELATION_TYPES` with docstrings and JSON
Schemas), so a prompt can never advertise something the library lacks.

The template directory is ``$FACTASK_PROMPTS`` if set (to try edited prompts),
else the ``prompts`` folder inside the installed package (it ships in the wheel).
"""

from __future__ import annotations

import inspect
import json
import os
import re
from collections.abc import Mapping
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any

from pydantic import BaseModel

from factask.relations import RELATION_TYPES
from factask.vocabulary.errors import FactaskError
from factask.vocabulary.kinds import ASSET_KINDS
from factask.vocabulary.palette import COLOR_NAMES
from factask.vocabulary.variables import (
    AtFixedPose,
    InCabinet,
    InRegion,
    MountedOn,
    OnTable,
    StartInside,
    StartOn,
)
from factask.vocabulary.world import WORKSPACE_X, WORKSPACE_Y

_PLACEHOLDER_RE = re.compile(r"\{\{\s*([a-z_][a-z0-9_]*)\s*\}\}")

#: The step templates every strategy needs (file stem -> purpose).
STEP_TEMPLATES = {
    "system": "shared system message: the vocabulary and the rules",
    "system_compact": "the system message for small contexts: a vocabulary summary",
    "one_shot": "baseline: the whole graph in one answer",
    "variables": "approach 1 step 1: the state variables",
    "subtask_plan": "approach 1 step 2: subtasks over subsets of the variables",
    "subtask_goal": "approach 1 step 3: one subtask's goal relation",
    "subtask_outline": "approach 2 step 1: subtask names and descriptions",
    "subtask_design": "approach 2 step 2: one subtask's variables and goal",
    "assembly": "approaches 1 and 2: repair the assembled graph",
    "feedback": "a failed check sent back to the model",
}


class PromptError(FactaskError):
    """A template is missing, or its placeholders and the values do not match."""


def prompts_dir() -> Path:
    """The template directory (see the module docstring).

    Raises:
        PromptError: none of the candidate directories exists.
    """
    env = os.environ.get("FACTASK_PROMPTS")
    candidates = [Path(env)] if env else []
    candidates.append(Path(str(resources.files("factask") / "prompts")))
    for c in candidates:
        if (c / "system.md").is_file():
            return c
    raise PromptError("prompt templates not found; looked in "
                      + ", ".join(str(c) for c in candidates) + " (set FACTASK_PROMPTS)")


@lru_cache(maxsize=64)
def _read(path: str, mtime: float) -> str:
    return Path(path).read_text(encoding="utf-8")


def load_template(step: str) -> str:
    """The text of the template ``<step>.md``.

    Raises:
        PromptError: no such template.
    """
    path = prompts_dir() / f"{step}.md"
    if not path.is_file():
        raise PromptError(f"no prompt template {path}")
    return _read(str(path), path.stat().st_mtime)


def placeholders(template: str) -> set[str]:
    """Names of the ``{{placeholders}}`` of a template."""
    return set(_PLACEHOLDER_RE.findall(template))


def render(step: str, /, **values: Any) -> str:
    """Fill the template ``<step>.md``.

    Args:
        step: Template name (positional: ``step`` is also a placeholder name).
        **values: One value per placeholder (converted with ``str``). The shared
            vocabulary (``asset_kinds``, ``colors``, ``relations``, ``placements``,
            ``world``) is filled in automatically.

    Returns:
        The prompt text.

    Raises:
        PromptError: a placeholder has no value, or a value has no placeholder
            (a typo in either would otherwise silently drop information).
    """
    template = load_template(step)
    wanted = placeholders(template)
    vocab = compact_vocabulary() if step == "system_compact" else vocabulary()
    given = dict(values)
    for k in wanted & set(vocab):
        given.setdefault(k, vocab[k])
    missing = wanted - set(given)
    if missing:
        raise PromptError(f"template {step!r} needs values for {sorted(missing)}")
    extra = set(values) - wanted
    if extra:
        raise PromptError(f"template {step!r} has no placeholder(s) {sorted(extra)}")
    return _PLACEHOLDER_RE.sub(lambda m: str(given[m.group(1)]), template)


# ------------------------------------------------------------------ vocabulary
def _strip_titles(value: Any) -> Any:
    if isinstance(value, dict):
        return {k: _strip_titles(v) for k, v in value.items() if k != "title"}
    if isinstance(value, list):
        return [_strip_titles(v) for v in value]
    return value


def compact_schema(model: type[BaseModel], drop: tuple[str, ...] = ()) -> dict[str, Any]:
    """A model's JSON Schema without titles and without the ``drop`` properties."""
    schema = _strip_titles(model.model_json_schema())
    # The docstring is printed next to the schema; do not repeat it.
    schema.pop("description", None)
    for name in drop:
        schema.get("properties", {}).pop(name, None)
        if name in schema.get("required", []):
            schema["required"].remove(name)
    defs = schema.get("$defs", {})
    text = json.dumps({k: v for k, v in schema.items() if k != "$defs"})
    used = {k: v for k, v in defs.items() if f"#/$defs/{k}" in text}
    if used:
        schema["$defs"] = used
    else:
        schema.pop("$defs", None)
    return schema


def _doc(obj: Any) -> str:
    return " ".join((inspect.getdoc(obj) or "").split())


def asset_kinds_text() -> str:
    """One line per asset kind: description, default size, capabilities."""
    lines = []
    for spec in ASSET_KINDS.values():
        caps = [c for c in ("movable", "support", "receptacle", "region", "round")
                if getattr(spec, c)]
        if not spec.movable:
            caps.insert(0, "fixed")
        if not spec.collides:
            caps.append("no collision")
        size = ", ".join(f"{s:g}" for s in spec.default_size)
        lines.append(f"- `{spec.name}`: {spec.description}; default size [{size}]; "
                     f"{', '.join(caps)}")
    return "\n".join(lines)


def colors_text() -> str:
    """The palette's colour names."""
    return ", ".join(COLOR_NAMES)


def relations_text() -> str:
    """Each relation type: its docstring and the JSON Schema of its parameters."""
    blocks = []
    for name, cls in RELATION_TYPES.items():
        schema = compact_schema(cls, drop=("tolerances",))
        blocks.append(f"- `{name}`: {_doc(cls)}\n  parameters: "
                      f"{json.dumps(schema, separators=(',', ':'))}")
    return "\n".join(blocks)


def placements_text() -> str:
    """Each initial placement of a variable (field ``initial``)."""
    lines = []
    for cls in (OnTable, InRegion, StartOn, StartInside, AtFixedPose, InCabinet,
                MountedOn):
        kind = cls.model_fields["type"].default
        schema = compact_schema(cls)
        lines.append(f"- `{kind}`: {_doc(cls)} {json.dumps(schema, separators=(',', ':'))}")
    return "\n".join(lines)


def world_text() -> str:
    """The workspace in one sentence."""
    return (f"Table top at z = 0; workspace x in [{WORKSPACE_X[0]}, {WORKSPACE_X[1]}] m, "
            f"y in [{WORKSPACE_Y[0]}, {WORKSPACE_Y[1]}] m; a suction gripper picks objects "
            "from above and places them.")


@lru_cache(maxsize=1)
def _vocabulary() -> tuple[tuple[str, str], ...]:
    return (("asset_kinds", asset_kinds_text()), ("colors", colors_text()),
            ("relations", relations_text()), ("placements", placements_text()),
            ("world", world_text()))


def vocabulary() -> dict[str, str]:
    """The shared placeholders, rendered from the code's definitions."""
    return dict(_vocabulary())


def schema_text(schema: Mapping[str, Any]) -> str:
    """A step schema for the prompt (titles dropped, compact JSON)."""
    return json.dumps(_strip_titles(dict(schema)), separators=(",", ":"))


# ------------------------------------------------------- compact variants
@lru_cache(maxsize=1)
def _compact_vocabulary() -> tuple[tuple[str, str], ...]:
    kinds = "; ".join(f"{s.name} [{', '.join(f'{x:g}' for x in s.default_size)}]"
                      + ("" if s.movable else " fixed") for s in ASSET_KINDS.values())
    relations = "; ".join(
        f"{name}: " + ", ".join(f for f in cls.model_fields if f not in ("type", "tolerances",
                                                                         "matches"))
        for name, cls in RELATION_TYPES.items())
    placements = "table (default, a free spot), pose (x, y, yaw_deg), on (support), " \
                 "inside (container)"
    return (("asset_kinds", kinds), ("colors", colors_text()), ("relations", relations),
            ("placements", placements), ("world", world_text()))


def compact_vocabulary() -> dict[str, str]:
    """The vocabulary in a few lines (names and fields only), for small contexts."""
    return dict(_compact_vocabulary())


def schema_skeleton(schema: Mapping[str, Any], limit: int = 6) -> str:
    """An outline of the answer a JSON Schema describes: fields with their allowed
    values (``a|b|c``, at most ``limit`` shown), alternatives joined by ``OR``.

    Args:
        schema: A strict step schema (:mod:`factask.gen.answers.step_schemas`).
        limit: Enum values shown before ``...``.

    Returns:
        Compact text, far shorter than the schema.
    """
    def walk(node: Any) -> str:
        if not isinstance(node, Mapping):
            return "?"
        if "const" in node:
            return json.dumps(node["const"])
        if "enum" in node:
            vals = [str(v) for v in node["enum"]]
            shown = "|".join(vals[:limit]) + ("|..." if len(vals) > limit else "")
            return f'"{shown}"'
        if "anyOf" in node:
            return " OR ".join(walk(n) for n in node["anyOf"])
        kind = node.get("type")
        if kind == "object":
            inner = ", ".join(f'"{k}": {walk(v)}' for k, v in node.get("properties", {}).items())
            return "{" + inner + "}"
        if kind == "array":
            return f"[{walk(node.get('items', {}))}, ...]"
        if kind == "string":
            return '"<name>"' if "a-z" in str(node.get("pattern", "")) and \
                "{0,15}" in str(node.get("pattern", "")) else '"<text>"'
        if kind in ("number", "integer"):
            lo, hi = node.get("minimum", node.get("exclusiveMinimum")), node.get("maximum")
            return f"<{kind} {lo}..{hi}>" if lo is not None and hi is not None else f"<{kind}>"
        return f"<{kind}>"

    return walk(schema)
