"""Minimum-cost assignment in every world at once: the batched twin of SciPy's
``linear_sum_assignment``, for the oracle's "which free slot does each object take".

The scalar status (:func:`factask.relations.status.factor_status`) gives every
object still to place a free slot by one optimal assignment (SciPy's shortest
augmenting path, Crouse 2016). Calling SciPy once per world is a Python loop over
worlds; here the same algorithm runs over the world axis: each row (object) is
added in turn, and the Dijkstra search for its augmenting path advances one column
in every world per NumPy step, worlds that found their path standing still. Rows and
columns outside a world's masks take no part, so one call serves worlds with
different objects to place and different free slots.

For a cost matrix whose optimal assignment is unique (any matrix of distances
between real poses, save a measure-zero set of ties), the result is SciPy's. Ties
are broken by the lowest column index (SciPy walks its own column order), so on a
tied matrix the two may pick different, equally cheap, assignments.
"""

from __future__ import annotations

import numpy as np

from factask.vocabulary.errors import InvalidValueError


def assign_min_cost(cost: np.ndarray, rows: np.ndarray | None = None,
                    cols: np.ndarray | None = None) -> np.ndarray:
    """The column each row takes in every world, by one minimum-cost assignment.

    Args:
        cost: Finite costs (W, n, m).
        rows: Rows that take part (W, n) (default all).
        cols: Columns that may be taken (W, m) (default all). Each world needs at
            least as many columns as rows.

    Returns:
        Column of each row (W, n), -1 for rows that do not take part.

    Raises:
        InvalidValueError: shapes disagree, a cost is not finite, or a world has
            more rows than columns.
    """
    cost = np.asarray(cost, dtype=float)
    if cost.ndim != 3:
        raise InvalidValueError(f"cost must be (worlds, rows, columns), got {cost.shape}")
    w, n, m = cost.shape
    rows = np.ones((w, n), dtype=bool) if rows is None else np.asarray(rows, dtype=bool)
    cols = np.ones((w, m), dtype=bool) if cols is None else np.asarray(cols, dtype=bool)
    if rows.shape != (w, n) or cols.shape != (w, m):
        raise InvalidValueError(f"rows {rows.shape} and cols {cols.shape} must be ({w}, {n}) "
                                f"and ({w}, {m})")
    if not np.isfinite(cost[rows[:, :, None] & cols[:, None, :]]).all():
        raise InvalidValueError("assignment costs must be finite (give forbidden pairs a "
                                "large finite cost)")
    if (rows.sum(axis=1) > cols.sum(axis=1)).any():
        raise InvalidValueError("a world has more rows to assign than columns to take")
    world = np.arange(w)
    u = np.zeros((w, n))
    v = np.zeros((w, m))
    row_of_col = np.full((w, m), -1)
    col_of_row = np.full((w, n), -1)
    for cur in range(n):
        searching = rows[:, cur].copy()
        if not searching.any():
            continue
        path = np.full((w, m), -1)
        spc = np.full((w, m), np.inf)  # shortest path cost to each column
        seen_rows = np.zeros((w, n), dtype=bool)
        seen_cols = np.zeros((w, m), dtype=bool)
        remaining = cols & searching[:, None]
        row = np.full(w, cur)
        min_val = np.zeros(w)
        sink = np.full(w, -1)
        while searching.any():
            s = np.flatnonzero(searching)
            r_s = row[s]
            seen_rows[s, r_s] = True
            reduced = (min_val[s, None] + cost[s, r_s] - u[s, r_s][:, None] - v[s])
            better = remaining[s] & (reduced < spc[s])
            spc_s = np.where(better, reduced, spc[s])
            spc[s] = spc_s
            path[s] = np.where(better, r_s[:, None], path[s])
            # The closest remaining column; on a tie an unassigned one (it ends the
            # search), then the lowest index.
            masked = np.where(remaining[s], spc_s, np.inf)
            lowest = masked.min(axis=1)
            tied = masked == lowest[:, None]
            free_tied = tied & (row_of_col[s] < 0)
            j = np.where(free_tied.any(axis=1), free_tied.argmax(axis=1), tied.argmax(axis=1))
            min_val[s] = lowest
            seen_cols[s, j] = True
            remaining[s, j] = False
            owner = row_of_col[s, j]
            found = owner < 0
            sink[s[found]] = j[found]
            row[s[~found]] = owner[~found]
            searching[s[found]] = False
        act = rows[:, cur]
        # Dual update (SciPy's rule), then the augmentation along the path.
        u[act, cur] += min_val[act]
        back = np.where(col_of_row >= 0, spc[world[:, None], np.maximum(col_of_row, 0)], 0.0)
        others = seen_rows & act[:, None]
        others[:, cur] = False
        u += np.where(others, min_val[:, None] - back, 0.0)
        v -= np.where(seen_cols & act[:, None], min_val[:, None] - spc, 0.0)
        j = np.where(act, sink, -1)
        going = act.copy()
        while going.any():
            g = np.flatnonzero(going)
            jg = j[g]
            ig = path[g, jg]
            row_of_col[g, jg] = ig
            previous = col_of_row[g, ig]
            col_of_row[g, ig] = jg
            j[g] = previous
            going[g[ig == cur]] = False
    return np.where(rows, col_of_row, -1)


__all__ = ["assign_min_cost"]
