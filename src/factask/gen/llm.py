"""LLM access through litellm: configuration, a disk cache, usage and cost.

litellm is imported lazily (only when a call actually goes out) and with
``LITELLM_LOCAL_MODEL_COST_MAP=True`` so that it never tries to download its cost
map; importing this module is cheap.

Configuration comes from arguments first, then environment variables:

===========================  ================================================
``FACTASK_MODEL``            litellm model string (``openai/gpt-4o``,
                             ``anthropic/claude-3-5-sonnet-latest``,
                             ``ollama_chat/llama3.1``); default: the packaged
                             local model ``local/smollm2-135m``
``FACTASK_API_BASE``         API base URL (a proxy, Ollama, the loopback server)
``FACTASK_API_KEY``          API key (else the provider's own variable, e.g.
                             ``OPENAI_API_KEY``, is read by litellm)
``FACTASK_TEMPERATURE``      sampling temperature (default 0)
``FACTASK_SEED``             sampling seed (default 0; retries vary it)
``FACTASK_RETRIES``          retries of a transient failure (default 2)
``FACTASK_TIMEOUT``          seconds per call (default 120)
``FACTASK_MAX_TOKENS``       cap on every answer (default: sized per step)
``FACTASK_RESPONSE_FORMAT``  ``auto`` (default), ``json_schema``, ``llama_cpp``,
                             ``json_object`` or ``prompt`` (see
                             :mod:`factask.gen.providers`)
``FACTASK_CONTEXT``          the model's context in tokens (default: litellm's
                             model info, or the local server's ``n_ctx``)
``FACTASK_CACHE``            cache directory (default: no cache)
===========================  ================================================

Errors are typed (:mod:`factask.gen.llm_errors`): transient ones are retried
here with bounded exponential backoff; fatal ones (key, unknown model, quota,
context) are raised at once, never retried.
"""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass
from typing import Any

from factask.gen.cache import ResponseCache, normalise_api_base
from factask.gen.llm_errors import (
    LLMAuthError,
    LLMConfigError,
    LLMContextError,
    LLMError,
    LLMFatalError,
    LLMModelNotFoundError,
    LLMQuotaError,
    LLMRequestError,
    LLMTransientError,
    classify_llm_exception,
    make_error,
)
from factask.gen.providers import (
    FORM_CHOICES,
    StructuredForm,
    import_litellm,
    llama_grammar,
    response_format_param,
    structured_form,
)

Message = dict[str, str]

@dataclass
class LLMConfig:
    """How to reach a model.

    Attributes:
        model: litellm model string (provider prefix included), or
            ``local/<name>`` for a packaged local model (:mod:`factask.gen.local`).
        api_base: API base URL, or None for the provider's default.
        api_key: API key, or None to let litellm read the provider's variable.
        temperature: Sampling temperature of a step's first attempt.
        seed: Sampling seed of a step's first attempt (retries vary it).
        num_retries: Retries of a transient failure (bounded backoff).
        timeout: Seconds per call.
        max_tokens: Cap on every answer (None: sized per step).
        response_format: How structured output is requested (``auto`` decides
            per provider, see :func:`factask.gen.providers.structured_form`).
        context: The model's context in tokens (None: litellm's model info, or
            the local server's).
    """

    model: str = "local/smollm2-135m"
    api_base: str | None = None
    api_key: str | None = None
    temperature: float = 0.0
    seed: int = 0
    num_retries: int = 2
    timeout: float = 120.0
    max_tokens: int | None = None
    response_format: str = "auto"
    context: int | None = None

    def __post_init__(self) -> None:
        if self.response_format not in FORM_CHOICES:
            raise LLMConfigError(f"response_format must be one of {', '.join(FORM_CHOICES)}, "
                                 f"not {self.response_format!r}")
        if self.num_retries < 0 or self.timeout <= 0:
            raise LLMConfigError("num_retries must be >= 0 and timeout > 0")

    @property
    def is_local(self) -> bool:
        """True for a packaged local model (``local/...``)."""
        return self.model.startswith("local/")

    @classmethod
    def from_env(
        cls, env: Mapping[str, str] | None = None, **overrides: Any
    ) -> LLMConfig:
        """Build a config from arguments (non-None ``overrides``) and ``FACTASK_*`` variables.

        Args:
            env: Environment to read (default ``os.environ``).
            **overrides: Field values that win over the environment (None = unset).

        Returns:
            The configuration (with no model anywhere: the local default).

        Raises:
            LLMConfigError: an unknown setting, or a variable does not parse.
        """
        env = os.environ if env is None else env
        given = {k: v for k, v in overrides.items() if v is not None}
        unknown = set(given) - set(cls.__dataclass_fields__)
        if unknown:
            raise LLMConfigError(f"unknown LLM settings: {sorted(unknown)}")
        readers: dict[str, tuple[str, type]] = {
            "model": ("FACTASK_MODEL", str),
            "api_base": ("FACTASK_API_BASE", str),
            "api_key": ("FACTASK_API_KEY", str),
            "temperature": ("FACTASK_TEMPERATURE", float),
            "seed": ("FACTASK_SEED", int),
            "num_retries": ("FACTASK_RETRIES", int),
            "timeout": ("FACTASK_TIMEOUT", float),
            "max_tokens": ("FACTASK_MAX_TOKENS", int),
            "response_format": ("FACTASK_RESPONSE_FORMAT", str),
            "context": ("FACTASK_CONTEXT", int),
        }
        values: dict[str, Any] = {}
        for name, (var, typ) in readers.items():
            if name in given:
                values[name] = given[name]
            elif env.get(var):
                try:
                    values[name] = typ(env[var])
                except ValueError:
                    raise LLMConfigError(f"{var}={env[var]!r} is not a valid {typ.__name__}")\
                        from None
        return cls(**values)

    def cache_params(self) -> dict[str, Any]:
        """The parameters that change an answer (the cache key's part; no secrets:
        the API key is never part of it, the API base only normalised, and a local
        model's random port not at all)."""
        return {"temperature": self.temperature, "seed": self.seed,
                "max_tokens": self.max_tokens, "response_format": self.response_format,
                "api_base": None if self.is_local else normalise_api_base(self.api_base)}


@dataclass
class Usage:
    """Token usage and cost, summed over calls.

    Attributes:
        calls: Calls answered (cached ones included).
        cached_calls: Calls answered from the disk cache (free).
        prompt_tokens: Prompt tokens of the calls that went out.
        completion_tokens: Completion tokens of the calls that went out.
        cost_usd: Cost in US dollars as litellm prices it (0 where unknown).
        cost_unknown_calls: Calls litellm could not price (custom/local models).
    """

    calls: int = 0
    cached_calls: int = 0
    prompt_tokens: int = 0
    completion_tokens: int = 0
    cost_usd: float = 0.0
    cost_unknown_calls: int = 0

    @property
    def total_tokens(self) -> int:
        return self.prompt_tokens + self.completion_tokens

    def add(self, other: Usage) -> None:
        """Add ``other`` into this record."""
        for k in ("calls", "cached_calls", "prompt_tokens", "completion_tokens",
                  "cost_unknown_calls"):
            setattr(self, k, getattr(self, k) + getattr(other, k))
        self.cost_usd += other.cost_usd

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["total_tokens"] = self.total_tokens
        return d

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> Usage:
        return cls(**{k: data[k] for k in cls.__dataclass_fields__ if k in data})


@dataclass
class LLMReply:
    """One answer.

    Attributes:
        text: The assistant message's text.
        usage: This call's usage (tokens 0 and ``cached_calls`` 1 if from the cache).
        cached: Answered from the disk cache.
        key: The cache key of the request.
        finish_reason: Why generation stopped (``length``: cut at ``max_tokens``).
    """

    text: str
    usage: Usage
    cached: bool
    key: str
    finish_reason: str = ""


_import_litellm = import_litellm  # the seam tests replace

#: Backoff between retries of a transient failure: base * 2**i seconds, capped.
BACKOFF_BASE_S = 1.0
BACKOFF_CAP_S = 8.0


def backoff_delays(retries: int, base: float = BACKOFF_BASE_S,
                   cap: float = BACKOFF_CAP_S) -> list[float]:
    """The waits before each retry: ``base * 2**i``, at most ``cap`` seconds."""
    return [min(cap, base * 2 ** i) for i in range(max(0, retries))]


TokenCounter = Callable[[Sequence[Mapping[str, Any]]], int]


def fold_system_messages(messages: Sequence[Mapping[str, str]]) -> list[dict[str, str]]:
    """The same conversation for a chat format without a system turn: system
    messages are joined, in order, at the head of the first user message (a
    conversation with no user message gets one holding them).

    Args:
        messages: Chat messages (``role``, ``content``).

    Returns:
        New messages with no ``system`` role; every other message unchanged, in order.
    """
    system = [str(m["content"]) for m in messages if m["role"] == "system"]
    rest = [{"role": str(m["role"]), "content": str(m["content"])}
            for m in messages if m["role"] != "system"]
    if not system:
        return rest
    head = "\n\n".join(system)
    for msg in rest:
        if msg["role"] == "user":
            msg["content"] = f"{head}\n\n{msg['content']}"
            return rest
    return [{"role": "user", "content": head}, *rest]


class LLMClient:
    """Chat completions through litellm, with a disk cache and usage bookkeeping.

    Args:
        config: How to reach the model.
        cache: Disk cache, or None for none.
        wire_model: The model string litellm is called with (default
            ``config.model``; the local model is ``openai/<alias>``).
        context: The model's context in tokens (default ``config.context``, else
            litellm's model info where known).
        counter: Counts a request's prompt tokens (default: litellm's
            ``token_counter``).
        on_abandon: Called after a call timed out (the local server restarts, so
            the request the client gave up on stops generating).
        before_call: Called before every call that goes out (the local server is
            started again if it died, :meth:`factask.gen.local.LocalLlamaServer.revive`).
        seconds_per_token: Slowest expected generation speed (the local model on
            CPU): a request's timeout is at least ``30 + max_tokens * this`` plus
            the prompt's tokens at a tenth of it.
        prompt_budget: Most prompt tokens worth sending (None: the context is the
            only limit). On a CPU the prompt's processing dominates: the local model
            gets the compact prompt variants.
        system_role: The model's chat format has a system turn; False folds
            system messages into the first user turn (:func:`fold_system_messages`).

    Attributes:
        usage: Usage summed over every call made by this client.
        log: One dict per call (key, cached, tokens, cost).
        form: How structured output is requested (:mod:`factask.gen.providers`).
        succeeded: Calls that got an answer (cached ones included).
    """

    def __init__(self, config: LLMConfig, cache: ResponseCache | None = None, *,
                 wire_model: str | None = None, context: int | None = None,
                 counter: TokenCounter | None = None,
                 on_abandon: Callable[[], None] | None = None,
                 before_call: Callable[[], object] | None = None,
                 seconds_per_token: float = 0.0,
                 prompt_budget: int | None = None,
                 system_role: bool = True) -> None:
        self.config = config
        self.cache = cache
        self.wire_model = wire_model or config.model
        self.usage = Usage()
        self.log: list[dict[str, Any]] = []
        self.succeeded = 0
        self.form: StructuredForm = structured_form(self.wire_model, config.api_base,
                                                    config.is_local, config.response_format)
        self._context = context or config.context
        self._context_known = self._context is not None
        self._counter = counter
        self.on_abandon = on_abandon
        self.before_call = before_call
        self.seconds_per_token = seconds_per_token
        self.prompt_budget = prompt_budget
        self.system_role = system_role
        self._lock = threading.Lock()
        self.sleep: Callable[[float], None] = time.sleep

    # ------------------------------------------------------------ budgets
    @property
    def context(self) -> int | None:
        """The model's context in tokens, or None where unknown (no check then)."""
        if not self._context_known:
            from factask.gen.providers import context_window

            self._context = context_window(self.wire_model)
            self._context_known = True
        return self._context

    def count_tokens(self, messages: Sequence[Mapping[str, Any]]) -> int:
        """Prompt tokens of ``messages`` (the server's tokenizer for the local model,
        litellm's ``token_counter`` otherwise)."""
        if not self.system_role:
            messages = fold_system_messages(messages)
        if self._counter is not None:
            return int(self._counter(messages))
        litellm = import_litellm()
        msgs = [{"role": str(m["role"]), "content": str(m["content"])} for m in messages]
        return int(litellm.token_counter(model=self.wire_model, messages=msgs))

    # --------------------------------------------------------------- calls
    def complete(
        self,
        messages: Sequence[Mapping[str, Any]],
        schema: Mapping[str, Any] | None = None,
        schema_name: str = "answer",
        max_tokens: int | None = None,
        temperature: float | None = None,
        seed: int | None = None,
    ) -> LLMReply:
        """Ask the model; answer from the cache when the same request was made before.

        Args:
            messages: Chat messages (``role``, ``content``).
            schema: JSON Schema the answer must follow (requested in the provider's
                form, :attr:`form`; also part of the cache key).
            schema_name: Name of that schema.
            max_tokens: Cap on this answer (``config.max_tokens`` wins if smaller).
            temperature: Sampling temperature (default ``config.temperature``).
            seed: Sampling seed (default ``config.seed``).

        Returns:
            The reply with this call's usage.

        Raises:
            LLMTransientError: the model could not be reached (after
                ``num_retries`` retries with backoff).
            LLMRequestError: the provider rejected the request.
            LLMFatalError: key, model, quota or context error (never retried).
        """
        cfg = self.config
        msgs = [{"role": str(m["role"]), "content": str(m["content"])} for m in messages]
        if not self.system_role:
            msgs = fold_system_messages(msgs)
        caps = [c for c in (max_tokens, cfg.max_tokens) if c]
        limit = min(caps) if caps else None
        temp = cfg.temperature if temperature is None else float(temperature)
        seed_ = cfg.seed if seed is None else int(seed)
        params = {**cfg.cache_params(), "temperature": temp, "seed": seed_,
                  "max_tokens": limit, "response_format": self.form}
        if self.form == "llama_cpp":  # answers under the looser grammar are not reused
            params["grammar"] = "json-strings"
        key = ResponseCache.key(cfg.model, msgs, params, schema)
        if self.cache is not None:
            hit = self.cache.get(key)
            if hit is not None:
                usage = Usage(calls=1, cached_calls=1)
                self._record(key, usage, cached=True)
                return LLMReply(text=hit["text"], usage=usage, cached=True, key=key,
                                finish_reason=str(hit.get("finish_reason") or ""))
        kwargs: dict[str, Any] = {
            "model": self.wire_model, "messages": msgs, "temperature": temp, "seed": seed_,
            "timeout": cfg.timeout,
            # Retries are ours (only transient errors, with backoff): litellm's and
            # the OpenAI client's own are off.
            "num_retries": 0, "max_retries": 0,
            # A parameter a provider lacks is dropped rather than failing the call.
            "drop_params": True,
        }
        if cfg.api_base:
            kwargs["api_base"] = cfg.api_base
        if cfg.api_key:
            kwargs["api_key"] = cfg.api_key
        elif cfg.api_base and self.wire_model.startswith("openai/") and not os.environ.get(
                "OPENAI_API_KEY"):
            # OpenAI-compatible local servers (llama.cpp, Ollama, vLLM, the loopback)
            # need no key, but the OpenAI client refuses to start without one.
            kwargs["api_key"] = "not-needed"
        if limit:
            kwargs["max_tokens"] = limit
            prompt_s = 0.0
            if self.seconds_per_token and self._counter is not None:
                prompt_s = 0.1 * self.seconds_per_token * self.count_tokens(msgs)
            kwargs["timeout"] = max(cfg.timeout,
                                    30 + limit * self.seconds_per_token + prompt_s)
        if self.form == "llama_cpp" and temp > 0:
            # llama.cpp truncates (top_k 40, top_p 0.95, min_p 0.05) *before* the
            # temperature: under a grammar a small model's distribution is so peaked
            # that a warmer retry answered the same text. A warm retry samples from
            # every grammar-valid token instead.
            kwargs["top_p"] = 1.0
            kwargs["extra_body"] = {"min_p": 0.0, "top_k": 0}
        grammar = llama_grammar(schema) if self.form == "llama_cpp" and schema else None
        fmt = None if grammar else response_format_param(self.form, schema, schema_name)
        if grammar:  # our grammar: strings without control characters (providers)
            kwargs["extra_body"] = {**kwargs.get("extra_body", {}), "grammar": grammar}
        if fmt is not None:
            kwargs["response_format"] = fmt
        response = self._call(kwargs)
        try:
            choice = response.choices[0]
            text = choice.message.content or ""
            finish = str(getattr(choice, "finish_reason", "") or "")
        except (AttributeError, IndexError) as exc:
            raise LLMTransientError(f"LLM reply from {cfg.model} has no message: {exc}")\
                from None
        raw_usage = getattr(response, "usage", None)
        usage = Usage(
            calls=1,
            prompt_tokens=int(getattr(raw_usage, "prompt_tokens", 0) or 0),
            completion_tokens=int(getattr(raw_usage, "completion_tokens", 0) or 0),
        )
        try:
            litellm = import_litellm()
            usage.cost_usd = float(litellm.completion_cost(completion_response=response) or 0.0)
        except Exception:  # unpriced (custom or local) models: cost unknown, not an error
            usage.cost_unknown_calls = 1
        if self.cache is not None:
            self.cache.put(key, {"model": cfg.model, "messages": msgs, "params": params,
                                 "text": text, "finish_reason": finish,
                                 "usage": usage.to_dict()})
        self._record(key, usage, cached=False)
        return LLMReply(text=text, usage=usage, cached=False, key=key, finish_reason=finish)

    def _call(self, kwargs: dict[str, Any]) -> Any:
        """One completion, transient failures retried with backoff, the rest raised typed."""
        litellm = _import_litellm()
        delays = [*backoff_delays(self.config.num_retries), None]
        error: LLMError | None = None
        for delay in delays:
            if self.before_call is not None:
                self.before_call()
            try:
                return litellm.completion(**kwargs)
            except Exception as exc:  # litellm maps every provider error onto its own types
                kind = classify_llm_exception(exc)
                error = make_error(kind, self.config.model, f"{type(exc).__name__}: {exc}")
                if kind is not LLMTransientError:
                    raise error from None
                if "timeout" in type(exc).__name__.lower() and self.on_abandon is not None:
                    self.on_abandon()
                if delay is not None:
                    self.sleep(delay)
        assert error is not None
        raise error

    def _record(self, key: str, usage: Usage, cached: bool) -> None:
        with self._lock:
            self.usage.add(usage)
            self.succeeded += 1
            self.log.append({"key": key, "cached": cached, **usage.to_dict()})


__all__ = [
    "LLMAuthError", "LLMClient", "LLMConfig", "LLMConfigError", "LLMContextError", "LLMError",
    "LLMFatalError", "LLMModelNotFoundError", "LLMQuotaError", "LLMReply", "LLMRequestError",
    "LLMTransientError", "ResponseCache", "Usage", "backoff_delays", "classify_llm_exception",
    "import_litellm", "normalise_api_base",
]
