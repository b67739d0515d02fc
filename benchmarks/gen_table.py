"""The generation table: three strategies, constrained and unconstrained, one model.

Runs ``factask benchmark`` twice on the fixed 55-task research sample
(``--sample research55``): once with structured output constrained by the
provider (``--response-format auto``: llama.cpp's grammar for the local model)
and once unconstrained (``--response-format prompt``: the schema in the prompt
only). Each run resumes where it stopped. The modes take turns, ``--chunk``
tasks at a time (each turn one ``factask benchmark`` process, one server), so
a run stopped early still has both modes on the same tasks. Then it writes,
into the run directory, ``table.md`` (syntax / runtime / completion, tokens and wall time
per strategy and mode, with the research's GPT-4 numbers) and ``table.png``.

Usage::

    python benchmarks/gen_table.py --out runs/gen-smollm2            # all 55 tasks
    python benchmarks/gen_table.py --out runs/gen-smollm2 --limit 6  # what fits
    python benchmarks/gen_table.py --out runs/x --model local/gemma3-270m

Extra arguments after ``--`` go to ``factask benchmark`` unchanged.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

MODES = {"constrained": "auto", "unconstrained": "prompt"}
#: Tasks in the research sample (``factask.evaluation.benchmark.RESEARCH_SAMPLE_SIZE``).
SAMPLE_SIZE = 55
RESEARCH = {"one-shot": (95.0, 53.3, 16.7), "variables-first": (96.4, 78.2, 29.1),
            "subtasks-first": (98.3, 90.2, 16.7)}


def run_mode(out: Path, mode: str, args: argparse.Namespace, extra: list[str],
             limit: int | None = None) -> int:
    """Run (or resume) one mode's benchmark on the first ``limit`` tasks (None: all);
    returns its exit status."""
    cmd = [sys.executable, "-m", "factask", "benchmark", "--approach", "all",
           "--sample", "research55", "--out", str(out / mode),
           "--response-format", MODES[mode], "--max-repairs", str(args.max_repairs),
           "--episodes", str(args.episodes), "--temperature", "0", "--seed", "0"]
    if args.model:
        cmd += ["--model", args.model]
    if limit:
        cmd += ["--limit", str(limit)]
    return subprocess.call(cmd + extra)


def turns(total: int, chunk: int) -> list[int]:
    """The task counts the modes run up to, turn by turn: chunk, 2 chunk, ..., total."""
    step = max(1, chunk)
    return [*range(step, total, step), total]


def first_step_rates(run: Path, tasks: set[str] | None = None) -> dict[str, float]:
    """Per strategy: the fraction of generations whose first step (``one_shot``,
    ``variables``, ``subtask_outline``) passed at once -- the step a schema
    constraint helps most, before any later step can fail. Only ``tasks`` count
    (None: every task in the file), as in the summary's rates."""
    seen: dict[str, list[bool]] = {}
    latest: dict[tuple[str, str], dict[str, Any]] = {}
    path = run / "results.jsonl"
    for line in path.read_text().splitlines() if path.exists() else []:
        try:
            record = json.loads(line)
        except ValueError:
            continue
        if tasks is None or record.get("task") in tasks:
            latest[(record.get("approach", ""), record.get("task", ""))] = record
    for (approach, _), record in latest.items():
        steps = record.get("steps") or []
        if record.get("status") != "done" or not steps:
            continue
        seen.setdefault(approach, []).append(bool(steps[0].get("ok")))
    return {a: sum(v) / len(v) for a, v in seen.items() if v}


def table(summaries: dict[str, dict[str, Any]], firsts: dict[str, dict[str, float]]) -> str:
    """Markdown: one row per (strategy, mode)."""
    lines = ["| strategy | structured output | tasks | first step valid % | syntax % | "
             "runtime % | completion % | repairs | tokens | tokens / task | wall s / task | "
             "GPT-4 (research) % |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for approach, ref in RESEARCH.items():
        for mode, summary in summaries.items():
            row = summary["approaches"].get(approach)
            if not row or not row["tasks"]:
                continue
            n = row["tasks"]
            first = firsts.get(mode, {}).get(approach, 0.0)
            lines.append(
                f"| {approach} | {mode} | {n} | {100 * first:.1f} | {100 * row['syntax']:.1f} | "
                f"{100 * row['runtime']:.1f} | {100 * row['completion']:.1f} | "
                f"{row['repairs']} | {row['tokens']} | {row['tokens'] / n:.0f} | "
                f"{row.get('wall_s', 0.0) / n:.0f} | {' / '.join(f'{x:.1f}' for x in ref)} |")
    return "\n".join(lines)


def chart(summaries: dict[str, dict[str, Any]], firsts: dict[str, dict[str, float]],
          path: Path, title: str) -> None:
    """Grouped bars: per strategy, first step / syntax / runtime / completion per mode."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    levels = ("first step", "syntax", "runtime", "completion")
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.6), sharey=True)
    for ax, approach in zip(axes, RESEARCH, strict=True):
        width = 0.8 / (len(summaries) + 1)
        for i, (mode, summary) in enumerate(summaries.items()):
            row = summary["approaches"].get(approach, {})
            values = [100 * firsts.get(mode, {}).get(approach, 0.0)]
            values += [100 * row.get(lv, 0.0) for lv in levels[1:]]
            ax.bar([j + i * width for j in range(4)], values, width, label=mode)
        ax.bar([j + len(summaries) * width for j in range(1, 4)], RESEARCH[approach], width,
               label="GPT-4 (research)", color="lightgray")
        ax.set_xticks([j + width for j in range(4)], levels, fontsize=8)
        ax.set_title(approach)
        ax.set_ylim(0, 100)
    axes[0].set_ylabel("% of tasks")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", ncol=3, fontsize=8, frameon=False)
    fig.suptitle(title, y=0.02, fontsize=8)
    fig.tight_layout(rect=(0, 0.04, 1, 0.9))
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    """Run both modes, then write table.md and table.png; returns the exit status."""
    argv = list(sys.argv[1:] if argv is None else argv)
    extra = argv[argv.index("--") + 1:] if "--" in argv else []
    argv = argv[:argv.index("--")] if "--" in argv else argv
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("--model", default=None, help="default: the packaged local model")
    parser.add_argument("--limit", type=int, default=None, help="first N of the 55 tasks")
    parser.add_argument("--max-repairs", type=int, default=1)
    parser.add_argument("--episodes", type=int, default=1)
    parser.add_argument("--modes", default="constrained,unconstrained")
    parser.add_argument("--chunk", type=int, default=5,
                        help="tasks per turn of each mode (the modes alternate)")
    args = parser.parse_args(argv)
    summaries: dict[str, dict[str, Any]] = {}
    status = 0
    modes = args.modes.split(",")
    for limit in turns(args.limit or SAMPLE_SIZE, args.chunk):
        for mode in modes:
            code = run_mode(args.out, mode, args, extra, limit)
            status = status or code
            if code in (2, 3):  # the configuration cannot work: no point going on
                break
        if status in (2, 3):
            break
    for mode in modes:
        path = args.out / mode / "summary.json"
        if path.exists():
            summaries[mode] = json.loads(path.read_text())
    if not summaries:
        return status or 1
    from factask.evaluation.benchmark import default_tasks_path, load_tasks, research_sample

    names = {t.name for t in research_sample(load_tasks(default_tasks_path()))[:args.limit]}
    firsts = {mode: first_step_rates(args.out / mode, names) for mode in summaries}
    text = table(summaries, firsts)
    (args.out / "table.md").write_text(text + "\n")
    model = next(iter(summaries.values())).get("model", "?")
    chart(summaries, firsts, args.out / "table.png",
          f"{model}; research55 sample{f' (first {args.limit})' if args.limit else ''}; "
          f"max_repairs {args.max_repairs}; episodes {args.episodes}")
    print(text)
    return status


if __name__ == "__main__":
    raise SystemExit(main())
