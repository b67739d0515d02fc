"""LLM errors and how a provider's exception maps onto them.

Three families, by what the caller should do:

* :class:`LLMTransientError` — connection, timeout, overload, 5xx, a plain 429:
  retried with bounded backoff; when the retries are spent the generation is
  marked ``llm_error`` (a benchmark retries it on resume).
* :class:`LLMRequestError` — the provider rejected *this* request (bad request,
  content policy, other 4xx): the model's failure, counted in the rates.
* :class:`LLMFatalError` — no call can succeed until the user changes something:
  :class:`LLMAuthError` (missing or wrong key), :class:`LLMModelNotFoundError`,
  :class:`LLMQuotaError` (billing / quota exhausted) and :class:`LLMContextError`
  (the prompt does not fit the model's context). Never retried; the command
  stops with one line: the provider's message and the fix.

The mapping reads exception class names and ``status_code`` only, so litellm
need not be imported to classify.
"""

from __future__ import annotations

import re

from factask.vocabulary.errors import FactaskError


class LLMError(FactaskError):
    """An LLM call failed (network, provider or configuration error)."""


class LLMConfigError(LLMError):
    """The LLM settings do not parse (an unknown setting, a bad number)."""


class LLMTransientError(LLMError):
    """The LLM could not be reached or was overloaded (connection, timeout, rate
    limit, 5xx): an infrastructure problem, worth retrying later."""


class LLMRequestError(LLMError):
    """The provider rejected this request (bad request, content policy, other 4xx):
    retrying the same request would fail again, so it counts as the model's failure."""


class LLMFatalError(LLMError):
    """No call can succeed until the user changes the configuration: the run stops.

    Args:
        message: What the provider said (one line).
        fix: What to change (which variable to set, which model to pick).

    Attributes:
        message: What the provider said.
        fix: What to change.
    """

    what = "the LLM call cannot succeed"

    def __init__(self, message: str, fix: str = "") -> None:
        self.message = one_line(message)
        self.fix = fix
        super().__init__(self.line())

    def line(self) -> str:
        """The one line a command prints: what happened, the provider's words, the fix."""
        text = f"{self.what}: {self.message}"
        return f"{text} -- fix: {self.fix}" if self.fix else text


class LLMAuthError(LLMFatalError):
    """The provider refused the credentials (missing or wrong key, no permission)."""

    what = "the LLM provider refused the credentials"


class LLMModelNotFoundError(LLMFatalError):
    """The provider does not know the model (or litellm does not know the provider)."""

    what = "unknown model"


class LLMQuotaError(LLMFatalError):
    """The account's quota or billing limit is exhausted."""

    what = "the LLM account's quota is exhausted"


class LLMContextError(LLMFatalError):
    """A prompt does not fit the model's context window."""

    what = "the prompt does not fit the model's context"


_TRANSIENT_NAMES = frozenset([
    "APIConnectionError", "APITimeoutError", "Timeout", "RateLimitError",
    "ServiceUnavailableError", "InternalServerError", "ConnectionError", "TimeoutError",
])
_REQUEST_NAMES = frozenset([
    "ContentPolicyViolationError", "BadRequestError", "UnprocessableEntityError",
    "UnsupportedParamsError",
])
_AUTH_NAMES = frozenset(["AuthenticationError", "PermissionDeniedError"])
_QUOTA_RE = re.compile(r"insufficient[_ ]quota|exceeded your current quota|quota exceeded|"
                       r"billing|credit balance|out of credits", re.IGNORECASE)
_NOT_FOUND_RE = re.compile(r"model[^.]{0,80}(not found|does not exist|not exist|unknown)|"
                           r"no such model|LLM Provider NOT provided|unknown model",
                           re.IGNORECASE)
#: A server that validates its parameters and answers 500 (llama-cpp-python does) for
#: one it does not take: the request's fault, not an outage.
_REJECTED_PARAM_RE = re.compile(r"validation error.{0,200}(response_format|literal_error)|"
                                r"Input should be .{0,80}json_object", re.IGNORECASE | re.DOTALL)
_CONTEXT_RE = re.compile(r"context[ _-]?(length|window)|maximum context|too many tokens|"
                         r"exceeds? the (available )?context|n_ctx", re.IGNORECASE)


def one_line(text: str, limit: int = 300) -> str:
    """``text`` on one line (whitespace runs folded), at most ``limit`` characters."""
    flat = " ".join(str(text).split())
    return flat if len(flat) <= limit else flat[: limit - 3] + "..."


def classify_llm_exception(exc: BaseException) -> type[LLMError]:
    """Which :class:`LLMError` subclass a provider (litellm) exception maps onto.

    Args:
        exc: The exception litellm (or the HTTP client) raised.

    Returns:
        The class: read from the exception's class names (most specific first),
        then its message (quota, unknown model, context length), then its HTTP
        ``status_code``; anything unrecognised is transient.
    """
    names = [c.__name__ for c in type(exc).__mro__]
    text = str(exc)
    if "ContextWindowExceededError" in names:
        return LLMContextError
    if "NotFoundError" in names:
        return LLMModelNotFoundError
    for name in names:
        if name in _AUTH_NAMES:
            return LLMAuthError
        if name == "RateLimitError":
            return LLMQuotaError if _QUOTA_RE.search(text) else LLMTransientError
        if name in _REQUEST_NAMES:
            if _CONTEXT_RE.search(text):
                return LLMContextError
            if _NOT_FOUND_RE.search(text):
                return LLMModelNotFoundError
            return LLMRequestError
        if name in _TRANSIENT_NAMES:
            if _CONTEXT_RE.search(text) and "Timeout" not in name:
                return LLMContextError
            return LLMRequestError if _REJECTED_PARAM_RE.search(text) else LLMTransientError
    status = getattr(exc, "status_code", None)
    if isinstance(status, int):
        if status in (401, 403):
            return LLMAuthError
        if status == 402 or (status == 429 and _QUOTA_RE.search(text)):
            return LLMQuotaError
        if status == 404:
            return LLMModelNotFoundError
        if status == 429 or status >= 500:
            return LLMRequestError if _REJECTED_PARAM_RE.search(text) else LLMTransientError
        if 400 <= status < 500:
            return LLMContextError if _CONTEXT_RE.search(text) else LLMRequestError
    return LLMTransientError


#: Provider (litellm's prefix) -> the variables its key is read from.
PROVIDER_KEY_VARIABLES: dict[str, tuple[str, ...]] = {
    "openai": ("OPENAI_API_KEY",),
    "anthropic": ("ANTHROPIC_API_KEY",),
    "gemini": ("GEMINI_API_KEY",),
    "mistral": ("MISTRAL_API_KEY",),
    "groq": ("GROQ_API_KEY",),
    "together_ai": ("TOGETHERAI_API_KEY",),
    "openrouter": ("OPENROUTER_API_KEY",),
    "deepseek": ("DEEPSEEK_API_KEY",),
    "cohere": ("COHERE_API_KEY",),
    "azure": ("AZURE_API_KEY", "AZURE_API_BASE"),
}


def provider_of(model: str) -> str:
    """litellm's provider prefix of a model string (``openai/gpt-4o`` -> ``openai``;
    a bare name is taken as OpenAI's, as litellm does)."""
    return model.split("/", 1)[0].lower() if "/" in model else "openai"


def fix_for(kind: type[LLMError], model: str) -> str:
    """The fix a fatal error's line names, for ``model``.

    Args:
        kind: The error class.
        model: The litellm model string.

    Returns:
        What the user should change.
    """
    provider = provider_of(model)
    local = "or leave out --model to use the packaged local model"
    if issubclass(kind, LLMAuthError):
        names = PROVIDER_KEY_VARIABLES.get(provider, (f"{provider.upper()}_API_KEY",))
        return (f"set {' and '.join(names)} (or FACTASK_API_KEY) to a valid key for "
                f"{provider}, {local}")
    if issubclass(kind, LLMModelNotFoundError):
        return (f"pick a model {provider} serves, as a litellm model string "
                f"'provider/model' (e.g. openai/gpt-4o-mini), {local}")
    if issubclass(kind, LLMQuotaError):
        return f"add credit or raise the limit of the {provider} account, or pick another model"
    if issubclass(kind, LLMContextError):
        return ("pick a model with a longer context (--model), or lower --max-repairs so "
                "repair conversations stay short")
    return ""


def make_error(kind: type[LLMError], model: str, message: str) -> LLMError:
    """An instance of ``kind`` for a call to ``model`` that failed with ``message``."""
    if issubclass(kind, LLMFatalError):
        return kind(f"{model}: {message}", fix_for(kind, model))
    return kind(f"LLM call to {model} failed: {one_line(message, 600)}")


__all__ = [
    "PROVIDER_KEY_VARIABLES",
    "LLMAuthError",
    "LLMConfigError",
    "LLMContextError",
    "LLMError",
    "LLMFatalError",
    "LLMModelNotFoundError",
    "LLMQuotaError",
    "LLMRequestError",
    "LLMTransientError",
    "classify_llm_exception",
    "fix_for",
    "make_error",
    "one_line",
    "provider_of",
]
