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

Each step sends the strict JSON Schema of exactly its answer
(:mod:`factask.gen.answers.step_schemas`: the variables declared so far are enums where
the step refers to them) and runs as a conversation (:class:`~factask.gen.steps.StepRunner`).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from typing import Any

from pydantic import ValidationError

from factask.gen import grounded_steps
from factask.gen import grounded_subtasks as gs
from factask.gen.answers import step_schemas as ss
from factask.gen.answers.schemas import (
    AnswerError,
    GoalAnswer,
    OutlinedSubtask,
    SubtaskDesign,
    SubtaskOutline,
    SubtaskPlan,
    VariablesAnswer,
    check_graph_size,
    format_problems,
    validate_answer,
)
from factask.gen.conversation import PromptLevel
from factask.gen.fragments import (
    as_planned,
    ask_design,
    check_goal_scope,
    checked_fragment,
    closure,
    earlier_text,
    fragment,
    make_factor,
    merge_problems,
    order_problems,
    own_fragment,
    plan_problems,
    relabelled,
    vars_json,
    without_repeats,
)
from factask.gen.llm import LLMClient, LLMError, LLMFatalError, LLMRequestError
from factask.gen.memory import SubtaskMemory
from factask.gen.prompts import render, schema_skeleton
from factask.gen.reading import grounded
from factask.gen.reading.accounting import account, unread_summary
from factask.gen.reading.clauses import still_objects
from factask.gen.reading.mentions import grounding_feedback, mentions, mentions_text
from factask.gen.results import APPROACHES, DEFAULT_APPROACH, GenerationResult
from factask.gen.steps import (
    Abort,
    Evaluation,
    M,
    StepCallback,
    StepRunner,
    read_graph_answer,
    read_strict,
    read_valid,
)
from factask.gen.verify import Level, Verifier, at_least, level_index
from factask.graph.factors import SubtaskFactor
from factask.graph.taskgraph import TaskGraph, graph_problems, problems_from_pydantic
from factask.graph.templates import compose, extract_fragment
from factask.vocabulary.errors import CompositionError, FactaskError
from factask.vocabulary.names import slugify
from factask.vocabulary.variables import StateVariable


class UnknownApproachError(FactaskError):
    """An approach name that is not one of :data:`APPROACHES`."""


_PROPOSAL_RE = re.compile(r"^\s*([a-z0-9][a-z0-9_-]{1,99})\s*[:]\s+(.+)$", re.DOTALL)

#: Longest task name (:data:`factask.vocabulary.names.TASK_NAME_PATTERN`).
MAX_TASK_NAME = 100


#: Words a generated task's name leaves out (articles) or does not end on (a name
#: cut after "in the" reads as half a phrase: ``put-the-red-block-in-the``).
_NAME_SKIPS = frozenset({"the", "a", "an"})
_NAME_DANGLING = frozenset({"in", "into", "on", "onto", "to", "of", "and", "with", "at", "by",
                            "for", "from", "then", "next", "inside", "over", "under",
                            "between", "near", "beside", "around", "along", "so", "that",
                            "each", "every", "all", "its", "their", "your"})


def task_slug(text: str, max_words: int = 8) -> str:
    """A kebab-case task name from free text, in whole words: articles left out, at
    most ``max_words`` words, never ending on a preposition or conjunction ("put the
    red block in the green bowl" -> "put-red-block-in-green-bowl"), at most
    :data:`MAX_TASK_NAME` characters."""
    words = [w for w in re.findall(r"[a-z0-9]+", text.lower()) if w not in _NAME_SKIPS]
    words = words[:max_words]
    while len(words) > 1 and words[-1] in _NAME_DANGLING:
        words.pop()
    return slugify(" ".join(words), "-", MAX_TASK_NAME, "generated-task",
                   letter_first=False)


def given_name(name: str) -> str:
    """A name the user gave, made kebab-case and nothing more (every word kept)."""
    return slugify(name.replace("_", "-"), "-", MAX_TASK_NAME, "generated-task",
                   max_words=20, letter_first=False)


def split_proposal(proposal: str) -> tuple[str, str]:
    """``"name: description"`` -> (name, description); free text -> (slug, text)."""
    m = _PROPOSAL_RE.match(proposal)
    if m:
        return given_name(m.group(1)), m.group(2).strip()
    return task_slug(proposal), proposal.strip()


def normalise_weights(data: dict[str, Any]) -> dict[str, Any]:
    """A graph answer with its factor weights scaled to sum to 1 (positive numbers
    only; anything else is left for validation to report). Shares are arithmetic
    the library does, not the model."""
    factors = data.get("factors")
    if not isinstance(factors, list) or not factors:
        return data
    weights = [f.get("weight") if isinstance(f, dict) else None for f in factors]
    if not all(isinstance(w, (int, float)) and not isinstance(w, bool) and w > 0
               for w in weights):
        return data
    total = float(sum(weights))  # type: ignore[arg-type]
    return {**data, "factors": [{**f, "weight": float(w) / total}
                                for f, w in zip(factors, weights, strict=True)]}


def _kinds(variables: list[StateVariable]) -> dict[str, str]:
    return {v.name: v.kind for v in variables}


class Generator(StepRunner):
    """Runs the strategies against one LLM client and one verifier.

    Args:
        client: The LLM client (litellm, cache, usage).
        verifier: The ladder's checks (default :class:`Verifier`).
        memory: Subtask memory to read examples from and save verified subtasks to.
        max_repairs: Repairs per step after the first answer.
        on_step: Called with every :class:`AttemptRecord` as it happens.
        n_examples: In-context examples per prompt (per source).
        grounded: Fix the objects the proposal names in the step schemas and ask
            one-shot for a compact answer (:mod:`factask.gen.reading.grounded`); None:
            for the packaged local models only (a tiny model on a CPU), whose
            ``config.is_local`` is true.
    """

    def __init__(self, client: LLMClient, verifier: Verifier | None = None,
                 memory: SubtaskMemory | None = None, max_repairs: int = 3,
                 on_step: StepCallback | None = None, n_examples: int = 2,
                 grounded: bool | None = None) -> None:
        super().__init__(client, verifier, memory, max_repairs, on_step, n_examples)
        if grounded is None:
            grounded = bool(getattr(getattr(client, "config", None), "is_local", False))
        self.grounded = grounded

    # ------------------------------------------------------------------ API
    def generate(self, proposal: str, approach: str = DEFAULT_APPROACH,
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
            LLMFatalError: key, model, quota or context error (no call can work).
        """
        if approach not in APPROACHES:
            raise UnknownApproachError(f"unknown approach {approach!r}; use one of "
                                       f"{', '.join(APPROACHES)}")
        task, desc = split_proposal(proposal)
        task = given_name(name) if name else task
        desc = description or desc
        result = GenerationResult(approach=approach, proposal=proposal, task=task)
        self._result = result
        self._task = task
        run = {"one-shot": self._one_shot, "variables-first": self._variables_first,
               "subtasks-first": self._subtasks_first}[approach]
        try:
            run(task, desc)
        except Abort as exc:
            result.failure = str(exc)
        except LLMFatalError:
            self._result = None
            raise
        except LLMRequestError as exc:
            # The provider rejected the request (bad request, content policy): the
            # model's failure, at the level reached so far.
            result.failure = f"LLM request rejected: {exc}"
        except LLMError as exc:
            result.failure = f"LLM call failed: {exc}"
            result.llm_error = True
        if result.graph is not None:
            self._account(result, proposal)
        if result.failure is None and not result.completed:
            result.failure = f"stopped at level {result.level_reached!r}"
        self._result = None
        return result

    @staticmethod
    def _account(result: GenerationResult, proposal: str) -> None:
        """Record the proposal's words the final graph leaves unread; a completed graph
        with any ends at ``partial``: never a confident wrong task."""
        assert result.graph is not None
        accounting = account(proposal, result.graph)
        result.unread = accounting.to_dict()["unread"]
        if accounting.unread and result.level_reached == "completion":
            result.level_reached = "partial"
            if result.failure is None:
                result.failure = ("the oracle completes the graph, but it leaves words of the "
                                  f"proposal unread: {unread_summary(accounting.unread)}")

    # ---------------------------------------------------------- whole graphs
    def _evaluate_graph(self, task: str, desc: str, schema: dict[str, Any],
                        expand: Callable[[dict[str, Any]], dict[str, Any]] | None = None
                        ) -> Any:
        def evaluate(text: str) -> Evaluation:
            if expand is not None:  # a compact answer: its decisions -> the whole graph
                data = expand(read_strict(text, schema))
            else:
                data = normalise_weights(read_graph_answer(text, schema, {"name": task}))
            # The task's name is ours, not the model's to choose.
            graph = self.verifier.syntax({**data, "name": task,
                                          "description": data.get("description") or desc})
            check_graph_size(graph)
            lacking = grounding_feedback(f"{desc} {task}", graph.variables)
            if lacking:
                return None, "none", lacking
            outcome = self.verifier.check(graph)
            return graph, outcome.level, outcome.feedback
        return evaluate

    def _verify_assembled(self, task: str, desc: str, graph: TaskGraph | None,
                          problem: str | None, grounded_repair: bool = False) -> None:
        """Check the assembled graph; repair it with the model if the check fails
        (``grounded_repair``: in the grounded one-shot's grammar, where the words
        decide the objects and goals, as one-shot's own repairs are)."""
        step = "assembly"
        if graph is not None and problem is None:
            found = graph_problems(graph)
            if found:
                problem = (f"The assembled task graph is not valid ({len(found)} problem(s)):\n"
                           f"{format_problems(found)}")
            else:
                problem = grounding_feedback(f"{desc} {task}", graph.variables)
        level: Level = "none"
        if graph is not None and problem is None:
            outcome = self.verifier.check(graph)
            level, problem = outcome.level, outcome.feedback
        from factask.gen.results import AttemptRecord

        self._record(AttemptRecord(step, 0, problem is None, level, problem))
        if problem is None:
            self.finish(graph, level, None)
            return
        best_graph, best_level = (graph, level) if at_least(level, "syntax") else (None, "none")
        if self.max_repairs == 0:
            self.finish(best_graph, best_level, f"assembly: {problem}")
            return
        shown = graph.to_json(indent=None) if graph is not None else "{}"
        found = mentions(f"{desc} {task}")
        schema = grounded.compact_graph_schema(found, desc) if grounded_repair \
            else ss.graph_schema(task)
        expand = self._expand_compact(task, desc, found) if grounded_repair else None

        def prompt(lv: PromptLevel) -> str:
            return render("assembly", task_name=task, task_description=desc, graph=shown,
                          feedback=problem, schema=self.schema_for_prompt(schema, lv))

        try:
            out = self.ask(step, prompt, schema, "task_graph",
                           self._evaluate_graph(task, desc, schema, expand), first_attempt=1)
        except LLMRequestError as exc:  # keep the assembled graph and its level
            self.finish(best_graph, best_level, f"assembly: {problem}\n(then the LLM "
                        f"request was rejected: {exc})")
            return
        if out.value is not None and level_index(out.level) >= level_index(best_level):
            best_graph, best_level = out.value, out.level
        self.finish(best_graph, best_level, None if out.ok else f"assembly: {out.feedback}")

    # ------------------------------------------------------------- one-shot
    @staticmethod
    def _expand_compact(task: str, desc: str,
                        found: list[Any]) -> Callable[[dict[str, Any]], dict[str, Any]]:
        """A grounded one-shot answer -> the whole graph's data (its goals checked
        against the proposal's objects first)."""
        def expand(data: dict[str, Any]) -> dict[str, Any]:
            problems = grounded.goal_problems([f["goal"] for f in data["factors"]], found,
                                              still_objects(desc, found))
            if problems:
                raise AnswerError("The goals do not make the proposal's task:\n"
                                  + "\n".join(f"- {p}" for p in problems))
            return grounded.expand_graph(data, found, task, desc)
        return expand

    def _one_shot(self, task: str, desc: str) -> None:
        query = f"{task} {desc}"
        found = mentions(f"{desc} {task}")
        # The objects the proposal names come from its words; the model writes the
        # decisions (factask.gen.reading.grounded).
        compact = self.grounded and grounded.applies(found)
        schema = grounded.compact_graph_schema(found, desc) if compact else \
            ss.graph_schema(task)
        # The prompt shows the plain goal list's outline: the grammar's shapes
        # (factask.gen.reading.cover) would only lengthen it.
        outline = schema_skeleton(grounded.compact_graph_schema(found, desc, cover=False)) \
            if compact else ""

        def prompt(lv: PromptLevel) -> str:
            if compact:
                k = min(lv.examples, self.n_examples)
                # The grammar holds the answer to the schema: the prompt shows its
                # outline only (prompt processing dominates a call on a CPU).
                return render("one_shot_grounded", task_name=task, task_description=desc,
                              mentions=mentions_text(f"{desc} {task}"),
                              examples=grounded.compact_examples(query, k, task),
                              schema=outline)
            return render("one_shot", task_name=task, task_description=desc,
                          mentions=mentions_text(f"{desc} {task}"),
                          examples=self.examples(query, ("tasks", "memory"), lv.examples),
                          schema=self.schema_for_prompt(schema, lv))

        out = self.ask("one_shot", prompt, schema, "task_graph",
                       self._evaluate_graph(task, desc, schema,
                                            self._expand_compact(task, desc, found)
                                            if compact else None))
        self.finish(out.value, out.level, None if out.ok else f"one_shot: {out.feedback}")
        if out.ok and out.value is not None:
            for f in out.value.factors:
                self.remember(extract_fragment(out.value, f.name), task)

    # ------------------------------------------------------ variables-first
    def read(self, text: str, schema: dict[str, Any], model: type[M]) -> M:
        """A step's answer: the strict schema, or, on the ungrounded path, any answer
        the step's model takes (:func:`factask.gen.steps.read_valid`)."""
        if self.grounded:
            return validate_answer(read_strict(text, schema), model)
        return read_valid(text, schema, model)

    def _shaped(self, task: str, desc: str) -> grounded_steps.GroundedTask | None:
        """The grounded one-shot grammar in pieces, where grounding applies and its
        goals are a list of fixed length (None: the general steps)."""
        found = mentions(f"{desc} {task}")
        if not (self.grounded and grounded.applies(found)):
            return None
        return grounded_steps.grounded_task(found, desc)

    def _variables_first(self, task: str, desc: str) -> None:
        shaped = self._shaped(task, desc)
        if shaped is not None:  # the one-shot grammar's decisions, piece by piece
            self._verify_assembled(task, desc, *grounded_steps.variables_first(
                self, task, desc, shaped), grounded_repair=True)
            return
        query = f"{task} {desc}"
        variables = self._ask_variables(task, desc, query)
        by_name = {v.name: v for v in variables}
        plan = self._ask_plan(task, desc, query, variables)
        factors: list[SubtaskFactor] = []
        for sub in plan.subtasks:
            scope_vars = closure([by_name[n] for n in sub.variables], by_name)
            planned = [by_name[n] for n in sub.variables]
            before = list(factors)
            schema = grounded.goal_answer(planned, f"{desc} {sub.description}") \
                if self.grounded else ss.goal_answer(
                    _kinds(planned), [v.name for v in planned if v.fixed is False])

            def prompt(lv: PromptLevel, sub: Any = sub, scope_vars: Any = scope_vars,
                       schema: Any = schema) -> str:
                return render(
                    "subtask_goal", task_name=task, task_description=desc,
                    subtask_name=sub.name, subtask_description=sub.description,
                    initial_setup=sub.initial_setup or "(nothing)",
                    variables=vars_json(scope_vars),
                    examples=self.examples(f"{sub.name} {sub.description}",
                                           ("memory", "templates"), lv.examples),
                    schema=self.schema_for_prompt(schema, lv))

            def evaluate(text: str, sub: Any = sub, scope_vars: Any = scope_vars,
                         schema: Any = schema, before: Any = before) -> Evaluation:
                answer = self.read(text, schema, GoalAnswer)
                check_goal_scope(answer, sub.name, list(sub.variables), by_name)
                factor = make_factor(sub.name, answer.description or sub.description,
                                     answer.goal, scope=list(sub.variables),
                                     initial_setup=sub.initial_setup,
                                     after=sub.after)
                piece = fragment(task, factor, scope_vars, before, by_name)
                outcome = self.verifier.check(piece)
                return (factor, own_fragment(piece, factor.name)), outcome.level, \
                    outcome.feedback

            out = self.ask(f"subtask_goal:{sub.name}", prompt, schema, "goal_answer", evaluate)
            if out.value is None:
                raise Abort(f"subtask {sub.name!r}: no valid goal after "
                            f"{self.max_repairs + 1} attempt(s): {out.feedback}")
            factor, piece = out.value
            if out.ok:
                self.remember(piece, task)
            factors.append(factor)
        n = len(factors)
        graph = None
        problem = None
        try:
            # The plan lists its subtasks in the order they are done: that order
            # sequences the subtasks that move the same object (earlier ones
            # become milestones, as in Ravens' goal queue).
            graph = TaskGraph(name=task, description=desc, variables=variables,
                              factors=as_planned([f.model_copy(update={"weight": 1.0 / n})
                                                  for f in factors], plan.subtasks))
        except ValidationError as exc:
            problem = format_problems(problems_from_pydantic(exc, {}))
        self._verify_assembled(task, desc, graph, problem)

    def _ask_variables(self, task: str, desc: str, query: str) -> list[StateVariable]:
        found = mentions(f"{desc} {task}")
        use = self.grounded and grounded.applies(found)
        schema = grounded.variables_answer(found) if use else ss.variables_answer()
        named = [m.name for m in found] if use else []

        def prompt(lv: PromptLevel) -> str:
            return render("variables", task_name=task, task_description=desc,
                          mentions=mentions_text(f"{desc} {task}"),
                          examples=self.examples(query, ("tasks", "memory"), lv.examples),
                          schema=self.schema_for_prompt(schema, lv))

        def evaluate(text: str) -> Evaluation:
            answer = self.read(text, schema, VariablesAnswer)
            answer.variables = without_repeats(answer.variables, named)
            found = graph_problems(TaskGraph(name=task, variables=answer.variables))
            if found:
                return None, "none", ("The variables are not consistent:\n"
                                      + format_problems(found))
            lacking = grounding_feedback(f"{desc} {task}", answer.variables)
            if lacking:
                return None, "none", lacking
            return answer.variables, "syntax", None

        return list(self.ask_or_abort("variables", prompt, schema, "variables_answer", evaluate))

    def _ask_plan(self, task: str, desc: str, query: str,
                  variables: list[StateVariable]) -> SubtaskPlan:
        names = [v.name for v in variables]
        schema = ss.subtask_plan(names, grounded.plan_bound(variables) if self.grounded
                                 else ss.STEP_MAX_SUBTASKS)

        def prompt(lv: PromptLevel) -> str:
            return render("subtask_plan", task_name=task, task_description=desc,
                          variables=vars_json(variables),
                          examples=self.examples(query, ("memory", "templates"), lv.examples),
                          schema=self.schema_for_prompt(schema, lv))

        def evaluate(text: str) -> Evaluation:
            plan = self.read(text, schema, SubtaskPlan)
            plan = plan.model_copy(update={"subtasks": relabelled(plan.subtasks, names)})
            problems = plan_problems(plan, variables)
            if problems:
                return None, "none", ("The subtask plan has problems:\n"
                                      + format_problems(problems))
            return plan, "syntax", None

        return self.ask_or_abort("subtask_plan", prompt, schema, "subtask_plan", evaluate)

    # ------------------------------------------------------- subtasks-first
    def _subtasks_first(self, task: str, desc: str) -> None:
        shaped = self._shaped(task, desc)
        if shaped is not None:  # the one-shot grammar's decisions, piece by piece
            self._verify_assembled(task, desc, *grounded_steps.subtasks_first(
                self, task, desc, shaped), grounded_repair=True)
            return
        found = mentions(f"{desc} {task}")
        if self.grounded and grounded.applies(found):  # the named objects are constants
            self._assemble(task, desc, gs.design_fragments(self, task, desc, found), found)
        else:
            outline = self._ask_outline(task, desc, f"{task} {desc}")
            self._assemble(task, desc, self._subtask_fragments(task, desc, outline), None,
                           outline.subtasks)

    def _subtask_fragments(self, task: str, desc: str,
                           outline: SubtaskOutline) -> list[TaskGraph]:
        outline_text = "; ".join(f"`{s.name}`: {s.description}" for s in outline.subtasks)
        defined: dict[str, tuple[StateVariable, str]] = {}  # name -> (variable, subtask)
        fragments: list[TaskGraph] = []
        earlier: list[dict[str, Any]] = []
        done: list[SubtaskFactor] = []  # the factors so far, with the outline's `after`
        for sub in outline.subtasks:
            schema = ss.subtask_design(list(defined))
            before = list(done)

            def prompt(lv: PromptLevel, sub: Any = sub, schema: Any = schema) -> str:
                return render(
                    "subtask_design", task_name=task, task_description=desc,
                    mentions=mentions_text(f"{desc} {task}"),
                    outline=outline_text, subtask_name=sub.name,
                    subtask_description=sub.description, earlier=earlier_text(earlier),
                    examples=self.examples(f"{sub.name} {sub.description}",
                                           ("memory", "templates"), lv.examples),
                    schema=self.schema_for_prompt(schema, lv))

            def evaluate(text: str, sub: Any = sub, schema: Any = schema,
                         before: Any = before) -> Evaluation:
                design = self.read(text, schema, SubtaskDesign)
                problems = merge_problems(design, defined)
                if problems:
                    return None, "none", (
                        "The subtask's variables conflict with the earlier subtasks "
                        "(a shared name means the same object):\n" + format_problems(problems))
                local = {v.name: v for v in design.variables}
                known = {n: v for n, (v, _) in defined.items()}
                wanted = [local.get(n) or known[n] for n in design.goal.variable_names()
                          if n in local or n in known]
                wanted += [v for v in design.variables if v not in wanted]
                scope_vars = closure(wanted, {**known, **local})
                factor = make_factor(sub.name, design.description or sub.description,
                                     design.goal, scope=None, after=sub.after)
                return checked_fragment(self, task, factor, scope_vars, before,
                                        {**known, **local})

            piece, ok = ask_design(self, task, sub.name, prompt, schema, evaluate)
            fragments.append(piece)
            done.append(piece.factors[0].model_copy(update={"after": list(sub.after)}))
            for v in piece.variables:
                defined.setdefault(v.name, (v, sub.name))
            earlier.append({"subtask": sub.name, "verified": ok,
                            "variables": [v.model_dump(mode="json", exclude_none=True)
                                          for v in piece.variables],
                            "goal": piece.factors[0].goal.model_dump(mode="json",
                                                                      exclude_none=True)})
        return fragments

    def _assemble(self, task: str, desc: str, fragments: list[TaskGraph],
                  found: list[Any] | None, outlined: Sequence[OutlinedSubtask] = ()) -> None:
        """Merge the subtasks, verify the whole (``found``: grounded, goals use each;
        ``outlined``: the outline, whose ``after`` orders the factors)."""
        graph = None
        problem = None
        try:
            graph = compose(*fragments, name=task, description=desc)
            # The outline is in the order the subtasks are done (see variables-first).
            graph = graph.model_copy(update={"factors": as_planned(graph.factors, outlined)})
            if found is not None:
                problem = gs.assembly_problem(graph, found)
        except CompositionError as exc:
            problem = f"Merging the subtasks failed: {exc}"
        self._verify_assembled(task, desc, graph, problem)

    def _ask_outline(self, task: str, desc: str, query: str) -> SubtaskOutline:
        schema = ss.subtask_outline()

        def prompt(lv: PromptLevel) -> str:
            return render("subtask_outline", task_name=task, task_description=desc,
                          examples=self.examples(query, ("memory", "templates"), lv.examples),
                          schema=self.schema_for_prompt(schema, lv))

        def evaluate(text: str) -> Evaluation:
            outline = self.read(text, schema, SubtaskOutline)
            outline = outline.model_copy(update={"subtasks": relabelled(outline.subtasks)})
            problems = order_problems(outline.subtasks)
            if problems:
                return None, "none", ("The outline has problems:\n"
                                      + format_problems(problems))
            return outline, "syntax", None

        return self.ask_or_abort("subtask_outline", prompt, schema, "subtask_outline", evaluate)


def generate(proposal: str, approach: str, client: LLMClient, verifier: Verifier | None = None,
             memory: SubtaskMemory | None = None, max_repairs: int = 3,
             on_step: StepCallback | None = None) -> GenerationResult:
    """One-call form of :meth:`Generator.generate`."""
    return Generator(client, verifier, memory, max_repairs, on_step).generate(proposal, approach)
