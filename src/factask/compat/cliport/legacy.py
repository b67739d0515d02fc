"""Names of GenSim's Python 3.8 / NumPy 1.x stack, lent while a task file runs.

GenSim ran on Python 3.8 with a NumPy older than 1.24; factask runs on a newer
Python and NumPy 2, which removed names that code written for GenSim still uses
and that worked there (some with a deprecation warning):

* NumPy's aliases of builtins (``np.float``, ``np.int``, ``np.object``,
  ``np.str``, ``np.complex``; removed in 1.24) and the names NumPy 2 removed
  (``np.product``, ``np.cumproduct``, ``np.alltrue``, ``np.sometrue``,
  ``np.round_``, ``np.float_``, ``np.complex_``, ``np.int0``, ``np.uint0``,
  ``np.NaN``, ``np.Inf``, ``np.infty``, ``np.PINF``, ``np.NINF``, ``np.asfarray``,
  ``np.asscalar``);
* ``random.sample`` of a set or a dict view (``random.sample(utils.COLORS.keys(),
  3)``; Python 3.11 requires a sequence; 3.8 took ``tuple(population)``, so the
  same seed draws the same items), and ``random.shuffle(x, random)`` with its
  second argument (removed in 3.11; 3.8's algorithm).

:func:`legacy_names` adds each such name only where it is missing and removes
exactly what it added on exit, so nothing leaks into the rest of the process.
Why lend them rather than fail: the file runs unchanged on the stack it was
written for, so its failure would be factask's, not the author's.
"""

from __future__ import annotations

import contextlib
import math
import random
from collections.abc import Callable, Iterator, MutableSequence
from collections.abc import Set as AbstractSet
from typing import Any

import numpy as np

#: NumPy names GenSim-era code uses that NumPy 1.24 / 2.0 removed -> what they meant.
NUMPY_NAMES: dict[str, Any] = {
    "float": float, "int": int, "object": object, "str": str, "complex": complex,
    "unicode": str, "product": np.prod, "cumproduct": np.cumprod, "alltrue": np.all,
    "sometrue": np.any, "round_": np.round, "float_": np.float64, "complex_": np.complex128,
    "int0": np.intp, "uint0": np.uintp, "NaN": np.nan, "NAN": np.nan, "Inf": np.inf,
    "Infinity": np.inf, "infty": np.inf, "PINF": np.inf, "NINF": -np.inf,
    "asfarray": lambda a, dtype=np.float64: np.asarray(a, dtype=dtype),
    "asscalar": lambda a: np.asarray(a).item(),
}


def _sample(original: Callable[..., list[Any]]) -> Callable[..., list[Any]]:
    """``random.sample`` that takes a set or dict view as Python 3.8 did."""

    def sample(population: Any, k: int, **kwargs: Any) -> list[Any]:
        if isinstance(population, AbstractSet):
            population = tuple(population)  # 3.8: the same order, so the same draws
        return original(population, k, **kwargs)

    return sample


def _shuffle(original: Callable[..., None]) -> Callable[..., None]:
    """``random.shuffle`` that takes Python 3.8's second argument, a 0-1 generator."""

    def shuffle(x: MutableSequence[Any], random: Callable[[], float] | None = None) -> None:
        if random is None:
            original(x)
            return
        for i in reversed(range(1, len(x))):  # Python 3.8's shuffle with a given random()
            j = math.floor(random() * (i + 1))
            x[i], x[j] = x[j], x[i]

    return shuffle


def _has(module: Any, name: str) -> bool:
    # NumPy 2 answers the removed names from a module __getattr__ that raises (and
    # for some warns first): look in the module's own namespace only.
    return name in vars(module)


@contextlib.contextmanager
def legacy_names() -> Iterator[None]:
    """Lend GenSim-era NumPy names and Python 3.8's ``random.sample`` /
    ``random.shuffle`` behaviour for the duration of the block.

    Only names NumPy lacks are added (a NumPy that still has ``np.product`` keeps
    its own), and exactly those are removed again on exit; ``random.sample`` and
    ``random.shuffle`` are restored to the functions they were.
    """
    added = [name for name in NUMPY_NAMES if not _has(np, name)]
    for name in added:
        setattr(np, name, NUMPY_NAMES[name])
    saved_sample, saved_shuffle = random.sample, random.shuffle
    random.sample = _sample(saved_sample)  # type: ignore[assignment]
    random.shuffle = _shuffle(saved_shuffle)  # type: ignore[assignment]
    try:
        yield
    finally:
        random.sample, random.shuffle = saved_sample, saved_shuffle  # type: ignore[assignment]
        for name in added:
            if _has(np, name):
                delattr(np, name)
