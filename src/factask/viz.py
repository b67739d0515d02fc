"""Pictures of task graphs: the bipartite variable/factor graph as a PNG.

Variables are circles in their palette colour (left column); factors are squares
(right column) in their execution order, numbered, with the order numbers of the
factors each one waits for; a milestone (counts once achieved) is a diamond, a
final factor (must hold at the end) a square. Edges: solid to the variables a factor moves, dashed
to its anchors, dotted to the rest of its scope.

Uses :class:`matplotlib.figure.Figure` directly (no pyplot), so it works
headless and never touches the global backend.
"""

from __future__ import annotations

from pathlib import Path

from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from factask.model import GraphValidationError, TaskGraph, rgba

_X_VAR = 0.0
_X_FAC = 1.0
_ROW = 0.6  # inches per node row
_FONT = 8


def _factor_rows(graph: TaskGraph) -> dict[str, int]:
    """Factor name -> row, in dependency order (declaration order if cyclic)."""
    try:
        order = graph.factor_order()
    except GraphValidationError:  # a cyclic graph is still drawn, as declared
        order = graph.factor_names()
    return {name: i for i, name in enumerate(order)}


def _variable_rows(graph: TaskGraph, frow: dict[str, int]) -> dict[str, int]:
    """Variable name -> row: sorted by the mean row of their factors, which keeps
    edges short and mostly uncrossed (declaration order breaks ties)."""
    touching: dict[str, list[int]] = {v: [] for v in graph.variable_names()}
    for f in graph.factors:
        for v in f.scope_names:
            if v in touching:
                touching[v].append(frow.get(f.name, 0))
    n = max(len(frow), 1)

    def key(item: tuple[int, str]) -> tuple[float, int]:
        i, v = item
        rows = touching[v]
        return (sum(rows) / len(rows) if rows else float(n), i)

    ordered = sorted(enumerate(graph.variable_names()), key=key)
    return {v: i for i, (_, v) in enumerate(ordered)}


def _ys(count: int, rows: int) -> list[float]:
    """Vertical positions of ``count`` nodes centred in a column of ``rows`` rows."""
    offset = (rows - count) / 2.0
    return [rows - 1 - (offset + i) for i in range(count)]


def graph_figure(graph: TaskGraph, title: str | None = None) -> Figure:
    """A matplotlib figure of ``graph``'s bipartite structure.

    Args:
        graph: The task graph (need not be valid; unknown scope names are skipped).
        title: Figure title; default the task name and description.
    """
    frow = _factor_rows(graph)
    vrow = _variable_rows(graph, frow)
    rows = max(len(frow), len(vrow), 1)
    fig = Figure(figsize=(11.0, max(3.0, _ROW * rows + 1.4)), dpi=100)
    ax = fig.add_axes((0.0, 0.0, 1.0, 0.88 if rows > 2 else 0.8))
    ax.set_axis_off()
    ax.set_xlim(-0.6, 3.0)
    ax.set_ylim(-0.8, rows - 0.2)

    vy = dict(zip(sorted(vrow, key=vrow.__getitem__), _ys(len(vrow), rows), strict=True))
    fy = dict(zip(sorted(frow, key=frow.__getitem__), _ys(len(frow), rows), strict=True))
    variables = {v.name: v for v in graph.variables}

    # Edges first, so nodes sit on top of them.
    for f in graph.factors:
        moved, anchors = set(f.moved()), set(f.anchors())
        for v in f.scope_names:
            if v not in vy or f.name not in fy:
                continue
            style = "-" if v in moved else "--" if v in anchors else ":"
            ax.plot([_X_VAR, _X_FAC], [vy[v], fy[f.name]], style, color="0.45", lw=1.1,
                    zorder=1)

    for name, y in vy.items():
        v = variables[name]
        ax.scatter([_X_VAR], [y], s=420, marker="o", color=[rgba(v.color)],
                   edgecolors="black", linewidths=1.6 if v.is_fixed else 0.8, zorder=3)
        count = f" x{v.count}" if v.count > 1 else ""
        fixed = ", fixed" if v.is_fixed else ""
        ax.text(_X_VAR - 0.09, y, f"{name}\n{v.kind}{count} ({v.color}{fixed})",
                ha="right", va="center", fontsize=_FONT, zorder=4)

    deps = _dependencies(graph)
    for f in graph.factors:
        if f.name not in fy:
            continue
        y = fy[f.name]
        ax.scatter([_X_FAC], [y], s=480 if f.milestone else 380,
                   marker="D" if f.milestone else "s", color="#f3efe0", edgecolors="black",
                   linewidths=0.8, zorder=3)
        ax.text(_X_FAC, y, str(frow[f.name] + 1), ha="center", va="center",
                fontsize=_FONT, weight="bold", zorder=4)
        waits = sorted(frow[d] + 1 for d in deps.get(f.name, ()) if d in frow)
        after = f"  after {', '.join(map(str, waits))}" if waits else ""
        desc = f.description if len(f.description) <= 84 else f.description[:81] + "..."
        kind = ", milestone" if f.milestone else ""
        ax.text(_X_FAC + 0.09, y,
                f"{f.name}  [{f.goal.type}{kind}, w={f.weight:.2f}]{after}\n{desc}",
                ha="left", va="center", fontsize=_FONT, zorder=4)

    head = title if title is not None else graph.name
    sub = "" if title is not None or not graph.description else graph.description
    if len(sub) > 150:
        sub = sub[:147] + "..."
    fig.suptitle(head, fontsize=11, weight="bold", y=0.985)
    if sub:
        fig.text(0.5, 0.985 - 0.35 / fig.get_figheight(), sub, ha="center", va="top",
                 fontsize=_FONT, wrap=True)
    ax.legend(
        handles=[Line2D([], [], ls="-", color="0.45", label="moves"),
                 Line2D([], [], ls="--", color="0.45", label="anchored to"),
                 Line2D([], [], ls=":", color="0.45", label="other scope"),
                 Line2D([], [], ls="", marker="s", color="black", mfc="#f3efe0",
                        label="final: holds at the end"),
                 Line2D([], [], ls="", marker="D", color="black", mfc="#f3efe0",
                        label="milestone: counts once reached")],
        loc="lower left", fontsize=_FONT - 1, frameon=False, ncol=5,
    )
    return fig


def _dependencies(graph: TaskGraph) -> dict[str, list[str]]:
    """Factor -> the factors that must come before it (explicit and anchored)."""
    d = graph.dependency_graph()
    return {n: sorted(d.predecessors(n)) for n in d.nodes}


def draw_graph(graph: TaskGraph, path: str | Path, title: str | None = None) -> Path:
    """Draw ``graph`` to a PNG file at ``path`` (parent folders are created).

    The file carries no timestamp or software version, so the same graph gives
    the same bytes with the same matplotlib.

    Returns:
        The path written.
    """
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig = graph_figure(graph, title=title)
    fig.savefig(out, format="png", metadata={"Software": None})
    return out
