"""LIBERO's BDDL task files, read into typed values (issue 38, its first step).

LIBERO (Liu et al., 2023) defines its manipulation tasks as BDDL problems. This
package reads them (:func:`parse_bddl`, :func:`load_bddl`) into a
:class:`BddlProblem` and writes them back (:func:`format_bddl`);
:func:`import_libero` turns a problem into a factask task graph, its objects mapped
to factask stand-ins (:data:`LIBERO_KINDS`: every type LIBERO registers; its scenes:
:data:`LIBERO_SCENES`). Three of LIBERO's suites ship with factask,
unchanged, for development and tests (``factask/data/libero``, MIT licence):
:func:`shipped_bddl_files`.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from factask.compat.libero.bddl import load_bddl, parse_bddl
from factask.compat.libero.importer import LiberoImport, import_libero
from factask.compat.libero.kinds import (
    LIBERO_KINDS,
    LIBERO_SCENES,
    LiberoKind,
    LiberoUnsupported,
    UnknownLiberoRegion,
    UnknownLiberoType,
)
from factask.compat.libero.model import BddlProblem, Predicate, Region, format_bddl
from factask.compat.libero.sexpr import BddlError

#: The LIBERO suites shipped with factask (10 task files each).
SHIPPED_SUITES = ("libero_goal", "libero_object", "libero_spatial")


def libero_data_dir() -> Path:
    """The folder of the shipped LIBERO files (``factask/data/libero``: one folder per
    suite, LIBERO's LICENSE and a README saying where they come from).

    Returns:
        The folder.
    """
    return Path(str(resources.files("factask") / "data" / "libero"))


def shipped_bddl_files(suite: str | None = None) -> list[Path]:
    """The shipped BDDL files, sorted by suite then name.

    Args:
        suite: One of :data:`SHIPPED_SUITES`, or None for all three.

    Returns:
        The files' paths.

    Raises:
        BddlError: ``suite`` is not a shipped suite.
    """
    if suite is not None and suite not in SHIPPED_SUITES:
        raise BddlError(str(suite), "not a shipped LIBERO suite", f"one of {SHIPPED_SUITES}")
    suites = SHIPPED_SUITES if suite is None else (suite,)
    return [path for name in suites for path in sorted((libero_data_dir() / name).glob("*.bddl"))]


__all__ = [
    "LIBERO_KINDS", "LIBERO_SCENES", "SHIPPED_SUITES", "BddlError", "BddlProblem",
    "LiberoImport", "LiberoKind", "LiberoUnsupported", "Predicate", "Region",
    "UnknownLiberoRegion", "UnknownLiberoType",
    "format_bddl", "import_libero", "libero_data_dir", "load_bddl", "parse_bddl",
    "shipped_bddl_files",
]
