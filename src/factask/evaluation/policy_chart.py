"""The bar chart of a policy evaluation: success at the end per task, 95 % intervals."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from factask.evaluation.policy import TaskScore


def plot_scores(scores: Sequence[TaskScore], path: str | Path, title: str = "") -> Path:
    """Write a PNG bar chart of success at the end per task, with its Wilson interval.

    Args:
        scores: One score per task (:func:`~factask.evaluation.policy.evaluate_policy`).
        path: The PNG file.
        title: The chart's title.

    Returns:
        The path written.
    """
    import matplotlib

    matplotlib.use("Agg")  # files only: no display needed
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(max(4.0, 0.6 * len(scores) + 2), 3.5))
    x = np.arange(len(scores))
    rates = np.array([s.success_at_end for s in scores])
    below = rates - np.array([s.success_at_end_ci[0] for s in scores])
    above = np.array([s.success_at_end_ci[1] for s in scores]) - rates
    ax.bar(x, rates, yerr=[below, above], capsize=3, color="#4c78a8")
    ax.set_xticks(x, [s.task for s in scores], rotation=45, ha="right", fontsize=8)
    ax.set_ylim(0, 1.05)
    ax.set_ylabel("success at end (95 % CI)")
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
