"""Typed errors of the CLIPort compatibility layer."""

from __future__ import annotations

from factask.model.errors import FactaskError


class CliportImportError(FactaskError):
    """A CLIPort/GenSim task file could not be turned into a task graph.

    The message names the file, and where it applies the line of the user's code
    that failed (syntax errors, exceptions raised in ``reset``), so the author can
    fix it without reading factask's code.
    """


class Unsupported(CliportImportError):
    """The task code uses a CLIPort/PyBullet feature factask does not model.

    Examples: deformables (cloth, rope, piles), spatula pushing, Google scanned
    objects, an unknown URDF, a PyBullet call with no recorded meaning. The
    message names the call or the asset.
    """
