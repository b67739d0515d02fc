"""The generation benchmark: a task list through generation and verification.

One JSON line per finished (approach, task) pair is appended to
``RUN_DIR/results.jsonl`` as soon as it finishes (flushed and fsynced), so an
interrupted run loses nothing and a rerun resumes where it stopped without
repeating a finished pair. At the end the three rates of the research — the
fraction of tasks whose final graph reaches *syntax*, *runtime* and
*completion* — are written per approach as ``summary.json``, ``summary.md``
and a bar chart ``rates.png`` next to the research's numbers, with a fourth:
*faithful*, the fraction of tasks with a reference graph whose final graph means
the task (:func:`factask.gen.compare.compare`; every line says whether its graph is
faithful and what differs). A task's reference is its own entry's ``reference``
(a graph, or a library task's name), else the library's graph of the same name
(188 of the 192 list).

Tasks that need deformables a rigid suction world cannot express (ropes, cloth,
bags, particle piles, spatula sweeping) are not sent to the model; they get a
``not_expressible`` line and their own column in the table.
"""

from __future__ import annotations

import json
import os
import random
import re
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from factask.gen.compare import compare
from factask.gen.llm import LLMFatalError
from factask.gen.memory import SubtaskMemory
from factask.gen.results import APPROACHES
from factask.gen.strategies import Generator
from factask.gen.verify import LEVELS, at_least
from factask.graph.taskgraph import TaskGraph, parse_graph
from factask.vocabulary.errors import FactaskError, GraphValidationError

#: The research's rates in percent (syntax, runtime, completion), GPT-4, 55 tasks.
RESEARCH_RATES: dict[str, tuple[float, float, float]] = {
    "one-shot": (95.0, 53.3, 16.7),
    "variables-first": (96.4, 78.2, 29.1),
    "subtasks-first": (98.3, 90.2, 16.7),
}
#: The rates' levels, in table order.
RATE_LEVELS = ("syntax", "runtime", "completion")

RESULTS_FILE = "results.jsonl"

#: What no factask world can hold: cloth and bags (ropes and piles of small blocks
#: are relations with their own oracles: ``rope_along``, ``pile_in_zone``).
_CLOTH_WORDS = re.compile(r"\b(cloths?|fabrics?|towels?|bags?|sacks?)\b")
_CLOTH_ASSETS = ("cloth", "bag")
#: The research sample's pool is the rigid tasks (as the research's table was):
#: these words and assets keep a task out of it, ropes and piles included.
_NON_RIGID_WORDS = re.compile(
    r"\b(ropes?|cables?|cloths?|fabrics?|bags?|sacks?|piles?|particles?|sweep(?:ing|s)?|"
    r"swept|spatula)\b")
_NON_RIGID_ASSETS = ("rope", "cloth", "bag", "cable")
_PUSH_WORDS = re.compile(r"\b(push(?:ing|es)?|sweep(?:ing|s)?)\b")


class BenchmarkError(FactaskError):
    """The task list cannot be read, or the run directory is not usable."""


@dataclass
class BenchTask:
    """One task proposal of the list.

    Attributes:
        name: Task name (kebab-case).
        description: What the task is.
        assets: GenSim/Ravens URDF names the original used.
        origin: Where it comes from (``ravens_cliport_original``, ``gensim_generated``).
        reference: The graph the task means (a graph dict, or a library task's name);
            None: the library's graph of the same name, if there is one.
    """

    name: str
    description: str
    assets: list[str] = field(default_factory=list)
    origin: str = ""
    reference: dict[str, Any] | str | None = None

    @property
    def proposal(self) -> str:
        return f"{self.name}: {self.description}"


def default_tasks_path() -> Path:
    """The 192-task list shipped with factask (``factask/data/gensim_tasks.json``)."""
    return Path(str(resources.files("factask") / "data" / "gensim_tasks.json"))


def load_tasks(path: str | os.PathLike[str]) -> list[BenchTask]:
    """Read a task list (a JSON list of ``{name, description, assets, origin}``).

    Raises:
        BenchmarkError: the file is missing or not such a list.
    """
    try:
        data = json.loads(Path(path).read_text())
    except (OSError, json.JSONDecodeError) as exc:
        raise BenchmarkError(f"cannot read task list {path}: {exc}") from None
    if isinstance(data, Mapping):
        data = data.get("tasks", [])
    if not isinstance(data, list):
        raise BenchmarkError(f"{path}: expected a JSON list of tasks")
    tasks = []
    for i, item in enumerate(data):
        if not isinstance(item, Mapping) or not item.get("name"):
            raise BenchmarkError(f"{path}: entry {i} has no name")
        tasks.append(BenchTask(name=str(item["name"]), description=str(item.get("description",
                                                                                 "")),
                               assets=[str(a) for a in item.get("assets", [])],
                               origin=str(item.get("origin", "")),
                               reference=item.get("reference")))
    return tasks


#: Size and seed of the fixed research sample (the research used 55 tasks).
RESEARCH_SAMPLE_SIZE = 55
RESEARCH_SAMPLE_SEED = 224


def research_sample(tasks: Sequence[BenchTask], n: int = RESEARCH_SAMPLE_SIZE,
                    seed: int = RESEARCH_SAMPLE_SEED) -> list[BenchTask]:
    """The fixed task sample of the generation table.

    The rule: of the rigid tasks (:func:`non_rigid_reason` is None: no rope,
    cloth, bag, pile or sweeping -- the research's table covered rigid tasks),
    sorted by name, ``n`` drawn by ``random.Random(seed).sample``; returned in
    the list's own order. With the packaged list this is always the same 55
    tasks (docs/generation.md lists them).

    Args:
        tasks: The task list.
        n: Sample size (all rigid tasks if fewer).
        seed: Seed of the draw.

    Returns:
        The sample.
    """
    pool = sorted((t for t in tasks if non_rigid_reason(t) is None), key=lambda t: t.name)
    chosen = {t.name for t in random.Random(seed).sample(pool, min(n, len(pool)))}
    return [t for t in tasks if t.name in chosen]


def _found(task: BenchTask, words: re.Pattern[str], assets: Sequence[str],
           pushed_small_blocks: bool) -> str | None:
    """What of ``words`` and ``assets`` the task mentions, or None."""
    text = f"{task.name.replace('-', ' ')} {task.description}".lower()
    found = sorted(set(words.findall(text)))
    used = " ".join(task.assets).lower()
    bad_assets = [a for a in assets if a in used]
    if pushed_small_blocks and "block/small.urdf" in used and _PUSH_WORDS.search(text):
        bad_assets.append("small blocks pushed as a pile")
    parts = []
    if found:
        parts.append("mentions " + ", ".join(found))
    if bad_assets:
        parts.append("assets: " + ", ".join(bad_assets))
    return "; ".join(parts) or None


def not_expressible_reason(task: BenchTask) -> str | None:
    """Why factask cannot express ``task``, or None if it can.

    Cloth and bags (from the task's words and assets) have no factask kind;
    ropes and piles of small blocks do (``rope_along``, ``pile_in_zone``), so
    such tasks are sent to the model like any other.
    """
    found = _found(task, _CLOTH_WORDS, _CLOTH_ASSETS, pushed_small_blocks=False)
    if found is None:
        return None
    return "needs cloth or bags, which factask has no kind for: " + found


def non_rigid_reason(task: BenchTask) -> str | None:
    """Why ``task`` is not a rigid pick-and-place task (ropes, cloth, bags, piles,
    sweeping), or None: the research sample's pool (:func:`research_sample`)."""
    found = _found(task, _NON_RIGID_WORDS, _NON_RIGID_ASSETS, pushed_small_blocks=True)
    return None if found is None else "needs deformables or particles: " + found


# ------------------------------------------------------------------ results file
def read_results(path: str | os.PathLike[str]) -> list[dict[str, Any]]:
    """Every complete line of a results file (a torn last line is ignored)."""
    p = Path(path)
    if not p.exists():
        return []
    out = []
    for line in p.read_text().splitlines():
        line = line.strip()
        if not line:
            continue
        try:
            out.append(json.loads(line))
        except json.JSONDecodeError:
            continue
    return out


def is_finished(record: Mapping[str, Any]) -> bool:
    """A line whose pair need not run again (an LLM outage is retried; an
    unexpected ``error`` is a recorded failure, not retried)."""
    return record.get("status") in ("done", "not_expressible", "error")


def finished_pairs(records: Iterable[Mapping[str, Any]]) -> set[tuple[str, str]]:
    """(approach, task) pairs already finished."""
    return {(r["approach"], r["task"]) for r in records if is_finished(r)}


def _repair_tail(path: Path) -> None:
    """Cut a torn last line (a run killed mid-write) so appends stay line-aligned."""
    if not path.exists() or path.stat().st_size == 0:
        return
    data = path.read_bytes()
    if data.endswith(b"\n"):
        return
    cut = data.rfind(b"\n") + 1
    with open(path, "r+b") as fh:
        fh.truncate(cut)


def _append(fh: Any, record: Mapping[str, Any]) -> None:
    fh.write(json.dumps(record) + "\n")
    fh.flush()
    os.fsync(fh.fileno())


# ------------------------------------------------------------------------ runner
OnStart = Callable[[str, BenchTask], None]
OnResult = Callable[[dict[str, Any]], None]


def run_benchmark(
    tasks: Sequence[BenchTask],
    approaches: Sequence[str],
    generator: Generator,
    out_dir: str | os.PathLike[str],
    on_start: OnStart | None = None,
    on_result: OnResult | None = None,
    meta: Mapping[str, Any] | None = None,
) -> dict[str, Any]:
    """Run every (task, approach) pair not finished yet; write results and summary.

    Args:
        tasks: The task proposals.
        approaches: Approaches to run (each of :data:`APPROACHES`).
        generator: Generation + verification (its client, verifier and memory).
        out_dir: The run directory.
        on_start: Called before a pair runs.
        on_result: Called with each new line as it is written.
        meta: Extra fields for ``summary.json`` (model, task file, ...).

    Returns:
        The summary (as written to ``summary.json``).

    Raises:
        BenchmarkError: an unknown approach, or an unusable run directory.
        LLMFatalError: key, model, quota or context error (the run stops; finished
            pairs are kept).

    Any other error of one pair becomes a line with ``status: "error"`` and the
    exception text (a failure at level none); the run goes on. In-context
    examples never include the task itself (library tasks and remembered
    subtasks of the same or a near-duplicate name are left out), and with a
    subtask memory each approach reads and writes its own subdirectory
    (``MEMORY/<approach>``), so approaches do not leak into each other and a
    resumed run sees what an uninterrupted one would.
    """
    for a in approaches:
        if a not in APPROACHES:
            raise BenchmarkError(f"unknown approach {a!r}; use {', '.join(APPROACHES)} or all")
    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise BenchmarkError(f"cannot create run directory {out}: {exc}") from None
    path = out / RESULTS_FILE
    _repair_tail(path)
    done = finished_pairs(read_results(path))
    base_memory = generator.memory
    try:
        with open(path, "a", encoding="utf-8") as fh:
            for task in tasks:
                reason = not_expressible_reason(task)
                for approach in approaches:
                    if (approach, task.name) in done:
                        continue
                    if on_start is not None:
                        on_start(approach, task)
                    if base_memory is not None:  # one memory per approach
                        generator.memory = SubtaskMemory(base_memory.directory / approach)
                    record = _run_guarded(generator, task, approach, reason)
                    _append(fh, record)
                    if is_finished(record):
                        done.add((approach, task.name))
                    if on_result is not None:
                        on_result(record)
    finally:
        generator.memory = base_memory
    summary = summarize(read_results(path), approaches, [t.name for t in tasks])
    summary["examples"] = {"exclude_task_itself": True,
                           "rule": "library tasks and memory entries whose task name equals "
                                   "the task's (normalised) or shares >= 80% of its name "
                                   "words are never shown",
                           "memory": "per approach" if base_memory is not None else "none"}
    summary.update(dict(meta or {}))
    write_summary(out, summary)
    return summary


def _run_guarded(generator: Generator, task: BenchTask, approach: str,
                 reason: str | None) -> dict[str, Any]:
    """:func:`_run_one`, with an unexpected error recorded as a failed line."""
    start = time.perf_counter()
    try:
        return _run_one(generator, task, approach, reason)
    except (LLMFatalError, KeyboardInterrupt):
        raise
    except Exception as exc:
        return {"approach": approach, "task": task.name, "origin": task.origin,
                "status": "error", "level_reached": "none", "llm_error": False,
                "failure": f"unexpected {type(exc).__name__}: {exc}",
                "error": f"{type(exc).__name__}: {exc}", "repairs": 0,
                "wall_s": round(time.perf_counter() - start, 3)}


def _run_one(generator: Generator, task: BenchTask, approach: str,
             reason: str | None) -> dict[str, Any]:
    base = {"approach": approach, "task": task.name, "origin": task.origin}
    if reason is not None:
        return {**base, "status": "not_expressible", "reason": reason, "level_reached": "none"}
    start = time.perf_counter()
    result = generator.generate(task.proposal, approach, name=task.name,
                                description=task.description)
    record = {**base, **result.to_dict(), "task": task.name,
              "status": "llm_error" if result.llm_error else "done",
              "repairs": result.repairs,
              "wall_s": round(time.perf_counter() - start, 3)}
    record.update(meaning_of(result.graph, task))
    return record


def reference_graph(task: BenchTask) -> TaskGraph | None:
    """The graph ``task`` means: its own ``reference``, else the library's graph of the
    same name, else None.

    Raises:
        BenchmarkError: the entry's reference is not a valid graph or library name.
    """
    from factask.library.tasks import UnknownTaskError, get_task

    ref = task.reference
    try:
        if isinstance(ref, str):
            return get_task(ref)
        if ref is not None:
            return parse_graph(ref)
    except (UnknownTaskError, GraphValidationError) as exc:
        raise BenchmarkError(f"task {task.name!r}: its reference is not usable: {exc}") from None
    try:
        return get_task(task.name)
    except UnknownTaskError:
        return None


def meaning_of(graph: TaskGraph | None, task: BenchTask) -> dict[str, Any]:
    """A result line's meaning fields: ``faithful`` (True / False; None without a
    reference) and ``meaning`` (the comparison, or why there is none)."""
    reference = reference_graph(task)
    if reference is None:
        return {"faithful": None, "meaning": {"reference": None}}
    if graph is None:
        return {"faithful": False, "meaning": {"reference": reference.name,
                                               "differences": ["no graph"]}}
    result = compare(graph, reference, task.description)  # colours the words leave open
    return {"faithful": result.equivalent,
            "meaning": {"reference": reference.name, **result.to_dict()}}


# ----------------------------------------------------------------------- summary
def summarize(records: Iterable[Mapping[str, Any]], approaches: Sequence[str],
              task_names: Sequence[str] | None = None) -> dict[str, Any]:
    """The rates per approach from result lines (the last line of a pair wins).

    Args:
        records: Lines of ``results.jsonl``.
        approaches: Approaches to report, in order.
        task_names: Restrict to these tasks (None: every task in the file).

    Returns:
        ``{"approaches": {approach: {tasks, syntax, runtime, completion (rates in
        [0, 1]), counts, not_expressible, llm_errors, errors, tokens, cost_usd}},
        "research": RESEARCH_RATES}``.
    """
    wanted = set(task_names) if task_names is not None else None
    latest: dict[tuple[str, str], Mapping[str, Any]] = {}
    for r in records:
        if wanted is not None and r.get("task") not in wanted:
            continue
        latest[(r["approach"], r["task"])] = r
    table: dict[str, Any] = {}
    for a in approaches:
        rows = [r for (ap, _), r in latest.items() if ap == a]
        # An unexpected error is a failure at level none, counted in the rates.
        done = [r for r in rows if r.get("status") in ("done", "error")]
        counts = {lvl: sum(1 for r in done if at_least(r.get("level_reached", "none"), lvl))
                  for lvl in RATE_LEVELS}
        n = len(done)
        tokens = sum(int(r.get("usage", {}).get("total_tokens", 0)) for r in done)
        cost = sum(float(r.get("usage", {}).get("cost_usd", 0.0)) for r in done)
        wall = sum(float(r.get("wall_s", 0.0)) for r in done)
        judged = [r for r in done if r.get("faithful") is not None]
        faithful = sum(1 for r in judged if r.get("faithful"))
        table[a] = {
            "tasks": n,
            **{lvl: (counts[lvl] / n if n else 0.0) for lvl in RATE_LEVELS},
            "faithful": faithful / len(judged) if judged else None,
            "counts": {**counts, "faithful": faithful, "with_reference": len(judged)},
            "not_expressible": sum(1 for r in rows if r.get("status") == "not_expressible"),
            "llm_errors": sum(1 for r in rows if r.get("status") == "llm_error"),
            "errors": sum(1 for r in rows if r.get("status") == "error"),
            "repairs": sum(int(r.get("repairs", 0)) for r in done),
            "tokens": tokens,
            "cost_usd": round(cost, 6),
            "wall_s": round(wall, 1),
        }
    return {"approaches": table, "levels": list(RATE_LEVELS),
            "research": {k: list(v) for k, v in RESEARCH_RATES.items()}}


def summary_table(summary: Mapping[str, Any]) -> str:
    """The summary as a Markdown table (ours next to the research's numbers)."""
    head = ("| approach | tasks | syntax % | runtime % | completion % | faithful % | "
            "not expressible | LLM errors | repairs | tokens | wall s | cost $ | research "
            "syntax / runtime / completion % |")
    lines = [head, "|" + "---|" * 13]
    for a, row in summary["approaches"].items():
        ref = RESEARCH_RATES.get(a)
        ref_text = " / ".join(f"{x:.1f}" for x in ref) if ref else "-"
        rate = row.get("faithful")
        with_ref = row.get("counts", {}).get("with_reference", 0)
        faithful = "-" if rate is None else f"{100 * rate:.1f} (of {with_ref})"
        lines.append(
            f"| {a} | {row['tasks']} | {100 * row['syntax']:.1f} | {100 * row['runtime']:.1f} | "
            f"{100 * row['completion']:.1f} | {faithful} | {row['not_expressible']} | "
            f"{row['llm_errors']} | "
            f"{row['repairs']} | {row['tokens']} | {row.get('wall_s', 0.0):.0f} | "
            f"{row['cost_usd']:.4f} | {ref_text} |")
    return "\n".join(lines)


def write_summary(out_dir: str | os.PathLike[str], summary: Mapping[str, Any]) -> None:
    """Write ``summary.json``, ``summary.md`` and ``rates.png`` into ``out_dir``."""
    out = Path(out_dir)
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    md = ["# Generation benchmark", "",
          "Rates: fraction of tasks whose final graph reaches each level "
          "(syntax: valid graph; runtime: compiles, resets and steps; completion: the "
          "oracle succeeds in at least half of the episodes); faithful: of the tasks with a "
          "reference graph, the fraction whose final graph is the same task "
          "(`factask compare`).", "", summary_table(summary), ""]
    (out / "summary.md").write_text("\n".join(md))
    plot_rates(summary, out / "rates.png")


def plot_rates(summary: Mapping[str, Any], path: str | os.PathLike[str]) -> None:
    """Grouped bar chart: per approach and level, this run's rate and the research's, and
    the faithful rate (the research had none)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    approaches = list(summary["approaches"])
    panels = [*RATE_LEVELS, "faithful"]
    fig, axes = plt.subplots(1, len(panels), figsize=(4.2 * len(panels), 4.0), sharey=True)
    width = 0.38
    for ax, lvl in zip(axes, panels, strict=True):
        xs = range(len(approaches))
        ours = [100 * (summary["approaches"][a].get(lvl) or 0.0) for a in approaches]
        ax.bar([x - width / 2 for x in xs], ours, width, label="this run", color="#4e79a7")
        if lvl in RATE_LEVELS:  # the research reported no meaning rate
            i = RATE_LEVELS.index(lvl)
            ref = [RESEARCH_RATES.get(a, (0.0, 0.0, 0.0))[i] for a in approaches]
            ax.bar([x + width / 2 for x in xs], ref, width, label="research (GPT-4)",
                   color="#bab0ac")
        for x, v in zip(xs, ours, strict=True):
            ax.text(x - width / 2, v + 1, f"{v:.0f}", ha="center", fontsize=8)
        ax.set_xticks(list(xs))
        ax.set_xticklabels(approaches, rotation=15, fontsize=8)
        ax.set_title(f"{lvl} rate" if lvl == "faithful" else f"{lvl} pass rate")
        ax.set_ylim(0, 110)
    axes[0].set_ylabel("% of tasks")
    handles, labels = axes[0].get_legend_handles_labels()
    # One legend above the panels: inside a panel it would hide the bars.
    fig.legend(handles, labels, loc="upper center", ncol=2, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    fig.savefig(path, dpi=100)
    plt.close(fig)


__all__ = [
    "LEVELS",
    "RATE_LEVELS",
    "RESEARCH_RATES",
    "BenchTask",
    "BenchmarkError",
    "default_tasks_path",
    "finished_pairs",
    "load_tasks",
    "meaning_of",
    "non_rigid_reason",
    "not_expressible_reason",
    "plot_rates",
    "read_results",
    "reference_graph",
    "research_sample",
    "run_benchmark",
    "summarize",
    "summary_table",
    "write_summary",
]
