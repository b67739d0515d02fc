"""factask: robot manipulation tasks as explicit factor graphs, compiled to MuJoCo.

The graph model is imported eagerly (it is pure Python). Everything that pulls in
heavy dependencies — the MuJoCo backend, the task library, drawing, LLM
generation, the CLIPort layer — is re-exported *lazily*: ``factask.FactaskEnv``
runs ``import factask.sim.env`` on first use, so ``import factask`` stays fast.
"""

from __future__ import annotations

from collections.abc import Callable
from types import ModuleType
from typing import Any

from factask.graph import *  # noqa: F403
from factask.graph import __all__ as _model_all

__version__ = "0.1.0"


# One loader per lazily re-exported module: a plain import, run on first use.
def _library() -> ModuleType:
    import factask.library as module

    return module


def _templates() -> ModuleType:
    import factask.library.templates as module

    return module


def _viz() -> ModuleType:
    import factask.viz as module

    return module


def _compile() -> ModuleType:
    import factask.sim.build.compile as module

    return module


def _collision() -> ModuleType:
    import factask.scene.collision as module

    return module


def _env() -> ModuleType:
    import factask.sim.env as module

    return module


def _oracle() -> ModuleType:
    import factask.sim.oracle.scripted as module

    return module


def _episode() -> ModuleType:
    import factask.sim.episode as module

    return module


def _render() -> ModuleType:
    import factask.sim.render.offscreen as module

    return module


def _registration() -> ModuleType:
    import factask.registration as module

    return module


def _gen() -> ModuleType:
    import factask.gen as module

    return module


def _benchmark() -> ModuleType:
    import factask.evaluation.benchmark as module

    return module


def _cliport() -> ModuleType:
    import factask.compat.cliport as module

    return module


def _batch() -> ModuleType:
    import factask.batch.env as module

    return module


#: Lazily re-exported names: public name -> the loader of the module defining it.
_LAZY: dict[str, Callable[[], ModuleType]] = {
    # task library
    "get_task": _library,
    "task_names": _library,
    "list_tasks": _library,
    "TEMPLATES": _templates,
    "get_template": _templates,
    # pictures
    "draw_graph": _viz,
    # MuJoCo backend
    "compile_graph": _compile,
    "CompileError": _compile,
    "LayoutError": _collision,
    "FactaskEnv": _env,
    "Oracle": _oracle,
    "run_episode": _episode,
    "evaluate_task": _episode,
    "check_runtime": _episode,
    "EpisodeResult": _episode,
    "TaskResult": _episode,
    "SceneRenderer": _render,
    "VideoRecorder": _render,
    # gymnasium ids and observation modes
    "make": _registration,
    "env_id": _registration,
    # LLM generation by factorization
    "generate": _gen,
    "Generator": _gen,
    "GenerationResult": _gen,
    "LLMConfig": _gen,
    "LLMClient": _gen,
    "Verifier": _gen,
    "SubtaskMemory": _gen,
    "LoopbackServer": _gen,
    "run_benchmark": _benchmark,
    # CLIPort / GenSim task code
    "import_cliport": _cliport,
    # many worlds at once on MuJoCo Warp (the gpu extra)
    "make_batch": _batch,
}

__all__ = [*_model_all, *_LAZY, "__version__"]


def __getattr__(name: str) -> Any:
    loader = _LAZY.get(name)
    if loader is None:
        raise AttributeError(f"module 'factask' has no attribute {name!r}")
    value = getattr(loader(), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


# gymnasium ids factask/<task>-v0: string entry points, so MuJoCo loads only on make.
_registration().register_envs()
