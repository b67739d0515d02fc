"""The MuJoCo backend of factask: assets, compilation, robot, layout, checks, rendering.

Imports only the graph model (:mod:`factask.graph`) and :mod:`factask.geometry`;
never the generation side. Submodules are imported explicitly
(``from factask.sim.build.compile import compile_graph``) so that importing this
package stays cheap.

Importing this package picks a headless OpenGL backend for MuJoCo when
``MUJOCO_GL`` is not set: MuJoCo (and dm_control, which ``dm_control.mjcf``
imports) read ``MUJOCO_GL`` once, when they are first imported, and otherwise
fall back to GLFW, which needs an X display. A value the user set is never
changed. :mod:`factask.sim.render.offscreen` repairs the choice if MuJoCo was imported
before this package.
"""

from __future__ import annotations

import ctypes.util
import os


def _default_gl_backend() -> str | None:
    """The headless GL backend to use: EGL if libEGL is present, else OSMesa, else None."""
    if ctypes.util.find_library("EGL"):
        return "egl"
    if ctypes.util.find_library("OSMesa"):
        return "osmesa"
    return None


if not os.environ.get("MUJOCO_GL"):
    _backend = _default_gl_backend()
    if _backend is not None:
        os.environ["MUJOCO_GL"] = _backend
