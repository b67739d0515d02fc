"""Subtask memory: verified subtasks saved on disk and retrieved as examples.

Every subtask that passed the whole ladder in one task is stored as a one-factor
fragment (the factor, weight 1, with its scope variables), one JSON file per
subtask in a directory (argument, or ``FACTASK_MEMORY``). Later generations get
the most similar ones (word overlap) as in-context examples.
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path
from typing import Any

from factask.gen.answers.examples import Example, same_task, top_k
from factask.graph.taskgraph import TaskGraph, parse_graph
from factask.vocabulary.errors import FactaskError


class SubtaskMemoryError(FactaskError):
    """The memory directory cannot be written."""


class SubtaskMemory:
    """A directory of verified subtask fragments.

    Args:
        directory: Where the entries live (created on first save).
    """

    def __init__(self, directory: str | os.PathLike[str]) -> None:
        self.directory = Path(directory)

    @classmethod
    def from_env(cls, directory: str | os.PathLike[str] | None = None) -> SubtaskMemory | None:
        """The memory at ``directory``, else at ``$FACTASK_MEMORY``, else None."""
        where = directory or os.environ.get("FACTASK_MEMORY")
        return cls(where) if where else None

    def save(self, fragment: TaskGraph, task: str, approach: str) -> Path:
        """Store a verified one-factor fragment (idempotent: same content, same file).

        Args:
            fragment: The fragment (one factor, weight 1, its variables).
            task: Name of the task it was verified in.
            approach: The generation approach that produced it.

        Returns:
            The entry's path.

        Raises:
            SubtaskMemoryError: the directory cannot be written.
        """
        data = fragment.to_dict()
        digest = hashlib.sha256(json.dumps(data, sort_keys=True).encode()).hexdigest()[:12]
        name = fragment.factors[0].name if fragment.factors else fragment.name
        path = self.directory / f"{name}-{digest}.json"
        entry = {"name": name, "description": fragment.description, "task": task,
                 "approach": approach, "fragment": data}
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
            tmp = path.with_suffix(f".{os.getpid()}.tmp")
            tmp.write_text(json.dumps(entry, indent=1))
            os.replace(tmp, path)
        except OSError as exc:
            raise SubtaskMemoryError(
                f"cannot write subtask memory {self.directory}: {exc}") from None
        return path

    def entries(self) -> list[dict[str, Any]]:
        """Every readable, valid entry (unreadable or invalid files are skipped)."""
        out = []
        if not self.directory.is_dir():
            return out
        for path in sorted(self.directory.glob("*.json")):
            try:
                entry = json.loads(path.read_text())
                parse_graph(entry["fragment"])  # only valid fragments are shown
            except Exception:
                continue
            out.append(entry)
        return out

    def retrieve(self, query: str, k: int = 3, exclude_task: str | None = None) -> list[Example]:
        """The ``k`` entries most similar to ``query`` as examples.

        Args:
            query: Retrieval text.
            k: How many.
            exclude_task: The task being generated: entries verified in that task
                (or a near-duplicate of it, :func:`~factask.gen.answers.examples.same_task`)
                are left out, so a task never sees its own earlier answers.
        """
        candidates = [
            Example("memory", e["name"], e.get("description", ""), e["fragment"],
                    note=f"verified in task {e.get('task', '?')}")
            for e in self.entries()
            if not (exclude_task and same_task(str(e.get("task", "")), exclude_task))
        ]
        return top_k(candidates, query, k)

    def __len__(self) -> int:
        return len(self.entries())
