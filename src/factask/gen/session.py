"""Opening an LLM client for a run: the local server when no model is configured,
a preflight check of the provider's key otherwise.

:func:`open_client` is a context manager: it yields an :class:`LLMClient` and,
for a ``local/...`` model, owns the llama.cpp server (started before, stopped
after, killed on error too).
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from dataclasses import replace
from types import FrameType
from typing import TYPE_CHECKING

from factask.gen.first_choice import READER_MODEL, FirstChoiceResponder
from factask.gen.llm import LLMClient, LLMConfig, ResponseCache, import_litellm
from factask.gen.llm_errors import LLMAuthError, fix_for, provider_of
from factask.gen.local import LocalLlamaServer, check_local_model
from factask.gen.loopback import LoopbackServer
from factask.gen.reference_model import ReferenceResponder, is_reference_model, noise_of

if TYPE_CHECKING:
    from factask.graph.taskgraph import TaskGraph

#: The slowest generation speed planned for on a busy 2-core CPU: measured 0.2-3 s
#: per token with a grammar at load average 5-7; a request's timeout leaves room
#: for its whole answer at this speed.
LOCAL_SECONDS_PER_TOKEN = 1.5
#: Prompt tokens worth sending to the local model: its prompt processing on a CPU
#: dominates a call, and a 135M model gains little from a long prompt.
LOCAL_PROMPT_BUDGET = 3000


def missing_keys(config: LLMConfig) -> list[str]:
    """Environment variables the provider needs and the environment lacks.

    Nothing is missing for the local model, with an explicit API key, or with an
    ``api_base`` (a proxy or a local OpenAI-compatible server may need no key).

    Args:
        config: The configuration.

    Returns:
        The names of the missing variables (litellm's ``validate_environment``).
    """
    if config.is_local or config.api_key or config.api_base:
        return []
    litellm = import_litellm()
    try:
        report = litellm.validate_environment(model=config.model)
    except Exception:  # a provider litellm cannot check: let the call tell
        return []
    if report.get("keys_in_environment", True):
        return []
    return [str(k) for k in report.get("missing_keys", [])]


def preflight(config: LLMConfig) -> None:
    """Fail now, before any call, when the run cannot work.

    Raises:
        LLMAuthError: the provider's key variable is not set.
        LocalModelError: the local model is not installed.
        LLMConfigError: llama-cpp-python is not installed.
    """
    if config.is_local:
        check_local_model(config.model)
        return
    missing = missing_keys(config)
    if missing:
        raise LLMAuthError(f"{config.model}: no API key ({', '.join(missing)} not set)",
                           fix_for(LLMAuthError, config.model))


@contextmanager
def open_client(config: LLMConfig, cache: ResponseCache | None = None,
                startup_timeout: float = 90.0,
                references: Mapping[str, TaskGraph] | None = None) -> Iterator[LLMClient]:
    """An LLM client for ``config``; for a local model, with its server running.

    Args:
        config: How to reach the model (``local/...``: the packaged local model;
            ``local/reader``: no model, the first choice of each step's schema,
            :mod:`factask.gen.first_choice`; ``local/reference`` and
            ``local/noisy-reference[:RATE]``: each step answered from the task's
            reference graph, on the path remote models take,
            :mod:`factask.gen.reference_model`).
        cache: Disk cache, or None.
        startup_timeout: Seconds the local server may take to answer.
        references: The reference graphs by task name (reference models only).

    Yields:
        The client.

    Raises:
        LLMAuthError: a remote provider's key is missing (before any call).
        LocalModelError: the local model is missing or its server did not start.
    """
    if config.model == READER_MODEL:  # no model: the reading's first choices
        with LoopbackServer(FirstChoiceResponder()) as reader:
            # the schema itself goes out (json_schema), not a grammar made from it
            yield LLMClient(replace(config, api_base=reader.url, response_format="json_schema"),
                            cache,
                            wire_model="openai/reader")  # no context: prompts of any size
        return
    if is_reference_model(config.model):  # a capable model's answers, from references
        responder = ReferenceResponder(references or {}, noise_of(config.model),
                                       config.seed or 0)
        with LoopbackServer(responder) as reference:
            # a remote model's path: not local (so not grounded), the schema sent
            yield LLMClient(replace(config, model="openai/reference", api_base=reference.url,
                                    response_format="json_schema"), cache)
        return
    preflight(config)
    if not config.is_local:
        yield LLMClient(config, cache)
        return
    server = LocalLlamaServer(config.model, n_ctx=config.context,
                              startup_timeout=startup_timeout)
    previous = _exit_on_sigterm()
    try:
        server.start()
        local = replace(config, api_base=server.url, context=server.n_ctx)
        yield LLMClient(local, cache, wire_model=f"openai/{server.alias}",
                        context=server.n_ctx, counter=server.count_messages,
                        on_abandon=server.restart, before_call=server.revive,
                        seconds_per_token=LOCAL_SECONDS_PER_TOKEN,
                        prompt_budget=LOCAL_PROMPT_BUDGET,
                        system_role=server.spec.system_role)
    finally:
        server.stop()
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


def _terminate(signum: int, frame: FrameType | None) -> None:
    raise SystemExit(128 + signum)


def _exit_on_sigterm() -> object | None:
    """Make SIGTERM unwind the stack (so the local server is stopped, not orphaned);
    returns the previous handler, or None off the main thread (nothing changed)."""
    if threading.current_thread() is not threading.main_thread():
        return None
    return signal.signal(signal.SIGTERM, _terminate)


__all__ = ["missing_keys", "open_client", "preflight", "provider_of"]
