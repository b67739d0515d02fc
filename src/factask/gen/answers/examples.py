"""In-context examples: library task graphs, subtask templates and remembered
subtasks, retrieved by simple word overlap with the proposal.

The research found that showing a few successful subtask designs fixed the
granularity problem; the examples here are real, valid library objects, so a
prompt never shows something the library cannot do.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from factask.library import get_task, task_names
from factask.library.templates import TEMPLATES

_WORD_RE = re.compile(r"[a-z]+")
# Words that say nothing about which task is meant.
_STOP = frozenset([
    "a", "an", "the", "and", "or", "of", "to", "in", "on", "into", "onto", "with",
    "without", "then", "than", "for", "from", "by", "at", "as", "is", "are", "be", "it",
    "its", "their", "them", "each", "every", "all", "one", "two", "three", "four", "five",
    "six", "put", "place", "pick", "move", "make", "build", "task", "tasks", "object",
    "objects", "top", "other", "using", "use",
])


def words(text: str) -> set[str]:
    """Content words of ``text`` (lower case, split on non-letters, stop words out,
    trailing plural ``s`` stripped so "blocks" meets "block")."""
    out = set()
    for w in _WORD_RE.findall(text.lower().replace("_", " ").replace("-", " ")):
        if w in _STOP or len(w) < 2:
            continue
        out.add(w[:-1] if len(w) > 3 and w.endswith("s") and not w.endswith("ss") else w)
    return out


#: Name-token overlap at or above which two task names count as the same task.
NEAR_DUPLICATE_RATIO = 0.8


def normalise_name(name: str) -> str:
    """A task name reduced to lower-case letters and digits joined by ``-``."""
    return "-".join(re.findall(r"[a-z0-9]+", name.lower()))


def same_task(a: str, b: str) -> bool:
    """True if task names ``a`` and ``b`` denote the same task: equal after
    :func:`normalise_name`, or sharing at least :data:`NEAR_DUPLICATE_RATIO` of
    their name tokens (``|A & B| / max(|A|, |B|)``, plurals folded)."""
    if not a or not b:
        return False
    na, nb = normalise_name(a), normalise_name(b)
    if na == nb:
        return True
    ta, tb = _name_tokens(na), _name_tokens(nb)
    if not ta or not tb:
        return False
    return len(ta & tb) / max(len(ta), len(tb)) >= NEAR_DUPLICATE_RATIO


def _name_tokens(name: str) -> set[str]:
    return {t[:-1] if len(t) > 3 and t.endswith("s") and not t.endswith("ss") else t
            for t in name.split("-") if t}


def overlap(query: str, text: str) -> int:
    """Number of content words ``query`` and ``text`` share."""
    return len(words(query) & words(text))


@dataclass
class Example:
    """One in-context example.

    Attributes:
        source: ``library-task``, ``template`` or ``memory``.
        name: Its name.
        description: Its description.
        payload: The JSON shown to the model.
        score: Word overlap with the query.
        note: Shown to the model but not used for retrieval (e.g. the source task).
    """

    source: str
    name: str
    description: str
    payload: dict[str, Any]
    score: int = 0
    note: str = ""

    def render(self) -> str:
        """Markdown block: a title line and the JSON."""
        note = f" ({self.note})" if self.note else ""
        return (f"Example ({self.source}) `{self.name}`: {self.description}{note}\n```json\n"
                f"{json.dumps(self.payload, separators=(',', ':'))}\n```")


def top_k(candidates: Iterable[Example], query: str, k: int) -> list[Example]:
    """The ``k`` best candidates by word overlap (ties keep the input order);
    candidates sharing no word are used only to fill up to ``k``."""
    scored = []
    for i, c in enumerate(candidates):
        c.score = overlap(query, f"{c.name} {c.description}")
        scored.append((-c.score, i, c))
    scored.sort(key=lambda t: (t[0], t[1]))
    return [c for _, _, c in scored[:k]]


def library_task_examples(query: str, k: int = 2, exclude: str | None = None) -> list[Example]:
    """Whole library task graphs most similar to ``query``.

    Args:
        query: Retrieval text (the proposal).
        k: How many.
        exclude: The task being generated: a library task of the same name (or a
            near-duplicate, :func:`same_task`) is never shown, so a benchmark task
            that also exists in the library is not given its own answer.
    """
    candidates = []
    try:
        for name in task_names():
            if exclude and same_task(name, exclude):
                continue
            graph = get_task(name)
            if exclude and same_task(graph.name, exclude):
                continue
            candidates.append(Example("library-task", graph.name, graph.description,
                                      graph.to_dict()))
    except Exception:  # a broken library entry must not break generation
        return []
    return top_k(candidates, query, k)


def template_examples(query: str, k: int = 3) -> list[Example]:
    """Subtask templates most similar to ``query``."""
    values = TEMPLATES.values() if isinstance(TEMPLATES, dict) else TEMPLATES
    candidates = []
    for t in values:
        try:
            payload = t.model_dump(mode="json", exclude_none=True)
        except AttributeError:
            continue
        candidates.append(Example("template", t.name, t.description, payload))
    return top_k(candidates, query, k)


def render_examples(examples: Iterable[Example]) -> str:
    """All examples as Markdown, or a line saying there are none."""
    blocks = [e.render() for e in examples]
    return "\n\n".join(blocks) if blocks else "(no examples available)"
