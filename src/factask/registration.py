"""gymnasium ids ``factask/<task>-v0`` for every library task, and :func:`make`.

``import factask`` registers the ids (cheap: the entry point is a string, so
nothing of MuJoCo loads until ``gymnasium.make``)::

    env = gymnasium.make("factask/stack-block-pyramid-v0", robot="arm", obs_mode="rgbd")

Each id also has a ``vector_entry_point``, the batched backend (:mod:`factask.batch`,
the ``gpu`` extra): ``gymnasium.make_vec(id, num_envs=N)`` gives a
:class:`~factask.batch.vector.BatchVectorEnv` (gymnasium takes a ``vector_entry_point``
when no ``vectorization_mode`` is named); ``vectorization_mode="sync"`` or ``"async"``
gives gymnasium's wrappers around N single envs instead (no extra needed).

:func:`make` takes a library name, a gymnasium id, a :class:`TaskGraph`, a graph
JSON file or a CLIPort task file (``FILE.py[:Class]``, user code: it is executed).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import gymnasium as gym
from gymnasium.envs.registration import register, registry

from factask.graph.taskgraph import TaskGraph, parse_graph
from factask.library.tasks import get_task, task_names
from factask.vocabulary.errors import FactaskError, GraphValidationError

#: The namespace of factask's gymnasium ids.
NAMESPACE = "factask"
#: The version suffix of every id.
VERSION = 0


class TaskSpecError(FactaskError, ValueError):
    """A task given to :func:`make` that is none of: name, id, graph, file."""


def env_id(task: str) -> str:
    """The gymnasium id of a library task: ``factask/<task>-v0``."""
    return f"{NAMESPACE}/{task}-v{VERSION}"


def task_of_id(spec: str) -> str:
    """The task name inside an id (``factask/x-v0`` -> ``x``); other text unchanged."""
    prefix, suffix = f"{NAMESPACE}/", f"-v{VERSION}"
    if spec.startswith(prefix) and spec.endswith(suffix):
        return spec[len(prefix):-len(suffix)]
    return spec


def register_envs() -> list[str]:
    """Register every library task's id (idempotent).

    Returns:
        The ids.
    """
    ids = []
    for name in task_names():
        gid = env_id(name)
        if gid not in registry:
            register(id=gid, entry_point="factask.registration:make_env",
                     vector_entry_point="factask.registration:make_vector_env",
                     kwargs={"task": name})
        ids.append(gid)
    return ids


def resolve_task(task: str | Path | TaskGraph) -> TaskGraph:
    """A task graph from a graph, a library name or id, or a graph/CLIPort file.

    Raises:
        TaskSpecError: unreadable file, invalid graph, or unknown name.
    """
    if isinstance(task, TaskGraph):
        return task
    spec = str(task)
    path_part, _, class_name = spec.partition(":") if ".py" in spec else (spec, "", "")
    if path_part.endswith(".py"):
        from factask.compat.cliport import import_cliport

        try:
            return import_cliport(path_part, class_name or None).graph
        except FactaskError as exc:
            raise TaskSpecError(f"cannot import {spec}: {exc}") from exc
    if spec.endswith(".json") or Path(spec).is_file():
        try:
            return parse_graph(Path(spec).read_text())
        except OSError as exc:
            raise TaskSpecError(f"cannot read task file {spec}: {exc.strerror or exc} "
                                "(fix: give an existing graph JSON file)") from exc
        except GraphValidationError as exc:
            raise TaskSpecError(f"{spec}: invalid task graph\n{exc}") from exc
    return get_task(task_of_id(spec))  # UnknownTaskError names close tasks


def make_env(task: str | Path | TaskGraph, robot: str = "floating", obs_mode: str = "state",
             render_mode: str | None = None, image_size: tuple[int, int] | None = None,
             cameras: Any = None, pixel_size: float | None = None,
             show_markers: bool = False) -> gym.Env:
    """A factask env observed in ``obs_mode`` (the gymnasium entry point).

    Args:
        task: Library name or id, :class:`TaskGraph`, graph JSON or CLIPort file.
        robot: A name of the robot registry ("floating", "arm", ...).
        obs_mode: "state", "rgbd" or "heightmap" (:mod:`factask.sim.render.observations`).
        render_mode: None or "rgb_array".
        image_size: (width, height) of the default (Ravens) cameras.
        cameras: A tuple of :class:`~factask.sim.render.cameras.CameraSpec` instead.
        pixel_size: Height-map metres per pixel (default CLIPort's 3.125 mm).
        show_markers: Draw goal markers in camera images.

    Returns:
        An :class:`~factask.sim.render.observations.ObservationWrapper` around a
        :class:`~factask.sim.env.FactaskEnv`.

    Raises:
        TaskSpecError, UnknownTaskError: the task cannot be found.
        InvalidValueError, CameraError, CompileError: bad options or graph.
    """
    from factask.sim.env import FactaskEnv
    from factask.sim.render.heightmaps import PIXEL_SIZE
    from factask.sim.render.observations import (
        DEFAULT_IMAGE_SIZE,
        ObservationConfig,
        ObservationWrapper,
    )

    config = ObservationConfig(
        mode=obs_mode, cameras=tuple(cameras) if cameras is not None else None,
        image_size=tuple(image_size) if image_size is not None else DEFAULT_IMAGE_SIZE,
        pixel_size=PIXEL_SIZE if pixel_size is None else float(pixel_size),
        show_markers=show_markers)
    env = FactaskEnv(resolve_task(task), robot=robot, render_mode=render_mode)
    try:
        return ObservationWrapper(env, config)
    except FactaskError:
        env.close()
        raise


def make_vector_env(num_envs: int, task: str | Path | TaskGraph, robot: str = "floating",
                    obs_mode: str = "state", device: str | None = None,
                    **kwargs: Any) -> gym.vector.VectorEnv:
    """``num_envs`` worlds of a task on the batched backend (the ids' vector entry point).

    Args:
        num_envs: Worlds.
        task: Library name or id, :class:`TaskGraph`, graph JSON or CLIPort file.
        robot: "floating" (the batched pick-and-place moves the floating cup only).
        obs_mode: "state" (the only mode the batch observes so far).
        device: "cpu", "cuda", "cuda:N" or None (a GPU if there is one, else the CPU).
        **kwargs: Passed to :class:`~factask.batch.env.BatchEnv` (``nconmax``, ...).

    Returns:
        A :class:`~factask.batch.vector.BatchVectorEnv`.

    Raises:
        InvalidValueError: another robot or observation mode.
        BatchBackendMissing: the ``gpu`` extra is not installed (or use
            ``vectorization_mode="sync"`` / ``"async"``).
        DeviceUnavailableError: a GPU asked for that is not there.
    """
    from factask.batch.vector import BatchVectorEnv
    from factask.vocabulary.errors import InvalidValueError

    if obs_mode != "state" or robot != "floating":
        raise InvalidValueError(
            f"the batched vector env runs robot 'floating' in obs_mode 'state', not robot "
            f"{robot!r} in {obs_mode!r} (fix: make_vec(..., vectorization_mode='sync' or "
            "'async') for the single env's robots and modes)")
    return BatchVectorEnv(resolve_task(task), num_envs, device=device, **kwargs)


def make(task: str | Path | TaskGraph, **kwargs: Any) -> gym.Env:
    """:func:`make_env` under its public name (``factask.make``)."""
    return make_env(task, **kwargs)
