"""Regenerate the template and task tables of docs/library.md from the registry.

The tables sit between ``<!-- templates:begin -->``/``<!-- templates:end -->`` and
``<!-- tasks:begin -->``/``<!-- tasks:end -->``: one row per template (slots, its
factors' relations, the tasks using it) and one per task (family, sizes,
templates, description), read from the code so the page cannot drift. Run:
``.venv/bin/python scripts/library_docs.py``.
"""

from __future__ import annotations

from pathlib import Path

from factask.library import TEMPLATES, list_tasks
from factask.library.builders import FAMILIES

DOC = Path(__file__).resolve().parents[1] / "docs" / "library.md"


def table() -> str:
    """The markdown table of every library task."""
    rows = ["| task | family | variables | factors | movable | templates | description |",
            "|---|---|---|---|---|---|---|"]
    for i in list_tasks():
        desc = i.description.replace("|", "/")
        rows.append(f"| `{i.name}` | {FAMILIES.get(i.name, '')} | {i.n_variables} | "
                    f"{i.n_factors} | {i.n_movable} | {', '.join(i.templates)} | {desc} |")
    return "\n".join(rows)


def template_table() -> str:
    """The markdown table of every template and the tasks that use it."""
    users: dict[str, list[str]] = {t: [] for t in TEMPLATES}
    for i in list_tasks():
        for t in i.templates:
            if t in users:  # a task's own template (unregistered) is not listed
                users[t].append(i.name)
    rows = ["| template | slots | factor: relation | tasks | used by |", "|---|---|---|---|---|"]
    for name, t in TEMPLATES.items():
        slots = ", ".join(f"`{s.name}`" + ("[]" if s.many else "") for s in t.slots)
        factors = "; ".join(f"`{f.name}`: {f.goal.type}" for f in t.factors)
        rows.append(f"| `{name}` | {slots} | {factors} | {len(users[name])} | "
                    f"{', '.join(users[name])} |")
    return "\n".join(rows)


def _replace(text: str, marker: str, body: str) -> str:
    begin, end = f"<!-- {marker}:begin -->", f"<!-- {marker}:end -->"
    head, rest = text.split(begin, 1)
    _, tail = rest.split(end, 1)
    return f"{head}{begin}\n{body}\n{end}{tail}"


def main() -> None:
    text = _replace(DOC.read_text(), "templates", template_table())
    DOC.write_text(_replace(text, "tasks", table()))
    print(f"wrote {DOC}")


if __name__ == "__main__":
    main()
