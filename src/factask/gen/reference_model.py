"""Reference "models": each step answered from a task's reference graph, perfectly or
with typical model errors.

A capable remote model that understood the proposal would answer every step with
the task it means. ``local/reference`` does exactly that from the reference graph
(the library's graph of a 192-list task, a proposal set's ``reference``): one-shot
and assembly get the whole graph, variables-first the variables, a plan (in an order
the reference allows, ``after`` where it orders subtasks) and each subtask's goal,
subtasks-first an outline and each subtask's variables and goal. Every answer is put
in its step's own form (the step's strict schema: fields it does not ask for left
out, texts cut to its length and characters) and cut at the request's
``max_tokens`` (about :data:`CHARS_PER_TOKEN` characters a token), as a provider
would. Served by the loopback server and reached through litellm on the *ungrounded*
path remote models take, it shows what the pipeline does with the right answers:
100 % faithful is the target, and anything less is a place the pipeline loses a
correct task.

``local/noisy-reference`` (``local/noisy-reference:0.3`` for another rate; default
:data:`DEFAULT_NOISE`) first answers a step with one typical error at that rate
(:data:`ERROR_KINDS`: an unknown name, a missing field, a kind not in the
vocabulary, a goal on itself, a cut-off answer), chosen by hashing the task and step
(:func:`planned_error`: the same run, the same errors), and answers every repair
correctly. :func:`repair_table` reads a benchmark's records back into how often each
kind of error was caught, repaired, and ended in a faithful task.
"""

from __future__ import annotations

import hashlib
import json
import re
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

from factask.gen.answers import step_schemas as ss
from factask.gen.first_choice import first_choice, resolve_ref
from factask.gen.fragments import closure
from factask.gen.loopback import CutReply, conversation_step
from factask.gen.strategies import given_name
from factask.gen.verify import LEVELS
from factask.graph.taskgraph import TaskGraph
from factask.graph.templates import rename
from factask.vocabulary.errors import FactaskError

#: The model names (``--model``) of the perfect and the noisy reference.
REFERENCE_MODEL = "local/reference"
NOISY_REFERENCE_MODEL = "local/noisy-reference"
#: Share of first answers the noisy reference spoils when its name gives no rate.
DEFAULT_NOISE = 0.3
#: Characters per token used to honour ``max_tokens`` (JSON runs about 3 to 4).
CHARS_PER_TOKEN = 3
#: The errors the noisy reference makes, each where its step can hold it.
ERROR_KINDS = ("unknown_name", "missing_field", "wrong_kind", "goal_on_itself", "cut_off")
_STEP_ERRORS: dict[str, tuple[str, ...]] = {
    "one_shot": ERROR_KINDS, "assembly": ERROR_KINDS, "subtask_design": ERROR_KINDS,
    "variables": ("unknown_name", "missing_field", "wrong_kind", "cut_off"),
    "subtask_plan": ("unknown_name", "missing_field", "cut_off"),
    "subtask_goal": ("unknown_name", "missing_field", "goal_on_itself", "cut_off"),
    "subtask_outline": ("unknown_name", "missing_field", "cut_off"),
}
#: Words a model writes for a kind that the vocabulary calls otherwise.
_WRONG_KINDS = {"block": "cube", "bowl": "dish", "zone": "area", "box": "crate",
                "container": "bin", "cylinder": "can", "pallet": "tray"}
_TASK_RE = re.compile(r"^Task `(?P<task>[^`]+)`:", re.MULTILINE)


class ReferenceModelError(FactaskError):
    """A reference model name that cannot be read (``local/noisy-reference:RATE``)."""


def is_reference_model(model: str | None) -> bool:
    """True for ``local/reference`` and ``local/noisy-reference[:RATE]``."""
    return bool(model) and (model in (REFERENCE_MODEL, NOISY_REFERENCE_MODEL)
                            or str(model).startswith(NOISY_REFERENCE_MODEL + ":"))


def noise_of(model: str) -> float:
    """The share of first answers a reference model name spoils (0 for the perfect one).

    Raises:
        ReferenceModelError: a rate that is not a number in [0, 1].
    """
    if model == REFERENCE_MODEL:
        return 0.0
    if model == NOISY_REFERENCE_MODEL:
        return DEFAULT_NOISE
    text = model.split(":", 1)[1]
    try:
        rate = float(text)
    except ValueError:
        rate = -1.0
    if not 0.0 <= rate <= 1.0:
        raise ReferenceModelError(f"{model!r}: the noise rate after ':' must be a number in "
                                  f"[0, 1], e.g. {NOISY_REFERENCE_MODEL}:0.3")
    return rate


def _uniform(*parts: object) -> float:
    digest = hashlib.blake2b("|".join(map(str, parts)).encode(), digest_size=8).digest()
    return int.from_bytes(digest, "big") / 2**64


def planned_error(task: str, step: str, rate: float, seed: int = 0) -> str | None:
    """The error the noisy reference makes in its first answer to ``step`` of ``task``.

    Args:
        task: The task's name as the prompt gives it.
        step: The step as records name it (``subtask_goal:<subtask>``).
        rate: Share of first answers spoiled.
        seed: Another seed, other errors.

    Returns:
        One of :data:`ERROR_KINDS`, or None (the right answer).
    """
    kinds = _STEP_ERRORS.get(step.split(":", 1)[0], ())
    task = given_name(task)
    if not kinds or _uniform(seed, task, step, "spoil") >= rate:
        return None
    return kinds[int(_uniform(seed, task, step, "kind") * len(kinds))]


# ------------------------------------------------------------------ step forms
def fit(data: Any, schema: Mapping[str, Any]) -> Any:
    """``data`` put in the form ``schema`` asks for, as a model that follows the schema
    writes it: properties it does not ask for left out, required ones it lacks filled
    (null, an empty list or text, else the schema's first choice), texts with the
    schema's characters and length, numbers in range; in an ``anyOf`` the branch
    whose ``type`` the data names. Lists keep every item (a task that needs more
    objects than a step allows is the pipeline's to refuse or take).

    Args:
        data: A decoded answer (the reference's own form).
        schema: The step's strict schema.

    Returns:
        The answer in the step's form.
    """
    return _Fitter(schema).fit(data, schema)


class _Fitter:
    def __init__(self, root: Mapping[str, Any]) -> None:
        self.root = root

    def deref(self, node: Any) -> Any:
        for _ in range(64):  # a chain of references, never a cycle
            if not (isinstance(node, Mapping) and "$ref" in node):
                return node
            node = resolve_ref(str(node["$ref"]), self.root)
        return node

    def fit(self, data: Any, node: Any) -> Any:
        node = self.deref(node)
        if not isinstance(node, Mapping):
            return data
        if "const" in node:
            return node["const"]
        branches = node.get("anyOf") or node.get("oneOf")
        if branches:
            return self.fit(data, self.branch(data, branches))
        kind = node.get("type")
        if isinstance(data, Mapping) and (kind == "object" or "properties" in node):
            return self.fit_object(data, node)
        if isinstance(data, list) and kind == "array":
            items = list(data)  # as many as the task needs: the pipeline judges the count
            prefix = node.get("prefixItems")
            if prefix:
                return [self.fit(x, prefix[i]) if i < len(prefix) else x
                        for i, x in enumerate(items)]
            return [self.fit(x, node.get("items", {})) for x in items]
        if isinstance(data, str) and kind == "string" and "enum" not in node:
            return _text(data, node)
        if isinstance(data, (int, float)) and not isinstance(data, bool) \
                and kind in ("number", "integer"):
            low = node.get("minimum", node.get("exclusiveMinimum"))
            high = node.get("maximum", node.get("exclusiveMaximum"))
            value = data if low is None else max(data, low)
            return value if high is None else min(value, high)
        return data

    def branch(self, data: Any, branches: Sequence[Any]) -> Any:
        resolved = [self.deref(b) for b in branches]
        if data is None:
            return next((b for b in resolved if b.get("type") == "null"), resolved[0])
        if isinstance(data, Mapping) and "type" in data:
            for b in resolved:
                tag = self.deref((b.get("properties") or {}).get("type", {}))
                if data["type"] == tag.get("const") or data["type"] in tag.get("enum", ()):
                    return b
        wanted = {dict: "object", list: "array", str: "string", bool: "boolean",
                  int: "integer", float: "number"}.get(type(data))
        for b in resolved:
            if b.get("type") == wanted or (wanted == "integer" and b.get("type") == "number"):
                return b
        return resolved[0]

    def fit_object(self, data: Mapping[str, Any], node: Mapping[str, Any]) -> dict[str, Any]:
        props: Mapping[str, Any] = node.get("properties", {})
        out: dict[str, Any] = {}
        for key, value in data.items():
            if key in props:
                out[key] = self.fit(value, props[key])
            elif node.get("additionalProperties", True) is not False:
                out[key] = value
        for key in node.get("required", ()):
            if key not in out:
                out[key] = self.missing(props.get(key, {}))
        return out

    def missing(self, node: Any) -> Any:
        node = self.deref(node)
        branches = node.get("anyOf") or node.get("oneOf") or ()
        if any(self.deref(b).get("type") == "null" for b in branches):
            return None
        if node.get("type") == "array":
            return []
        if node.get("type") == "string" and "enum" not in node and "pattern" not in node:
            return ""
        return first_choice({**self.root, **node})


def _text(value: str, node: Mapping[str, Any]) -> str:
    """A free text in a step's characters (no quotes, backslashes or control
    characters) and length, cut at a word."""
    if node.get("pattern") == ss.TEXT_PATTERN:
        value = " ".join(value.replace('"', "'").replace("\\", "/").split())
    limit = node.get("maxLength")
    if limit is not None and len(value) > limit:
        cut = value[:limit]
        value = cut.rsplit(" ", 1)[0] if " " in cut else cut
    return value


# ------------------------------------------------------------------ answers
def _dump(model: Any) -> Any:
    return model.model_dump(mode="json", exclude_none=True)


def listed_factors(graph: TaskGraph) -> list[Any]:
    """The reference's factors in an order it allows (its listing where it can)."""
    by_name = {f.name: f for f in graph.factors}
    return [by_name[n] for n in graph.factor_order()]


def _subtask_of(graph: TaskGraph, subtask: str | None) -> Any:
    by_name = {f.name: f for f in graph.factors}
    if subtask in by_name:
        return by_name[subtask]
    # a name the pipeline made distinct ("put_block_2"): its stem
    stem = re.sub(r"_\d+$", "", subtask or "")
    return by_name.get(stem) or graph.factors[0]


def _closure(graph: TaskGraph, names: Iterable[str]) -> list[Any]:
    """The variables named, with every variable their starts rest on, in graph order."""
    pool = {v.name: v for v in graph.variables}
    wanted = {v.name for v in closure([pool[n] for n in names if n in pool], pool)}
    return [v for v in graph.variables if v.name in wanted]


def in_step_names(graph: TaskGraph) -> TaskGraph:
    """``graph`` with every name the steps' name pattern refuses shortened to one it
    takes (at most four parts of 15 characters: ``pile_in_zone_red_pile`` ->
    ``pile_in_zone_red``), as a model following the schema names them."""
    pattern = re.compile(ss.NAME_REGEX)
    names = [v.name for v in graph.variables] + [f.name for f in graph.factors]
    used = {n for n in names if pattern.match(n)}
    mapping: dict[str, str] = {}
    for n in names:
        if pattern.match(n):
            continue
        parts = [p[:15] for p in n.split("_") if p][:4] or ["x"]
        if not parts[0][0].isalpha():
            parts[0] = "n" + parts[0][:14]
        short = "_".join(parts)
        while short in used:  # a free variant that still fits the pattern
            parts = [*parts[:3], f"{len(used)}"]
            short = "_".join(parts)
        used.add(short)
        mapping[n] = short
    return rename(graph, mapping) if mapping else graph


def reference_answer(graph: TaskGraph, step: str, subtask: str | None) -> dict[str, Any]:
    """What a model that means ``graph`` answers to ``step`` (the reference's form).

    Args:
        graph: The reference graph.
        step: The step (``one_shot``, ``variables``, ``subtask_plan``, ...).
        subtask: The subtask a per-subtask step is about.

    Returns:
        The answer as data.

    Raises:
        ReferenceModelError: a step the reference cannot answer.
    """
    factors = listed_factors(graph)
    if step in ("one_shot", "assembly"):
        data = _dump(graph)
        data["factors"] = [_dump(f) for f in factors]
        return data
    if step == "variables":
        return {"variables": [_dump(v) for v in graph.variables]}
    if step in ("subtask_plan", "subtask_outline"):
        subtasks = []
        for f in factors:
            item = {"name": f.name, "description": f.description, "after": list(f.after)}
            if step == "subtask_plan":
                item["variables"] = [v.name for v in _closure(graph, f.scope_names)]
                item["initial_setup"] = f.initial_setup
            subtasks.append(item)
        return {"subtasks": subtasks}
    factor = _subtask_of(graph, subtask)
    if step == "subtask_goal":
        return {"goal": _dump(factor.goal), "description": factor.description}
    if step == "subtask_design":
        named = set(factor.scope_names)
        if factor.name == factors[0].name:  # objects no subtask uses come with the first
            used = {n for f in graph.factors for n in f.scope_names}
            named |= {v.name for v in graph.variables if v.name not in used}
        return {"variables": [_dump(v) for v in _closure(graph, named)],
                "goal": _dump(factor.goal), "description": factor.description}
    raise ReferenceModelError(f"the reference model has no answer for step {step!r}")


# ------------------------------------------------------------------ errors
def _goals(data: dict[str, Any]) -> list[dict[str, Any]]:
    if isinstance(data.get("goal"), dict):
        return [data["goal"]]
    return [f["goal"] for f in data.get("factors", []) if isinstance(f.get("goal"), dict)]


def spoil(data: dict[str, Any], kind: str) -> dict[str, Any] | str:
    """``data`` with one error of ``kind`` (a cut-off answer is text).

    Args:
        data: A right answer in its step's form.
        kind: One of :data:`ERROR_KINDS`.

    Returns:
        The spoiled answer (a copy).
    """
    data = json.loads(json.dumps(data))
    text = json.dumps(data, separators=(",", ":"))
    goals = _goals(data)
    variables = data.get("variables") if isinstance(data.get("variables"), list) else []
    variables = [v for v in variables if isinstance(v, dict)]
    if kind == "cut_off":
        return text[:max(1, len(text) // 2)]
    if kind == "unknown_name":
        if goals and goals[0].get("objects"):
            goals[0]["objects"][0] = goals[0]["objects"][0] + "s"
        elif data.get("subtasks"):
            first = data["subtasks"][-1]
            if first.get("variables"):
                first["variables"][0] = first["variables"][0] + "s"
            else:
                first["after"] = ["first_step"]
        elif variables:
            variables[-1]["initial"] = {"type": "on", "support": "tray"}
        return data
    if kind == "missing_field":
        if goals:
            goals[0].pop("objects", None)
        elif data.get("subtasks"):
            data["subtasks"][0].pop("description", None)
        elif variables:
            variables[0].pop("kind", None)
        return data
    if kind == "wrong_kind" and variables:
        v = variables[0]
        v["kind"] = _WRONG_KINDS.get(str(v.get("kind")), f"{v.get('kind')}_shape")
        return data
    if kind == "goal_on_itself" and goals:
        goal = goals[0]
        anchors = [k for k in ("support", "container", "zone", "base", "reference", "along")
                   if k in goal]
        objects = goal.get("objects") or []
        if objects and anchors:
            goal[anchors[0]] = objects[0]
        elif objects:
            goal["objects"] = [objects[0], *objects]
        return data
    return data


# ------------------------------------------------------------------ responder
class ReferenceResponder:
    """Answers each request from the reference graph of the task its prompt names.

    Args:
        references: Reference graphs by task name (the prompt's ``Task `name```).
        noise: Share of first answers spoiled (:func:`planned_error`).
        seed: Another seed, other errors.

    Attributes:
        spoiled: ``(task, step, kind)`` of every spoiled answer, in order.
    """

    def __init__(self, references: Mapping[str, TaskGraph], noise: float = 0.0,
                 seed: int = 0) -> None:
        self.references = {given_name(k): in_step_names(g) for k, g in references.items()}
        self.noise = noise
        self.seed = seed
        self.spoiled: list[tuple[str, str, str]] = []

    def __call__(self, request: dict[str, Any]) -> str:
        messages = request.get("messages", [])
        step, subtask = conversation_step(messages)
        first_user = next((str(m.get("content", "")) for m in messages
                           if m.get("role") == "user"), "")
        found = _TASK_RE.search(first_user)
        task = found.group("task") if found else ""
        graph = self.references.get(task)
        if graph is None:
            return f"I have no reference graph for task {task!r}."
        data = reference_answer(graph, step, subtask)
        schema = _step_schema(request)
        if schema is not None:
            data = fit(data, schema)
        key = f"{step}:{subtask}" if subtask else step
        kind = None
        if not any(m.get("role") == "assistant" for m in messages):
            kind = planned_error(task, key, self.noise, self.seed)
        answer: Any = spoil(data, kind) if kind else data
        if kind:
            self.spoiled.append((task, key, kind))
        text = answer if isinstance(answer, str) else json.dumps(answer, separators=(",", ":"))
        cap = request.get("max_tokens")
        if isinstance(cap, int) and cap > 0 and len(text) > cap * CHARS_PER_TOKEN:
            return CutReply(text[:cap * CHARS_PER_TOKEN])
        return text


def _step_schema(request: Mapping[str, Any]) -> Mapping[str, Any] | None:
    """The strict schema the request carries (``response_format: json_schema``)."""
    form = request.get("response_format")
    if isinstance(form, Mapping):
        inner = form.get("json_schema")
        if isinstance(inner, Mapping) and isinstance(inner.get("schema"), Mapping):
            return inner["schema"]
    return None


# ------------------------------------------------------------------ reading runs
def repair_table(records: Iterable[Mapping[str, Any]], rate: float,
                 seed: int = 0) -> dict[str, dict[str, int]]:
    """How the pipeline met each kind of error the noisy reference made in a run.

    Args:
        records: A benchmark's records (``results.jsonl`` lines).
        rate: The noise rate the run used.
        seed: Its seed.

    Returns:
        Per kind: ``made`` (first answers spoiled), ``caught`` (that answer refused),
        ``repaired`` (a later answer of the step passed it, or reached a higher level
        of the ladder: a whole graph that then ends ``partial`` for words its
        reference leaves unread is mended all the same), ``faithful`` (the
        generation ended faithful).
    """
    table = {k: {"made": 0, "caught": 0, "repaired": 0, "faithful": 0} for k in ERROR_KINDS}
    for record in records:
        steps = record.get("steps") or []
        for key in dict.fromkeys(s["step"] for s in steps):
            kind = planned_error(str(record.get("task", "")), key, rate, seed)
            if kind is None:
                continue
            # the assembly's attempt 0 checks the assembled graph: no answer yet
            tries = [s for s in steps if s["step"] == key
                     and not (key == "assembly" and s["attempt"] == 0)]
            if not tries:
                continue
            row = table[kind]
            row["made"] += 1
            row["caught"] += not tries[0]["ok"]
            first = LEVELS.index(tries[0].get("level", "none"))
            row["repaired"] += not tries[0]["ok"] and any(
                s["ok"] or LEVELS.index(s.get("level", "none")) > first for s in tries[1:])
            row["faithful"] += bool(record.get("faithful"))
    return table


__all__ = ["CHARS_PER_TOKEN", "DEFAULT_NOISE", "ERROR_KINDS", "NOISY_REFERENCE_MODEL",
           "REFERENCE_MODEL", "ReferenceModelError", "ReferenceResponder", "fit",
           "is_reference_model", "listed_factors", "noise_of", "planned_error",
           "reference_answer", "repair_table", "spoil"]
