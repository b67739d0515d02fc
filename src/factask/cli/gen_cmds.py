"""Commands of LLM generation: ``generate``, ``benchmark`` and ``compare`` (the meaning metric).

litellm and MuJoCo are imported only when a command runs.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

import typer
from rich.console import Console

from factask.cli.app import JSON_HELP, ROBOT_HELP, app, check_robot, fail, make_console

if TYPE_CHECKING:
    from factask.gen.strategies import Generator

console = make_console(highlight=False)
err_console = make_console(stderr=True, highlight=False)

_APPROACH_HELP = "one-shot (baseline), variables-first (approach 1) or subtasks-first (approach 2)"
# The default is factask.gen.results.DEFAULT_APPROACH, resolved when the command runs (the
# generation modules are not imported for --help); test_gen_cli checks this text names it.
_DEFAULT_APPROACH_HELP = "default one-shot: the best faithful rate measured (docs/generation.md)"


#: Exit status of a run that cannot work as configured (key, model, quota, context).
EXIT_CONFIG = 2
#: Exit status of a run in which no LLM call succeeded.
EXIT_NO_CALL = 3

_MODEL_HELP = ("litellm model, e.g. openai/gpt-4o ($FACTASK_MODEL); default: the packaged "
               "local model local/smollm2-135m (a small floor, not a recommendation)")
_FORMAT_HELP = ("structured output: auto (per provider), json_schema, llama_cpp, json_object "
                "or prompt (unconstrained) ($FACTASK_RESPONSE_FORMAT)")


def _fail(message: str, code: int = EXIT_CONFIG) -> NoReturn:
    # Plain text: a provider's message may hold square brackets.
    raise fail(f"error: {message}", code)


def _approaches(given: list[str], allow_all: bool) -> list[str]:
    """``-a`` values, each a name or a comma list (``-a a,b`` = ``-a a -a b``), in
    order, without repeats; ``all`` (where allowed) expands to every approach."""
    from factask.gen.results import APPROACHES

    out: list[str] = []
    for item in (n.strip() for a in given for n in a.split(",") if n.strip()):
        for name in (APPROACHES if allow_all and item == "all" else (item,)):
            if name not in APPROACHES:
                _fail(f"unknown approach {name!r}; use {', '.join(APPROACHES)}"
                      + (" or all" if allow_all else ""))
            if name not in out:
                out.append(name)
    return out


@contextmanager
def _session(model: str | None, api_base: str | None, cache: Path | None,
             max_repairs: int, episodes: int, memory: Path | None, robot: str,
             temperature: float | None, response_format: str | None = None,
             seed: int | None = None, on_step: Any = None,
             references: Any = None) -> Iterator[Generator]:
    """The generator for a command: client (the local server started and stopped
    around the command), verifier, memory. A configuration that cannot work exits
    with one line and status 2. ``references``: a callable giving the reference
    graphs by task name, called only for a reference model (``local/reference``)."""
    check_robot(robot)
    from factask.gen.llm import LLMConfig, LLMConfigError, LLMFatalError, ResponseCache
    from factask.gen.local import LocalModelError
    from factask.gen.memory import SubtaskMemory
    from factask.gen.reference_model import ReferenceModelError, is_reference_model
    from factask.gen.session import open_client
    from factask.gen.strategies import Generator as _Generator
    from factask.gen.verify import Verifier

    try:
        config = LLMConfig.from_env(model=model, api_base=api_base, temperature=temperature,
                                    response_format=response_format, seed=seed)
    except LLMConfigError as exc:
        _fail(str(exc))
    cache_dir = cache or (Path(os.environ["FACTASK_CACHE"]) if os.environ.get("FACTASK_CACHE")
                          else None)
    graphs = references() if references is not None and is_reference_model(config.model) \
        else None
    try:
        with open_client(config, ResponseCache(cache_dir) if cache_dir else None,
                         references=graphs) as client:
            verifier = Verifier(episodes=episodes, robot=robot)
            yield _Generator(client, verifier, SubtaskMemory.from_env(memory), max_repairs,
                             on_step)
    except LLMFatalError as exc:
        _fail(exc.line())
    except (LocalModelError, LLMConfigError, ReferenceModelError) as exc:
        _fail(str(exc))


def _library_graphs() -> dict[str, Any]:
    """The library's graphs by name: the references ``local/reference`` answers from
    in ``factask generate``."""
    from factask.library import get_task, task_names

    return {n: get_task(n) for n in task_names()}


def _step_printer(say: Console) -> Any:
    """Prints each attempt of a step as it happens (on stderr under ``--json``)."""

    def print_step(rec: Any) -> None:
        mark = "[green]ok[/green]" if rec.ok else "[red]failed[/red]"
        cached = " [dim](cached)[/dim]" if rec.cached else ""
        say.print(f"  {rec.step} attempt {rec.attempt}: {mark}, level "
                  f"[bold]{rec.level}[/bold]{cached}")
        if rec.feedback:
            for line in rec.feedback.splitlines()[:12]:
                say.print(f"      {line}", markup=False)

    return print_step


@app.command()
def generate(
    proposal: str = typer.Argument(..., help="Task proposal: 'task-name: description' or text."),
    approach: str = typer.Option(None, "--approach", "-a", show_default=False,
                                 help=f"{_APPROACH_HELP}; {_DEFAULT_APPROACH_HELP}"),
    model: str = typer.Option(None, "--model", "-m", help=_MODEL_HELP),
    api_base: str = typer.Option(None, "--api-base", help="API base URL ($FACTASK_API_BASE)."),
    out: Path = typer.Option(None, "--out", "-o", help="Graph file (default <task>.json)."),
    cache: Path = typer.Option(None, "--cache", help="LLM answer cache dir ($FACTASK_CACHE)."),
    max_repairs: int = typer.Option(3, "--max-repairs", min=0, help="Repairs per step."),
    episodes: int = typer.Option(3, "--episodes", min=1, help="Oracle episodes (completion)."),
    memory: Path = typer.Option(None, "--memory", help="Subtask memory dir ($FACTASK_MEMORY)."),
    robot: str = typer.Option("floating", "--robot", help=f"{ROBOT_HELP} Runs the oracle "
                              "episodes of the completion check."),
    temperature: float = typer.Option(None, "--temperature", help="($FACTASK_TEMPERATURE)"),
    seed: int = typer.Option(None, "--seed", help="Sampling seed ($FACTASK_SEED)."),
    response_format: str = typer.Option(None, "--response-format", help=_FORMAT_HELP),
    strict: bool = typer.Option(False, "--strict", help="Write no graph when it leaves words "
                                "of the proposal unread (level partial)."),
    as_json: bool = typer.Option(False, "--json", help=JSON_HELP),
) -> None:
    """Generate a task graph with an LLM, verify it, write it.

    Every colour, number, order, side, quantifier, shape, relation and kind word of the
    proposal must be used by the graph: words it leaves unread are listed, and a graph
    the oracle completes then ends at level ``partial`` (exit 1; ``--strict`` writes no
    graph).

    Exit status: 0 completion reached, 1 not reached, 2 the configuration cannot
    work (key, model, quota, context; one line says the fix), 3 no LLM call
    succeeded. With ``--json`` the steps go to stderr and stdout holds one
    object: the generation's record (``GenerationResult.to_dict()``) plus
    ``graph_file`` and ``exit_code``.
    """
    import json

    from rich.markup import escape

    from factask.gen.results import DEFAULT_APPROACH

    chosen = _approaches([approach or DEFAULT_APPROACH], allow_all=False)
    if len(chosen) != 1:
        _fail(f"--approach {approach}: generate takes one approach (benchmark takes several)")
    approach = chosen[0]
    say = err_console if as_json else console
    with _session(model, api_base, cache, max_repairs, episodes, memory, robot, temperature,
                  response_format, seed, _step_printer(say), _library_graphs) as gen:
        say.print(f"[bold]generate[/bold] ({approach}, {escape(gen.client.config.model)}, "
                  f"structured output: {gen.client.form}): {escape(proposal)}")
        result = gen.generate(proposal, approach)
        succeeded = gen.client.succeeded
    path = None
    if result.unread:
        words = ", ".join(dict.fromkeys(repr(w["word"]) for w in result.unread))
        say.print(f"[yellow]unread:[/yellow] {escape(words)}")
        for w in {w["word"]: w for w in result.unread}.values():
            say.print(f"      {w['word']!r} ({w['category']}): {w['why']}", markup=False)
    if result.graph is not None and strict and result.unread:
        say.print("no graph written (--strict): the graph leaves proposal words unread")
    elif result.graph is not None:
        path = out or Path(f"{result.task}.json")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(result.graph.to_json())
        say.print(f"graph written to {escape(str(path))}")
    u = result.usage
    say.print(f"level reached: [bold]{result.level_reached}[/bold]; {u.calls} call(s) "
              f"({u.cached_calls} cached), {u.total_tokens} tokens, ${u.cost_usd:.4f}")
    if result.failure:
        say.print(f"[yellow]failure:[/yellow] {escape(result.failure.splitlines()[0])}")
    code = EXIT_NO_CALL if succeeded == 0 else (0 if result.completed else 1)
    if as_json:
        print(json.dumps({**result.to_dict(), "graph_file": str(path) if path else None,
                          "exit_code": code}))
    if code == EXIT_NO_CALL:
        _fail(f"no LLM call succeeded: {(result.failure or '').splitlines()[0]}", EXIT_NO_CALL)
    raise typer.Exit(code)


@app.command()
def benchmark(
    approach: list[str] = typer.Option(["all"], "--approach", "-a",
                                       help=f"{_APPROACH_HELP}; repeat it or give a "
                                            "comma list (-a one-shot,subtasks-first), or "
                                            "'all'."),
    model: str = typer.Option(None, "--model", "-m", help=_MODEL_HELP),
    api_base: str = typer.Option(None, "--api-base", help="API base URL ($FACTASK_API_BASE)."),
    tasks: Path = typer.Option(None, "--tasks",
                               help="Task list JSON (default: the 192 GenSim tasks shipped "
                                    "with factask)."),
    sample: str = typer.Option("all", "--sample",
                               help="all, or research55: the fixed 55-task sample "
                                    "(factask.evaluation.benchmark.research_sample)."),
    limit: int = typer.Option(None, "--limit", min=1, help="Only the first N tasks."),
    out: Path = typer.Option(..., "--out", "-o", help="Run directory (resumed if it exists)."),
    cache: Path = typer.Option(None, "--cache",
                               help="LLM cache dir (default $FACTASK_CACHE, else RUN_DIR/cache)."),
    max_repairs: int = typer.Option(3, "--max-repairs", min=0, help="Repairs per step."),
    episodes: int = typer.Option(3, "--episodes", min=1, help="Oracle episodes (completion)."),
    memory: Path = typer.Option(None, "--memory", help="Subtask memory dir ($FACTASK_MEMORY)."),
    robot: str = typer.Option("floating", "--robot", help=f"{ROBOT_HELP} Runs the oracle "
                              "episodes of the completion check."),
    temperature: float = typer.Option(None, "--temperature", help="($FACTASK_TEMPERATURE)"),
    seed: int = typer.Option(None, "--seed", help="Sampling seed ($FACTASK_SEED)."),
    response_format: str = typer.Option(None, "--response-format", help=_FORMAT_HELP),
    as_json: bool = typer.Option(False, "--json", help=JSON_HELP),
) -> None:
    """Run a task list through generation + verification; write JSONL, summary, chart.

    Exit status: 0 done, 2 the configuration cannot work (one line says the fix;
    finished pairs are kept), 3 no LLM call succeeded. With ``--json`` progress
    goes to stderr and stdout holds the summary (``summary.json``'s object) plus
    ``exit_code``.
    """
    import json

    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn

    from factask.evaluation.benchmark import (
        RESULTS_FILE,
        BenchmarkError,
        default_tasks_path,
        finished_pairs,
        load_tasks,
        read_results,
        reference_graph,
        research_sample,
        run_benchmark,
        summary_table,
    )
    approaches = _approaches(approach, allow_all=True)
    say = err_console if as_json else console
    if sample not in ("all", "research55"):
        _fail(f"unknown sample {sample!r}; use all or research55")
    tasks_path = tasks or default_tasks_path()
    try:
        task_list = load_tasks(tasks_path)
    except BenchmarkError as exc:
        _fail(str(exc))
    if sample == "research55":
        task_list = research_sample(task_list)
    if limit:
        task_list = task_list[:limit]
    cache_dir = cache or (Path(os.environ["FACTASK_CACHE"]) if os.environ.get("FACTASK_CACHE")
                          else out / "cache")
    done = finished_pairs(read_results(out / RESULTS_FILE))
    total = len(task_list) * len(approaches)
    already = sum(1 for t in task_list for a in approaches if (a, t.name) in done)
    if already:
        say.print(f"resuming {out}: {already} of {total} pair(s) already finished")
    ran = {"pairs": 0, "sent": 0}
    def references() -> dict[str, Any]:
        return {t.name: g for t in task_list if (g := reference_graph(t)) is not None}

    with _session(model, api_base, cache_dir, max_repairs, episodes, memory, robot,
                  temperature, response_format, seed, None, references) as gen, \
            Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                     console=say) as progress:
        bar = progress.add_task("benchmark", total=total, completed=already)

        def on_start(a: str, t: Any) -> None:
            progress.update(bar, description=f"{a} {t.name}")

        def on_result(record: dict[str, Any]) -> None:
            progress.advance(bar)
            ran["pairs"] += 1
            ran["sent"] += record.get("status") in ("done", "llm_error", "error")
            meaning = {True: "faithful", False: "not faithful"}.get(record.get("faithful"), "")
            progress.console.print(f"  {record['approach']:<16} {record['task']:<40} "
                                   f"{record['status']:<15} {record.get('level_reached')!s:<11}"
                                   f" {meaning}", markup=False)

        try:
            summary = run_benchmark(task_list, approaches, gen, out, on_start, on_result,
                                    meta={"model": gen.client.config.model,
                                          "structured_output": gen.client.form,
                                          "tasks_file": str(tasks_path), "sample": sample,
                                          "episodes": episodes, "max_repairs": max_repairs})
        except BenchmarkError as exc:
            _fail(str(exc))
        succeeded = gen.client.succeeded
    say.print(summary_table(summary), markup=False)
    say.print(f"results: {out / RESULTS_FILE}; summary: {out / 'summary.json'}, "
              f"{out / 'summary.md'}; chart: {out / 'rates.png'}", markup=False)
    no_call = bool(ran["sent"]) and succeeded == 0
    if as_json:
        print(json.dumps({**summary, "exit_code": EXIT_NO_CALL if no_call else 0},
                         default=str))
    if no_call:
        _fail(f"no LLM call succeeded in {ran['sent']} generation(s): see the failures in "
              f"{out / RESULTS_FILE}", EXIT_NO_CALL)


@app.command()
def compare(
    generated: str = typer.Argument(..., help="The graph to judge: FILE.json, a library task "
                                    "name or FILE.py[:Class] (a CLIPort task file)."),
    reference: str = typer.Argument(..., help="The task it should be (same forms)."),
    proposal: str = typer.Option(None, "--proposal", "-p", help="The words both graphs "
                                 "read: colours they do not name match any colour."),
    as_json: bool = typer.Option(False, "--json", help=JSON_HELP),
) -> None:
    """Does GENERATED mean the task REFERENCE is? Exit 0 when the two are the same task
    (the same objects, goals and orders, up to names, wording, weights, tolerances and
    numeric parameters), 1 when not, with what differs; 2 when either cannot be read."""
    import json

    from factask.cli.run_cmds import load_task
    from factask.gen.compare import compare as compare_graphs

    result = compare_graphs(load_task(generated), load_task(reference), proposal)
    if as_json:
        typer.echo(json.dumps({"generated": generated, "reference": reference,
                               **result.to_dict()}))
    else:
        verdict = "the same task" if result.equivalent else "a different task"
        console.print(f"{generated} vs {reference}: {verdict}; object F1 "
                      f"{result.object_f1:.2f}, relation F1 {result.relation_f1:.2f}, order "
                      f"agreement {result.order_agreement:.2f}", markup=False, soft_wrap=True)
        for line in result.differences:
            console.print(f"  {line}", markup=False, soft_wrap=True)
        for line in result.details:
            console.print(f"  (not counted) {line}", markup=False, soft_wrap=True)
    raise typer.Exit(0 if result.equivalent else 1)
