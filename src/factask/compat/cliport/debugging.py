"""Stand-ins for the debugging modules task files import and never need.

LLM-written task files often start with ``import IPython`` or ``import ipdb`` and may
call ``IPython.embed()``, ``ipdb.set_trace()`` or ``breakpoint()`` on a path the author
tried. factask runs task files without a console: a real debugger would wait for input
for ever (or the import fails where the package is not installed). While a file runs,
these names are lent: each call does nothing and is recorded as a warning of the
import (``IPython.embed() ignored: ...``), and ``breakpoint()`` goes to the same
stand-in. Whatever the names meant before is restored afterwards.
"""

from __future__ import annotations

import contextlib
import sys
import types
from collections.abc import Callable, Iterator
from typing import Any

from factask.compat.cliport.recorder import active_session

#: Module -> the callables task code uses from it.
DEBUG_MODULES: dict[str, tuple[str, ...]] = {
    "IPython": ("embed", "display", "start_ipython", "get_ipython"),
    "IPython.core": (),
    "IPython.core.debugger": ("set_trace", "Pdb"),
    "IPython.display": ("display", "clear_output"),
    "ipdb": ("set_trace", "post_mortem", "pm", "runcall"),
    "pudb": ("set_trace", "post_mortem", "pm"),
}


def _ignored(name: str) -> Callable[..., Any]:
    def call(*args: Any, **kwargs: Any) -> None:
        with contextlib.suppress(Exception):  # outside an import: nothing to tell
            active_session().warn(f"{name}() ignored: factask runs task files without a "
                                  "console or debugger")
    call.__name__ = name.rsplit(".", 1)[-1]
    return call


def _stand_ins() -> dict[str, types.ModuleType]:
    modules: dict[str, types.ModuleType] = {}
    for name, calls in DEBUG_MODULES.items():
        module = types.ModuleType(name, f"factask's stand-in for {name} (task files only)")
        for call in calls:
            setattr(module, call, _ignored(f"{name}.{call}"))
        module.__path__ = []  # a package: its submodules import
        modules[name] = module
    for name, module in modules.items():
        parent, _, child = name.rpartition(".")
        if parent in modules:
            setattr(modules[parent], child, module)
    return modules


@contextlib.contextmanager
def debugging_stand_ins() -> Iterator[None]:
    """Lend the stand-ins (and a ``breakpoint()`` that does nothing) while a task file
    runs; restore what was there before on exit."""
    saved = {name: sys.modules.get(name) for name in DEBUG_MODULES}
    hook = sys.breakpointhook
    sys.modules.update(_stand_ins())
    sys.breakpointhook = _ignored("breakpoint")
    try:
        yield
    finally:
        sys.breakpointhook = hook
        for name, prev in saved.items():
            if prev is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = prev
