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
- :class:`~factask.gen.loopback.LoopbackServer` — a scripted OpenAI-compatible
  server for tests and offline demos.
"""

from factask.gen.llm import LLMClient, LLMConfig, LLMError, ResponseCache, Usage
from factask.gen.loopback import LoopbackServer, ScriptedResponder
from factask.gen.memory import SubtaskMemory
from factask.gen.results import APPROACHES, AttemptRecord, GenerationResult
from factask.gen.strategies import Generator, generate
from factask.gen.verify import LEVELS, Verifier, VerifyOutcome

__all__ = [
    "APPROACHES",
    "LEVELS",
    "AttemptRecord",
    "GenerationResult",
    "Generator",
    "LLMClient",
    "LLMConfig",
    "LLMError",
    "LoopbackServer",
    "ResponseCache",
    "ScriptedResponder",
    "SubtaskMemory",
    "Usage",
    "Verifier",
    "VerifyOutcome",
    "generate",
]
