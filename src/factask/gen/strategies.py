"""The three generation strategies, each ending in a verified TaskGraph or a
structured failure.

* ``one-shot`` (baseline, GenSim's top-down chain of thought): the whole graph in
  one answer, verified, repaired with feedback.
* ``variables-first`` (approach 1): state variables -> subtasks over subsets of
  them (with their intended initial setting) -> each subtask's goal, verified on
  its own as a one-factor fragment -> assembly, verified as a whole.
* ``subtasks-first`` (approach 2): subtask names and descriptions -> per subtask
  its variables and goal, verified on its own, each later one prompted with the
  earlier results -> merge of shared variables (same name = same variable,
  conflicts reported back) -> assembly, verified as a whole.

Every step is a conversation: the answer is read as data against the step's
schema, checked, and on failure the precise message goes back to the model as
the next user message, at most ``max_repairs`` times.

Why one file of ~630 lines: the three strategies share one repair loop and its
bookkeeping (attempts, feedback, usage); issue 19 (per-step schemas and budgets)
rewrites the steps and will split them by strategy.
"""

from __future__ import annotations

import re
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

from pydantic import ValidationError

from factask.gen.examples import (
    Example,
    library_task_examples,
    render_examples,
    template_examples,
)
from factask.gen.llm import LLMAuthError, LLMClient, LLMError, LLMRequestError, Usage
from factask.gen.memory import SubtaskMemory, SubtaskMemoryError
from factask.gen.prompts import render, schema_text
from factask.gen.results import APPROACHES, AttemptRecord, GenerationResult
from factask.gen.schemas import (
    AnswerError,
    GoalAnswer,
    SubtaskDesign,
    SubtaskOutline,
    SubtaskPlan,
    VariablesAnswer,
    check_graph_size,
    format_problems,
    parse_answer,
    schema_of,
)
from factask.gen.verify import Level, Verifier, at_least, level_index
from factask.model.errors import (
    CompositionError,
    FactaskError,
    GraphValidationError,
    InvalidValueError,
    Problem,
)
from factask.model.factors import SubtaskFactor
from factask.model.graph import TaskGraph, graph_problems, problems_from_pydantic
from factask.model.names import slugify
from factask.model.templates import compose, extract_fragment
from factask.model.variables import StateVariable

T = TypeVar("T")
StepCallback = Callable[[AttemptRecord], None]
#: An evaluation turns answer text into (artefact or None, level, feedback or None).
Evaluation = tuple[Any, Level, "str | None"]


class UnknownApproachError(FactaskError):
    """An approach name that is not one of :data:`APPROACHES`."""


class _Abort(Exception):
    """A planning step never produced a usable answer; the generation stops."""


@dataclass
class _Outcome(Generic[T]):
    value: T | None
    level: Level
    ok: bool
    feedback: str | None


_PROPOSAL_RE = re.compile(r"^\s*([a-z0-9][a-z0-9_-]{1,99})\s*[:]\s+(.+)$", re.DOTALL)


#: Longest task name (:data:`factask.model.names.TASK_NAME_PATTERN`).
MAX_TASK_NAME = 100


def task_slug(text: str, max_words: int = 6) -> str:
    """A kebab-case task name from free text ("Stack the blocks!" -> "stack-the-blocks"),
    at most :data:`MAX_TASK_NAME` characters."""
    return slugify(text, "-", MAX_TASK_NAME, "generated-task", max_words=max_words,
                   letter_first=False)


def split_proposal(proposal: str) -> tuple[str, str]:
    """``"name: description"`` -> (name, description); free text -> (slug, text)."""
    m = _PROPOSAL_RE.match(proposal)
    if m:
        return task_slug(m.group(1).replace("_", "-"), max_words=20), m.group(2).strip()
    return task_slug(proposal), proposal.strip()


class Generator:
    """Runs the strategies against one LLM client and one verifier.

    Args:
        client: The LLM client (litellm, cache, usage).
        verifier: The ladder's checks (default :class:`Verifier`).
        memory: Subtask memory to read examples from and save verified subtasks to.
        max_repairs: Repairs per step after the first answer.
        on_step: Called with every :class:`AttemptRecord` as it happens.
        n_examples: In-context examples per prompt (per source).
    """

    def __init__(
        self,
        client: LLMClient,
        verifier: Verifier | None = None,
        memory: SubtaskMemory | None = None,
        max_repairs: int = 3,
        on_step: StepCallback | None = None,
        n_examples: int = 2,
    ) -> None:
        if max_repairs < 0:
            raise InvalidValueError("max_repairs must be >= 0")
        self.client = client
        self.verifier = verifier or Verifier()
        self.memory = memory
        self.max_repairs = max_repairs
        self.on_step = on_step
        self.n_examples = n_examples
        self._result: GenerationResult | None = None
        self._task = ""
        self._system = ""

    # ------------------------------------------------------------------ API
    def generate(self, proposal: str, approach: str = "variables-first",
                 name: str | None = None, description: str | None = None) -> GenerationResult:
        """Generate and verify a task from a proposal.

        Args:
            proposal: ``"task-name: description"`` or free text.
            approach: One of :data:`APPROACHES`.
            name: Task name (overrides the one read from the proposal).
            description: Task description (overrides the proposal's).

        Returns:
            The result: the best graph reached, its level, every step, usage.

        Raises:
            UnknownApproachError: ``approach`` is not known.
            LLMAuthError: the provider refused the credentials (no call can work).
        """
        if approach not in APPROACHES:
            raise UnknownApproachError(f"unknown approach {approach!r}; use one of "
                                       f"{', '.join(APPROACHES)}")
        task, desc = split_proposal(proposal)
        task = task_slug(name.replace("_", "-"), max_words=20) if name else task
        desc = description or desc
        result = GenerationResult(approach=approach, proposal=proposal, task=task)
        self._result = result
        self._task = task
        self._system = render("system")
        run = {"one-shot": self._one_shot, "variables-first": self._variables_first,
               "subtasks-first": self._subtasks_first}[approach]
        try:
            run(task, desc)
        except _Abort as exc:
            result.failure = str(exc)
        except LLMAuthError:
            self._result = None
            raise
        except LLMRequestError as exc:
            # The provider rejected the request (context window, content policy,
            # bad request): the model's failure, at the level reached so far.
            result.failure = f"LLM request rejected: {exc}"
        except LLMError as exc:
            result.failure = f"LLM call failed: {exc}"
            result.llm_error = True
        if result.failure is None and not result.completed:
            result.failure = f"stopped at level {result.level_reached!r}"
        self._result = None
        return result

    # ------------------------------------------------------------ machinery
    def _record(self, rec: AttemptRecord) -> None:
        assert self._result is not None
        self._result.steps.append(rec)
        if self.on_step is not None:
            self.on_step(rec)

    def _usage(self) -> Usage:
        assert self._result is not None
        return self._result.usage

    def _converse(self, step: str, prompt: str, schema: dict[str, Any], schema_name: str,
                  evaluate: Callable[[str], Evaluation], first_attempt: int = 0) -> _Outcome[Any]:
        """Ask, evaluate, feed back, up to ``max_repairs`` repairs; keep the best
        artefact together with its own feedback.

        A provider rejection (:class:`LLMRequestError`, e.g. the conversation
        outgrew the context window) after a usable artefact ends the step with
        that artefact; before one, it propagates.
        """
        messages = [{"role": "system", "content": self._system},
                    {"role": "user", "content": prompt}]
        best: tuple[int, Any, Level, str | None] | None = None
        feedback: str | None = None
        last = first_attempt + self.max_repairs
        for attempt in range(first_attempt, last + 1):
            try:
                reply = self.client.complete(messages, schema=schema, schema_name=schema_name)
            except LLMRequestError as exc:
                if best is None:
                    raise
                return _Outcome(best[1], best[2], False,
                                f"{best[3]}\n(then the LLM request was rejected: {exc})")
            self._usage().add(reply.usage)
            try:
                value, level, feedback = evaluate(reply.text)
            except AnswerError as exc:
                value, level, feedback = None, "none", exc.feedback
            except (LLMError, _Abort):
                raise
            except Exception as exc:  # a bug or an odd answer must not kill the run
                value, level = None, "none"
                feedback = (f"Checking the answer failed unexpectedly "
                            f"({type(exc).__name__}: {exc}). Send a simpler, valid answer "
                            "following the schema.")
            self._record(AttemptRecord(step, attempt, feedback is None, level, feedback,
                                    reply.cached, reply.usage.total_tokens,
                                    reply.usage.cost_usd))
            if value is not None and (best is None or level_index(level) > best[0]):
                best = (level_index(level), value, level, feedback)
            if feedback is None:
                return _Outcome(value, level, True, None)
            if attempt < last:
                messages.append({"role": "assistant", "content": reply.text})
                messages.append({"role": "user", "content": render(
                    "feedback", step=step, attempt=attempt + 1, max_attempts=last + 1,
                    feedback=feedback)})
        if best is None:
            return _Outcome(None, "none", False, feedback)
        return _Outcome(best[1], best[2], False, best[3])

    def _examples(self, query: str, sources: tuple[str, ...]) -> str:
        found: list[Example] = []
        k = self.n_examples
        # Never the task itself: a library task (or a remembered subtask) of the
        # same or a near-duplicate name would show the model the answer.
        if "tasks" in sources:
            found += library_task_examples(query, k, exclude=self._task or None)
        if "templates" in sources:
            found += template_examples(query, k)
        if "memory" in sources and self.memory is not None:
            found += self.memory.retrieve(query, k, exclude_task=self._task or None)
        return render_examples(found)

    def _remember(self, fragment: TaskGraph, task: str) -> None:
        if self.memory is None or self._result is None:
            return
        try:
            self.memory.save(fragment, task=task, approach=self._result.approach)
        except SubtaskMemoryError as exc:  # memory is a help, never a reason to fail
            warnings.warn(str(exc), stacklevel=2)

    def _evaluate_graph(self, task: str, desc: str) -> Callable[[str], Evaluation]:
        def evaluate(text: str) -> Evaluation:
            graph = self.verifier.syntax(text)
            # The task's name is ours, not the model's to choose; the renamed graph
            # is validated again (model_copy would skip validation).
            graph = self.verifier.syntax({**graph.to_dict(), "name": task,
                                          "description": graph.description or desc})
            check_graph_size(graph)
            outcome = self.verifier.check(graph)
            return graph, outcome.level, outcome.feedback
        return evaluate

    def _finish(self, graph: TaskGraph | None, level: Level, failure: str | None) -> None:
        assert self._result is not None
        self._result.graph = graph
        self._result.level_reached = level if graph is not None else "none"
        if failure and not at_least(self._result.level_reached, "completion"):
            self._result.failure = failure

    def _verify_assembled(self, task: str, desc: str, graph: TaskGraph | None,
                          problem: str | None) -> None:
        """Check the assembled graph; repair it with the model if the check fails."""
        step = "assembly"
        if graph is not None and problem is None:
            found = graph_problems(graph)
            if found:
                problem = (f"The assembled task graph is not valid ({len(found)} problem(s)):\n"
                           f"{format_problems(found)}")
        level: Level = "none"
        if graph is not None and problem is None:
            outcome = self.verifier.check(graph)
            level, problem = outcome.level, outcome.feedback
        else:
            level = "none"
        self._record(AttemptRecord(step, 0, problem is None, level, problem))
        if problem is None:
            self._finish(graph, level, None)
            return
        best_graph, best_level = (graph, level) if at_least(level, "syntax") else (None, "none")
        if self.max_repairs == 0:
            self._finish(best_graph, best_level, f"assembly: {problem}")
            return
        shown = graph.to_json(indent=None) if graph is not None else "{}"
        prompt = render("assembly", task_name=task, task_description=desc, graph=shown,
                        feedback=problem, schema=schema_text(TaskGraph.json_schema()))
        try:
            out = self._converse(step, prompt, TaskGraph.json_schema(), "task_graph",
                                 self._evaluate_graph(task, desc), first_attempt=1)
        except LLMRequestError as exc:  # keep the assembled graph and its level
            self._finish(best_graph, best_level, f"assembly: {problem}\n(then the LLM "
                         f"request was rejected: {exc})")
            return
        if out.value is not None and level_index(out.level) >= level_index(best_level):
            best_graph, best_level = out.value, out.level
        self._finish(best_graph, best_level,
                     None if out.ok else f"assembly: {out.feedback}")

    # ------------------------------------------------------------- one-shot
    def _one_shot(self, task: str, desc: str) -> None:
        query = f"{task} {desc}"
        prompt = render("one_shot", task_name=task, task_description=desc,
                        examples=self._examples(query, ("tasks", "memory")),
                        schema=schema_text(TaskGraph.json_schema()))
        out = self._converse("one_shot", prompt, TaskGraph.json_schema(), "task_graph",
                             self._evaluate_graph(task, desc))
        self._finish(out.value, out.level, None if out.ok else f"one_shot: {out.feedback}")
        if out.ok and out.value is not None:
            for f in out.value.factors:
                self._remember(extract_fragment(out.value, f.name), task)

    # ------------------------------------------------------ variables-first
    def _variables_first(self, task: str, desc: str) -> None:
        query = f"{task} {desc}"
        variables = self._ask_variables(task, desc, query)
        by_name = {v.name: v for v in variables}
        plan = self._ask_plan(task, desc, query, variables)
        factors: list[SubtaskFactor] = []
        for sub in plan.subtasks:
            scope_vars = _closure([by_name[n] for n in sub.variables], by_name)
            prompt = render(
                "subtask_goal", task_name=task, task_description=desc,
                subtask_name=sub.name, subtask_description=sub.description,
                initial_setup=sub.initial_setup or "(nothing)",
                variables=_vars_json(scope_vars),
                examples=self._examples(f"{sub.name} {sub.description}",
                                        ("memory", "templates")),
                schema=schema_text(schema_of(GoalAnswer)))

            def evaluate(text: str, sub: Any = sub, scope_vars: Any = scope_vars) -> Evaluation:
                answer = parse_answer(text, GoalAnswer)
                _check_goal_scope(answer, sub.name, list(sub.variables), by_name)
                factor = _make_factor(sub.name, answer.description or sub.description,
                                      answer.goal, scope=list(sub.variables),
                                      initial_setup=sub.initial_setup)
                fragment = _fragment(task, factor, scope_vars)
                outcome = self.verifier.check(fragment)
                return (factor, fragment), outcome.level, outcome.feedback

            out = self._converse(f"subtask_goal:{sub.name}", prompt, schema_of(GoalAnswer),
                                 "goal_answer", evaluate)
            if out.value is None:
                raise _Abort(f"subtask {sub.name!r}: no valid goal after "
                             f"{self.max_repairs + 1} attempt(s): {out.feedback}")
            factor, fragment = out.value
            if out.ok:
                self._remember(fragment, task)
            factors.append(factor)
        n = len(factors)
        graph = None
        problem = None
        try:
            graph = TaskGraph(name=task, description=desc, variables=variables,
                              factors=[f.model_copy(update={"weight": 1.0 / n})
                                       for f in factors])
        except ValidationError as exc:
            problem = format_problems(problems_from_pydantic(exc, {}))
        self._verify_assembled(task, desc, graph, problem)

    def _ask_variables(self, task: str, desc: str, query: str) -> list[StateVariable]:
        prompt = render("variables", task_name=task, task_description=desc,
                        examples=self._examples(query, ("tasks", "memory")),
                        schema=schema_text(schema_of(VariablesAnswer)))

        def evaluate(text: str) -> Evaluation:
            answer = parse_answer(text, VariablesAnswer)
            found = graph_problems(TaskGraph(name=task, variables=answer.variables))
            if found:
                return None, "none", ("The variables are not consistent:\n"
                                      + format_problems(found))
            return answer.variables, "syntax", None

        out = self._converse("variables", prompt, schema_of(VariablesAnswer),
                             "variables_answer", evaluate)
        if not out.ok:
            raise _Abort(f"variables: {out.feedback}")
        return list(out.value)

    def _ask_plan(self, task: str, desc: str, query: str,
                  variables: list[StateVariable]) -> SubtaskPlan:
        names = [v.name for v in variables]
        prompt = render("subtask_plan", task_name=task, task_description=desc,
                        variables=_vars_json(variables),
                        examples=self._examples(query, ("memory", "templates")),
                        schema=schema_text(schema_of(SubtaskPlan)))

        def evaluate(text: str) -> Evaluation:
            plan = parse_answer(text, SubtaskPlan)
            problems: list[Problem] = []
            seen: set[str] = set()
            for s in plan.subtasks:
                if s.name in seen:
                    problems.append(Problem(s.name, "name", "two subtasks have this name",
                                            "rename one"))
                if s.name in names:
                    problems.append(Problem(s.name, "name", "a variable has this name",
                                            "rename the subtask"))
                seen.add(s.name)
                for v in s.variables:
                    if v not in names:
                        problems.append(Problem(s.name, "variables", f"unknown variable {v!r}",
                                                f"use only {names}"))
            if problems:
                return None, "none", ("The subtask plan has problems:\n"
                                      + format_problems(problems))
            return plan, "syntax", None

        out = self._converse("subtask_plan", prompt, schema_of(SubtaskPlan), "subtask_plan",
                             evaluate)
        if not out.ok:
            raise _Abort(f"subtask_plan: {out.feedback}")
        return out.value

    # ------------------------------------------------------- subtasks-first
    def _subtasks_first(self, task: str, desc: str) -> None:
        query = f"{task} {desc}"
        outline = self._ask_outline(task, desc, query)
        outline_text = "; ".join(f"`{s.name}`: {s.description}" for s in outline.subtasks)
        defined: dict[str, tuple[StateVariable, str]] = {}  # name -> (variable, subtask)
        moved: dict[str, str] = {}  # variable -> subtask that moves it
        fragments: list[TaskGraph] = []
        earlier: list[dict[str, Any]] = []
        for sub in outline.subtasks:
            prompt = render(
                "subtask_design", task_name=task, task_description=desc, outline=outline_text,
                subtask_name=sub.name, subtask_description=sub.description,
                earlier=_earlier_text(earlier),
                examples=self._examples(f"{sub.name} {sub.description}",
                                        ("memory", "templates")),
                schema=schema_text(schema_of(SubtaskDesign)))

            def evaluate(text: str, sub: Any = sub) -> Evaluation:
                design = parse_answer(text, SubtaskDesign)
                problems = _merge_problems(design, defined, moved)
                if problems:
                    return None, "none", (
                        "The subtask's variables conflict with the earlier subtasks "
                        "(a shared name means the same object):\n" + format_problems(problems))
                local = {v.name: v for v in design.variables}
                known = {n: v for n, (v, _) in defined.items()}
                wanted = [local.get(n) or known[n] for n in design.goal.variable_names()
                          if n in local or n in known]
                wanted += [v for v in design.variables if v not in wanted]
                scope_vars = _closure(wanted, {**known, **local})
                factor = _make_factor(sub.name, design.description or sub.description,
                                      design.goal, scope=None)
                fragment = _fragment(task, factor, scope_vars)
                outcome = self.verifier.check(fragment)
                return fragment, outcome.level, outcome.feedback

            out = self._converse(f"subtask_design:{sub.name}", prompt, schema_of(SubtaskDesign),
                                 "subtask_design", evaluate)
            if out.value is None:
                raise _Abort(f"subtask {sub.name!r}: no valid design after "
                             f"{self.max_repairs + 1} attempt(s): {out.feedback}")
            fragment = out.value
            if out.ok:
                self._remember(fragment, task)
            fragments.append(fragment)
            for v in fragment.variables:
                defined.setdefault(v.name, (v, sub.name))
            for o in fragment.factors[0].goal.objects:
                moved.setdefault(o, sub.name)
            earlier.append({"subtask": sub.name, "verified": out.ok,
                            "variables": [v.model_dump(mode="json", exclude_none=True)
                                          for v in fragment.variables],
                            "goal": fragment.factors[0].goal.model_dump(mode="json",
                                                                         exclude_none=True)})
        graph = None
        problem = None
        try:
            graph = compose(*fragments, name=task, description=desc)
        except CompositionError as exc:
            problem = f"Merging the subtasks failed: {exc}"
        self._verify_assembled(task, desc, graph, problem)

    def _ask_outline(self, task: str, desc: str, query: str) -> SubtaskOutline:
        prompt = render("subtask_outline", task_name=task, task_description=desc,
                        examples=self._examples(query, ("memory", "templates")),
                        schema=schema_text(schema_of(SubtaskOutline)))

        def evaluate(text: str) -> Evaluation:
            outline = parse_answer(text, SubtaskOutline)
            names = [s.name for s in outline.subtasks]
            dup = sorted({n for n in names if names.count(n) > 1})
            if dup:
                return None, "none", f"Subtask names must be unique; repeated: {dup}"
            return outline, "syntax", None

        out = self._converse("subtask_outline", prompt, schema_of(SubtaskOutline),
                             "subtask_outline", evaluate)
        if not out.ok:
            raise _Abort(f"subtask_outline: {out.feedback}")
        return out.value


# ---------------------------------------------------------------- helpers
def _vars_json(variables: list[StateVariable]) -> str:
    import json

    return json.dumps([v.model_dump(mode="json", exclude_none=True) for v in variables],
                      separators=(",", ":"))


def _earlier_text(earlier: list[dict[str, Any]]) -> str:
    import json

    if not earlier:
        return "(this is the first subtask)"
    return "\n".join(json.dumps(e, separators=(",", ":")) for e in earlier)


def _closure(variables: list[StateVariable],
             pool: dict[str, StateVariable]) -> list[StateVariable]:
    """``variables`` plus every variable their initial placements rest on/inside."""
    out = list(variables)
    names = {v.name for v in out}
    i = 0
    while i < len(out):
        for ref in out[i].references():
            if ref not in names and ref in pool:
                out.append(pool[ref])
                names.add(ref)
        i += 1
    return out


def _check_goal_scope(answer: GoalAnswer, subtask: str, scope: list[str],
                      pool: dict[str, StateVariable]) -> None:
    """Approach 1: the goal may use only the subtask's planned variables.

    Raises:
        AnswerError: naming each variable outside the scope, plus any other problem
            the goal has with those variables (e.g. a zone used as a support).
    """
    outside = [n for n in answer.goal.variable_names() if n not in scope]
    if not outside:
        return
    problems = [Problem(subtask, "goal", f"uses {n!r}, which is not one of this subtask's "
                        f"variables {scope}" + ("" if n in pool else " nor a task variable"),
                        f"use only {scope}") for n in outside]
    trial = TaskGraph(name="trial", variables=_closure(
        [pool[n] for n in [*scope, *outside] if n in pool], pool),
        factors=[SubtaskFactor(name=subtask, goal=answer.goal)])
    problems += [p for p in graph_problems(trial) if "missing variable" not in p.message]
    raise AnswerError("The goal does not fit the subtask:\n" + format_problems(problems),
                      problems)


def _make_factor(name: str, description: str, goal: Any, scope: list[str] | None,
                 initial_setup: str = "") -> SubtaskFactor:
    data: dict[str, Any] = {"name": name, "description": description,
                            "goal": goal.model_dump(mode="python", exclude_none=True),
                            "initial_setup": initial_setup}
    if scope is not None:
        data["scope"] = scope
    try:
        return SubtaskFactor.model_validate(data)
    except ValidationError as exc:
        problems = problems_from_pydantic(exc, data)
        raise AnswerError(f"The subtask is not valid:\n{format_problems(problems)}",
                          problems) from None


def _fragment(task: str, factor: SubtaskFactor, variables: list[StateVariable]) -> TaskGraph:
    """The single-factor fragment (weight 1) with its variables, valid as a whole.

    Raises:
        AnswerError: the fragment has problems (each naming its node).
    """
    name = f"{task}-{factor.name.replace('_', '-')}"[:100]
    graph = TaskGraph(name=name, description=factor.description, variables=variables,
                      factors=[factor.model_copy(update={"weight": 1.0, "after": []})])
    try:
        graph.ensure_valid()
    except GraphValidationError as exc:
        raise AnswerError(f"The subtask is not valid on its own ({len(exc.problems)} "
                          f"problem(s)):\n{format_problems(exc.problems)}",
                          exc.problems) from None
    return graph


def _merge_problems(design: SubtaskDesign, defined: dict[str, tuple[StateVariable, str]],
                    moved: dict[str, str]) -> list[Problem]:
    """Conflicts of a new subtask with the earlier ones (shared names, moved twice)."""
    problems = []
    for v in design.variables:
        if v.name in defined and defined[v.name][0] != v:
            old, where = defined[v.name]
            diff = [f"{k}: {getattr(old, k)!r} vs {getattr(v, k)!r}"
                    for k in type(v).model_fields if getattr(old, k) != getattr(v, k)]
            problems.append(Problem(v.name, "", f"defined differently by subtask {where!r} "
                                    f"({'; '.join(diff)})",
                                    "repeat it exactly, leave it out, or use a new name"))
    for o in design.goal.objects:
        if o in moved:
            problems.append(Problem(o, "goal.objects", f"is already moved by subtask "
                                    f"{moved[o]!r}; an object has one goal",
                                    "anchor on it instead (e.g. 'on' with support) or move "
                                    "another object"))
    return problems


def generate(proposal: str, approach: str, client: LLMClient, verifier: Verifier | None = None,
             memory: SubtaskMemory | None = None, max_repairs: int = 3,
             on_step: StepCallback | None = None) -> GenerationResult:
    """One-call form of :meth:`Generator.generate`."""
    return Generator(client, verifier, memory, max_repairs, on_step).generate(proposal, approach)
