"""LLM generation of task graphs by factorization.

litellm is imported only when a call goes out; importing this package is cheap.

Main entry points:
- :class:`~factask.gen.llm.LLMConfig`, :class:`~factask.gen.llm.LLMClient`,
  :class:`~factask.gen.llm.ResponseCache` — model access, disk cache, usage;
- :class:`~factask.gen.strategies.Generator` — the three strategies
  (:data:`~factask.gen.results.APPROACHES`) returning a
  :class:`~factask.gen.results.GenerationResult`;
- :class:`~factask.gen.verify.Verifier` — the syntax / runtime / completion ladder;
- :class:`~factask.gen.memory.SubtaskMemory` — verified subtasks on disk;
- :func:`~factask.gen.session.open_client` — a client for a run; with no model
  configured it starts the packaged local model
  (:class:`~factask.gen.local.LocalLlamaServer`) and stops it at the end;
- :class:`~factask.gen.loopback.LoopbackServer` — a scripted OpenAI-compatible
  server for tests and offline demos.
"""

from factask.gen.llm import LLMClient, LLMConfig, LLMError, LLMFatalError, ResponseCache, Usage
from factask.gen.local import DEFAULT_LOCAL_MODEL, LocalLlamaServer
from factask.gen.loopback import LoopbackServer, ScriptedResponder
from factask.gen.memory import SubtaskMemory
from factask.gen.results import APPROACHES, DEFAULT_APPROACH, AttemptRecord, GenerationResult
from factask.gen.session import open_client
from factask.gen.strategies import Generator, generate
from factask.gen.verify import LEVELS, Verifier, VerifyOutcome

__all__ = [
    "APPROACHES",
    "DEFAULT_APPROACH",
    "DEFAULT_LOCAL_MODEL",
    "LEVELS",
    "AttemptRecord",
    "GenerationResult",
    "Generator",
    "LLMClient",
    "LLMConfig",
    "LLMError",
    "LLMFatalError",
    "LocalLlamaServer",
    "LoopbackServer",
    "ResponseCache",
    "ScriptedResponder",
    "SubtaskMemory",
    "Usage",
    "Verifier",
    "VerifyOutcome",
    "generate",
    "open_client",
]
