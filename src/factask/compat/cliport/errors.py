"""Typed errors of the CLIPort compatibility layer."""

from __future__ import annotations

from factask.model.errors import FactaskError, InvalidValueError


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


class PoseError(InvalidValueError):
    """A pose or quaternion in CLIPort/PyBullet form is malformed (not four finite
    numbers, a zero quaternion, no 3-D position). A ``ValueError``, as PyBullet's."""


class UnknownColorNameError(FactaskError, KeyError):
    """``utils.COLORS[name]`` with a name the palette lacks (a ``KeyError``, as
    looking up CLIPort's colour dict is)."""
