"""factask: robot manipulation tasks as explicit factor graphs, compiled to MuJoCo.

The graph model is imported eagerly (it is pure Python). Everything that pulls in
heavy dependencies — the MuJoCo backend, the task library, drawing, LLM
generation, the CLIPort layer — is re-exported *lazily*: ``factask.FactaskEnv``
imports :mod:`factask.sim.env` on first use, so ``import factask`` stays fast.
"""

from __future__ import annotations

import importlib
from typing import Any

from factask.model import *  # noqa: F403
from factask.model import __all__ as _model_all

__version__ = "0.1.0"

#: Lazily re-exported names: public name -> (module, attribute).
_LAZY: dict[str, tuple[str, str]] = {
    # task library
    "get_task": ("factask.library", "get_task"),
    "task_names": ("factask.library", "task_names"),
    "list_tasks": ("factask.library", "list_tasks"),
    "TEMPLATES": ("factask.library.templates", "TEMPLATES"),
    "get_template": ("factask.library.templates", "get_template"),
    # pictures
    "draw_graph": ("factask.viz", "draw_graph"),
    # MuJoCo backend
    "compile_graph": ("factask.sim.compile", "compile_graph"),
    "CompileError": ("factask.sim.compile", "CompileError"),
    "LayoutError": ("factask.scene.collision", "LayoutError"),
    "FactaskEnv": ("factask.sim.env", "FactaskEnv"),
    "Oracle": ("factask.sim.oracle", "Oracle"),
    "run_episode": ("factask.sim.episode", "run_episode"),
    "evaluate_task": ("factask.sim.episode", "evaluate_task"),
    "check_runtime": ("factask.sim.episode", "check_runtime"),
    "EpisodeResult": ("factask.sim.episode", "EpisodeResult"),
    "TaskResult": ("factask.sim.episode", "TaskResult"),
    "SceneRenderer": ("factask.sim.render", "SceneRenderer"),
    "VideoRecorder": ("factask.sim.render", "VideoRecorder"),
    # LLM generation by factorization
    "generate": ("factask.gen", "generate"),
    "Generator": ("factask.gen", "Generator"),
    "GenerationResult": ("factask.gen", "GenerationResult"),
    "LLMConfig": ("factask.gen", "LLMConfig"),
    "LLMClient": ("factask.gen", "LLMClient"),
    "Verifier": ("factask.gen", "Verifier"),
    "SubtaskMemory": ("factask.gen", "SubtaskMemory"),
    "LoopbackServer": ("factask.gen", "LoopbackServer"),
    "run_benchmark": ("factask.evaluation.benchmark", "run_benchmark"),
    # CLIPort / GenSim task code
    "import_cliport": ("factask.compat.cliport", "import_cliport"),
}

__all__ = [*_model_all, *_LAZY, "__version__"]


def __getattr__(name: str) -> Any:
    try:
        module, attribute = _LAZY[name]
    except KeyError:
        raise AttributeError(f"module 'factask' has no attribute {name!r}") from None
    value = getattr(importlib.import_module(module), attribute)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
