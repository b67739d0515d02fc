"""LLM access through litellm: configuration, a disk cache, usage and cost.

litellm is imported lazily (only when a call actually goes out) and with
``LITELLM_LOCAL_MODEL_COST_MAP=True`` so that it never tries to download its cost
map; importing this module is cheap.

Configuration comes from arguments first, then environment variables:

=======================  =================================================
``FACTASK_MODEL``        litellm model string (``openai/gpt-4o``,
                         ``anthropic/claude-3-5-sonnet-latest``,
                         ``ollama_chat/llama3.1``)
``FACTASK_API_BASE``     API base URL (a proxy, Ollama, the loopback server)
``FACTASK_API_KEY``      API key (else the provider's own variable, e.g.
                         ``OPENAI_API_KEY``, is read by litellm)
``FACTASK_TEMPERATURE``  sampling temperature (default 0)
``FACTASK_RETRIES``      transport retries per call (default 2)
``FACTASK_TIMEOUT``      seconds per call (default 120)
``FACTASK_MAX_TOKENS``   cap on the answer length (default: the provider's)
``FACTASK_RESPONSE_FORMAT``  ``json_schema`` (default), ``json_object`` or ``off``
``FACTASK_CACHE``        cache directory (default: no cache)
=======================  =================================================
"""

from __future__ import annotations

import hashlib
import json
import os
import threading
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Literal
from urllib.parse import urlsplit, urlunsplit

from factask.model.errors import FactaskError

ResponseFormat = Literal["json_schema", "json_object", "off"]
Message = dict[str, str]

#: Bumped when the cache entry layout changes, so old entries are not misread.
CACHE_VERSION = 2


class LLMError(FactaskError):
    """An LLM call failed after its retries (network, provider or config error)."""


class LLMConfigError(LLMError):
    """The LLM is not configured (no model given and no FACTASK_MODEL)."""


class LLMTransientError(LLMError):
    """The LLM could not be reached or was overloaded (connection, timeout, rate
    limit, 5xx): an infrastructure problem, worth retrying later."""


class LLMRequestError(LLMError):
    """The provider rejected this request (context window exceeded, bad request,
    content policy): retrying the same request would fail again, so it counts
    as the model's failure."""


class LLMAuthError(LLMError):
    """The provider refused the credentials (authentication, permission): no
    call can succeed, the run must stop."""


_TRANSIENT_NAMES = frozenset([
    "APIConnectionError", "APITimeoutError", "Timeout", "RateLimitError",
    "ServiceUnavailableError", "InternalServerError", "ConnectionError", "TimeoutError",
])
_REQUEST_NAMES = frozenset([
    "ContextWindowExceededError", "ContentPolicyViolationError", "BadRequestError",
    "UnprocessableEntityError", "NotFoundError", "UnsupportedParamsError",
])
_AUTH_NAMES = frozenset(["AuthenticationError", "PermissionDeniedError"])


def classify_llm_exception(exc: BaseException) -> type[LLMError]:
    """Which :class:`LLMError` subclass a provider (litellm) exception maps onto.

    Read from the exception's class hierarchy by name (so litellm need not be
    imported), then from its HTTP ``status_code``: authentication/permission
    (401, 403) -> :class:`LLMAuthError`; connection, timeout, rate limit (429),
    service unavailable and other 5xx -> :class:`LLMTransientError`; context
    window, bad request, content policy and other 4xx -> :class:`LLMRequestError`.
    Anything unrecognised is taken as transient (retried on a resume).
    """
    names = [c.__name__ for c in type(exc).__mro__]
    # Most specific first: ContextWindowExceededError is a BadRequestError, Timeout
    # an APIConnectionError.
    for name in names:
        if name in _AUTH_NAMES:
            return LLMAuthError
        if name in _REQUEST_NAMES:
            return LLMRequestError
        if name in _TRANSIENT_NAMES:
            return LLMTransientError
    status = getattr(exc, "status_code", None)
    if isinstance(status, int):
        if status in (401, 403):
            return LLMAuthError
        if status == 429 or status >= 500:
            return LLMTransientError
        if 400 <= status < 500:
            return LLMRequestError
    return LLMTransientError


def normalise_api_base(api_base: str | None) -> str | None:
    """``api_base`` as part of a cache key: scheme and host lower case, no
    user:password, no trailing slash (None stays None)."""
    if not api_base:
        return None
    parts = urlsplit(api_base.strip())
    host = (parts.hostname or "").lower()
    netloc = f"{host}:{parts.port}" if parts.port else host
    path = parts.path.rstrip("/")
    return urlunsplit((parts.scheme.lower(), netloc, path, parts.query, ""))


@dataclass
class LLMConfig:
    """How to reach a model.

    Attributes:
        model: litellm model string (provider prefix included).
        api_base: API base URL, or None for the provider's default.
        api_key: API key, or None to let litellm read the provider's variable.
        temperature: Sampling temperature.
        num_retries: Transport retries per call (litellm's ``num_retries``).
        timeout: Seconds per call.
        max_tokens: Cap on the answer length, or None.
        response_format: How structured output is requested.
    """

    model: str
    api_base: str | None = None
    api_key: str | None = None
    temperature: float = 0.0
    num_retries: int = 2
    timeout: float = 120.0
    max_tokens: int | None = None
    response_format: ResponseFormat = "json_schema"

    @classmethod
    def from_env(
        cls, env: Mapping[str, str] | None = None, **overrides: Any
    ) -> LLMConfig:
        """Build a config from arguments (non-None ``overrides``) and ``FACTASK_*`` variables.

        Args:
            env: Environment to read (default ``os.environ``).
            **overrides: Field values that win over the environment (None = unset).

        Returns:
            The configuration.

        Raises:
            LLMConfigError: no model given and ``FACTASK_MODEL`` unset, or a
                variable does not parse.
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
            "num_retries": ("FACTASK_RETRIES", int),
            "timeout": ("FACTASK_TIMEOUT", float),
            "max_tokens": ("FACTASK_MAX_TOKENS", int),
            "response_format": ("FACTASK_RESPONSE_FORMAT", str),
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
        if not values.get("model"):
            raise LLMConfigError("no model: pass --model (e.g. openai/gpt-4o) or set "
                                 "FACTASK_MODEL")
        if values.get("response_format", "json_schema") not in ("json_schema", "json_object",
                                                                "off"):
            raise LLMConfigError("response_format must be json_schema, json_object or off")
        return cls(**values)

    def cache_params(self) -> dict[str, Any]:
        """The parameters that change an answer (the cache key's part; no secrets:
        the API key is never part of it, the API base only normalised)."""
        return {"temperature": self.temperature, "max_tokens": self.max_tokens,
                "response_format": self.response_format,
                "api_base": normalise_api_base(self.api_base)}


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
    """

    text: str
    usage: Usage
    cached: bool
    key: str


class ResponseCache:
    """Answers on disk, keyed on (model, messages, parameters): a rerun is free
    and reproducible.

    One JSON file per request (``<dir>/<key[:2]>/<key>.json``), written atomically
    (temporary file + rename) so an interrupted run never leaves a torn entry.

    Args:
        directory: Where entries live (created on first write).
    """

    def __init__(self, directory: str | os.PathLike[str]) -> None:
        self.directory = Path(directory)

    @staticmethod
    def key(model: str, messages: Sequence[Mapping[str, Any]], params: Mapping[str, Any],
            schema: Mapping[str, Any] | None) -> str:
        """SHA-256 of the canonical JSON of everything that shapes the answer."""
        blob = json.dumps({"v": CACHE_VERSION, "model": model, "messages": list(messages),
                           "params": dict(params), "schema": schema},
                          sort_keys=True, ensure_ascii=True, default=str)
        return hashlib.sha256(blob.encode()).hexdigest()

    def _path(self, key: str) -> Path:
        return self.directory / key[:2] / f"{key}.json"

    def get(self, key: str) -> dict[str, Any] | None:
        """The stored entry, or None (a corrupt entry counts as missing)."""
        path = self._path(key)
        try:
            data = json.loads(path.read_text())
        except (OSError, json.JSONDecodeError):
            return None
        if not isinstance(data, dict) or not isinstance(data.get("text"), str):
            return None
        return data

    def put(self, key: str, entry: Mapping[str, Any]) -> None:
        """Store ``entry`` under ``key`` (atomic replace)."""
        path = self._path(key)
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.{threading.get_ident()}.tmp")
        tmp.write_text(json.dumps(dict(entry), indent=1))
        os.replace(tmp, path)

    def __len__(self) -> int:
        return sum(1 for _ in self.directory.glob("*/*.json")) if self.directory.exists() else 0


def _import_litellm() -> Any:
    # Use the bundled cost map: offline, litellm would otherwise try to download it.
    os.environ.setdefault("LITELLM_LOCAL_MODEL_COST_MAP", "True")
    import litellm

    litellm.suppress_debug_info = True
    return litellm


def response_format_param(mode: ResponseFormat, schema: Mapping[str, Any] | None,
                          name: str) -> dict[str, Any] | None:
    """The ``response_format`` argument for litellm.

    Args:
        mode: ``json_schema``: the step's JSON Schema (non-strict, since the graph
            schema uses unions and defaults that strict mode rejects);
            ``json_object``: any JSON object; ``off``: nothing requested.
        schema: The step's JSON Schema.
        name: Schema name (letters, digits, ``_`` and ``-``).

    Returns:
        The parameter, or None.
    """
    if mode == "off":
        return None
    if mode == "json_schema" and schema is not None:
        return {"type": "json_schema",
                "json_schema": {"name": name, "schema": dict(schema), "strict": False}}
    return {"type": "json_object"}


class LLMClient:
    """Chat completions through litellm, with a disk cache and usage bookkeeping.

    Args:
        config: How to reach the model.
        cache: Disk cache, or None for none.

    Attributes:
        usage: Usage summed over every call made by this client.
        log: One dict per call (key, cached, tokens, cost).
    """

    def __init__(self, config: LLMConfig, cache: ResponseCache | None = None) -> None:
        self.config = config
        self.cache = cache
        self.usage = Usage()
        self.log: list[dict[str, Any]] = []
        self._lock = threading.Lock()

    def complete(
        self,
        messages: Sequence[Mapping[str, Any]],
        schema: Mapping[str, Any] | None = None,
        schema_name: str = "answer",
    ) -> LLMReply:
        """Ask the model; answer from the cache when the same request was made before.

        Args:
            messages: Chat messages (``role``, ``content``).
            schema: JSON Schema the answer must follow (requested as structured
                output where the provider supports it; also part of the cache key).
            schema_name: Name of that schema.

        Returns:
            The reply with this call's usage.

        Raises:
            LLMTransientError: the model could not be reached (after
                ``num_retries`` retries).
            LLMRequestError: the provider rejected the request.
            LLMAuthError: the credentials were refused.
        """
        cfg = self.config
        msgs = [{"role": str(m["role"]), "content": str(m["content"])} for m in messages]
        key = ResponseCache.key(cfg.model, msgs, cfg.cache_params(), schema)
        if self.cache is not None:
            hit = self.cache.get(key)
            if hit is not None:
                usage = Usage(calls=1, cached_calls=1)
                self._record(key, usage, cached=True)
                return LLMReply(text=hit["text"], usage=usage, cached=True, key=key)

        litellm = _import_litellm()
        kwargs: dict[str, Any] = {
            "model": cfg.model,
            "messages": msgs,
            "temperature": cfg.temperature,
            "num_retries": cfg.num_retries,
            "timeout": cfg.timeout,
            # Providers that lack a parameter (e.g. response_format) get it dropped
            # instead of failing: the prompt carries the schema as well.
            "drop_params": True,
        }
        if cfg.api_base:
            kwargs["api_base"] = cfg.api_base
        if cfg.api_key:
            kwargs["api_key"] = cfg.api_key
        elif cfg.api_base and cfg.model.startswith("openai/") and not os.environ.get(
                "OPENAI_API_KEY"):
            # OpenAI-compatible local servers (Ollama, vLLM, the loopback) need no
            # key, but the OpenAI client refuses to start without one.
            kwargs["api_key"] = "not-needed"
        if cfg.max_tokens:
            kwargs["max_tokens"] = cfg.max_tokens
        fmt = response_format_param(cfg.response_format, schema, schema_name)
        if fmt is not None:
            kwargs["response_format"] = fmt
        try:
            response = litellm.completion(**kwargs)
        except Exception as exc:  # litellm maps every provider error onto its own types
            kind = classify_llm_exception(exc)
            raise kind(f"LLM call to {cfg.model} failed: {type(exc).__name__}: {exc}")\
                from None
        try:
            text = response.choices[0].message.content or ""
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
            usage.cost_usd = float(litellm.completion_cost(completion_response=response) or 0.0)
        except Exception:  # unpriced (custom or local) models: cost unknown, not an error
            usage.cost_unknown_calls = 1
        if self.cache is not None:
            self.cache.put(key, {"model": cfg.model, "messages": msgs,
                                 "params": cfg.cache_params(), "text": text,
                                 "usage": usage.to_dict()})
        self._record(key, usage, cached=False)
        return LLMReply(text=text, usage=usage, cached=False, key=key)

    def _record(self, key: str, usage: Usage, cached: bool) -> None:
        with self._lock:
            self.usage.add(usage)
            self.log.append({"key": key, "cached": cached, **usage.to_dict()})
