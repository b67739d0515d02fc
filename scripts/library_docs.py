"""Regenerate the task table of docs/library.md from the registry.

The table sits between ``<!-- tasks:begin -->`` and ``<!-- tasks:end -->``; one
row per task with its family, sizes, templates and description, read from the
graphs so the page cannot drift from the code. Run:
``.venv/bin/python scripts/library_docs.py``.
"""

from __future__ import annotations

from pathlib import Path

from factask.library import list_tasks
from factask.library.builders import FAMILIES

DOC = Path(__file__).resolve().parents[1] / "docs" / "library.md"
BEGIN, END = "<!-- tasks:begin -->", "<!-- tasks:end -->"


def table() -> str:
    """The markdown table of every library task."""
    rows = ["| task | family | variables | factors | movable | templates | description |",
            "|---|---|---|---|---|---|---|"]
    for i in list_tasks():
        desc = i.description.replace("|", "/")
        rows.append(f"| `{i.name}` | {FAMILIES.get(i.name, '')} | {i.n_variables} | "
                    f"{i.n_factors} | {i.n_movable} | {', '.join(i.templates)} | {desc} |")
    return "\n".join(rows)


def main() -> None:
    text = DOC.read_text()
    head, rest = text.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    DOC.write_text(f"{head}{BEGIN}\n{table()}\n{END}{tail}")
    print(f"wrote {DOC}")


if __name__ == "__main__":
    main()
