"""Observation modes of a :class:`~factask.sim.env.FactaskEnv`: ``state``, ``rgbd``, ``heightmap``.

Every mode carries the state keys:

* ``object_poses`` (n, 7), ``ee_pose`` (7,), ``suction`` (1,): the env's own observation;
* ``factor_progress`` (k,): each factor's progress in ``graph.factor_names()`` order;
* ``instruction``: the episode's language instruction (the task's description);
* ``goal``: the language goal of the current factor (the first unsatisfied one in the
  graph's factor order; empty once all are satisfied).

Both texts are UTF-8 bytes, zero-padded to :data:`MAX_TEXT_BYTES` (``uint8`` arrays;
:func:`decode_text` turns one back into a string): gymnasium's ``Text`` space does not
survive ``AsyncVectorEnv``'s shared memory (it reads strings once, at start-up).
``info["instruction"]`` and ``info["goal"]`` carry the full strings.

``rgbd`` adds ``images[camera]`` = {``rgb`` (h, w, 3) uint8, ``depth`` (h, w) float32
metres, ``segmentation`` (h, w) int32} per camera (default: Ravens' front, left,
right); segmentation id 0 is background, id i + 1 is object instance i
(:attr:`ObservationWrapper.segmentation_labels` names its instance and variable).
``heightmap`` adds CLIPort's fused top-down ``heightmap`` = {``color`` (ny, nx, 3)
uint8, ``height`` (ny, nx) float32 metres above the table}: rows run along y,
columns along x, over the workspace at :data:`PIXEL_SIZE` m per pixel
(:mod:`factask.sim.render.heightmaps`).

The modes are a gymnasium wrapper so the env's own stepping stays untouched.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from factask.sim.render.cameras import CameraRig, CameraSpec, ravens_cameras
from factask.sim.render.heightmaps import PIXEL_SIZE, HeightmapGrid, fuse_heightmaps
from factask.vocabulary.errors import InvalidValueError

#: The observation modes.
OBS_MODES = ("state", "rgbd", "heightmap")
#: Default camera image size (width, height) of the rgbd and heightmap modes.
DEFAULT_IMAGE_SIZE = (160, 120)
#: Bytes of language text an observation holds (longer text is cut at a character).
MAX_TEXT_BYTES = 512


@dataclass(frozen=True)
class ObservationConfig:
    """What an observation holds.

    Attributes:
        mode: One of :data:`OBS_MODES`.
        cameras: The cameras (default: Ravens' three at ``image_size``).
        image_size: (width, height) of the default cameras.
        pixel_size: Height-map resolution (m per pixel).
        show_markers: Draw the goal markers in RGB images (Ravens does not).
    """

    mode: str = "state"
    cameras: tuple[CameraSpec, ...] | None = None
    image_size: tuple[int, int] = DEFAULT_IMAGE_SIZE
    pixel_size: float = PIXEL_SIZE
    show_markers: bool = False

    def __post_init__(self) -> None:
        if self.mode not in OBS_MODES:
            raise InvalidValueError(f"obs_mode must be one of {OBS_MODES}, got {self.mode!r} "
                                    "(fix: obs_mode='state')")
        if not self.pixel_size > 0:
            raise InvalidValueError(f"pixel_size must be positive, got {self.pixel_size}")

    def camera_specs(self) -> tuple[CameraSpec, ...]:
        """The cameras in use."""
        return self.cameras if self.cameras is not None else ravens_cameras(*self.image_size)


def encode_text(text: str) -> np.ndarray:
    """``text`` as UTF-8 bytes, cut at a character boundary and zero-padded to
    :data:`MAX_TEXT_BYTES`."""
    raw = text.encode("utf-8")[:MAX_TEXT_BYTES].decode("utf-8", "ignore").encode("utf-8")
    out = np.zeros(MAX_TEXT_BYTES, dtype=np.uint8)
    out[:len(raw)] = np.frombuffer(raw, dtype=np.uint8)
    return out


def decode_text(array: np.ndarray) -> str:
    """The string an :func:`encode_text` array holds."""
    return bytes(np.asarray(array, dtype=np.uint8)).rstrip(b"\0").decode("utf-8", "ignore")


class ObservationWrapper(gym.Wrapper):
    """A :class:`~factask.sim.env.FactaskEnv` observed in one of :data:`OBS_MODES`.

    Args:
        env: The env (unwrapped ``FactaskEnv``).
        config: What to observe.

    Raises:
        InvalidValueError, CameraError: a bad mode or camera set-up.
    """

    def __init__(self, env: gym.Env, config: ObservationConfig | None = None) -> None:
        super().__init__(env)
        self.config = config or ObservationConfig()
        base: Any = env.unwrapped
        self._base = base
        graph = base.graph
        self.factor_names: list[str] = graph.factor_names()
        self._order: list[str] = graph.factor_order()
        self._goals = {f.name: f.description or "" for f in graph.factors}
        self.instruction: str = graph.description or graph.name
        text = spaces.Box(0, 255, (MAX_TEXT_BYTES,), np.uint8)
        names = base.object_names
        var_of = {n: o.variable for n, o in base.objects.items()}
        #: Segmentation id -> {"instance": name, "variable": variable name}.
        self.segmentation_labels: dict[int, dict[str, str]] = {
            i + 1: {"instance": n, "variable": var_of[n]} for i, n in enumerate(names)}
        space: dict[str, spaces.Space] = dict(base.observation_space.spaces)
        space["factor_progress"] = spaces.Box(0.0, 1.0, (len(self.factor_names),), np.float64)
        space["instruction"] = text
        space["goal"] = text
        self._rig: CameraRig | None = None
        self._grid: HeightmapGrid | None = None
        mode = self.config.mode
        if mode in ("rgbd", "heightmap"):
            cams = self.config.camera_specs()
            self._rig = CameraRig(base.model, cams, base.scene.geom_object,
                                  show_markers=self.config.show_markers)
        if mode == "rgbd":
            space["images"] = spaces.Dict({c.name: spaces.Dict({
                "rgb": spaces.Box(0, 255, (c.height, c.width, 3), np.uint8),
                "depth": spaces.Box(0.0, np.inf, (c.height, c.width), np.float32),
                "segmentation": spaces.Box(0, len(names), (c.height, c.width), np.int32),
            }) for c in cams})
        elif mode == "heightmap":
            self._grid = HeightmapGrid(pixel_size=self.config.pixel_size)
            ny, nx = self._grid.shape
            space["heightmap"] = spaces.Dict({
                "color": spaces.Box(0, 255, (ny, nx, 3), np.uint8),
                "height": spaces.Box(0.0, np.inf, (ny, nx), np.float32),
            })
        self.observation_space = spaces.Dict(space)

    def current_goal(self, info: dict[str, Any]) -> str:
        """The language goal of the first unsatisfied factor in order ("" if none)."""
        satisfied = info.get("satisfied", {})
        for name in self._order:
            if not satisfied.get(name, False):
                return self._goals[name]
        return ""

    def observe(self, obs: dict[str, np.ndarray], info: dict[str, Any]) -> dict[str, Any]:
        """The full observation from the env's own ``obs`` and ``info``."""
        out: dict[str, Any] = dict(obs)
        factors = info.get("factors", {})
        out["factor_progress"] = np.clip(np.array(
            [float(factors.get(n, 0.0)) for n in self.factor_names], dtype=np.float64), 0, 1)
        goal = self.current_goal(info)
        out["instruction"] = encode_text(self.instruction)
        out["goal"] = encode_text(goal)
        info["instruction"], info["goal"] = self.instruction, goal
        if self._rig is not None:
            data = self._base.data
            if self.config.mode == "rgbd":
                out["images"] = {c.name: {
                    "rgb": self._rig.rgb(data, c.name),
                    "depth": self._rig.depth(data, c.name),
                    "segmentation": self._rig.segmentation(data, c.name),
                } for c in self._rig.cameras}
            else:
                assert self._grid is not None
                color, height = fuse_heightmaps(
                    [(c, self._rig.rgb(data, c.name), self._rig.depth(data, c.name))
                     for c in self._rig.cameras], self._grid)
                out["heightmap"] = {"color": color, "height": height}
        return out

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None
              ) -> tuple[dict[str, Any], dict[str, Any]]:
        """Reset the env; the observation in this wrapper's mode."""
        obs, info = self.env.reset(seed=seed, options=options)
        return self.observe(obs, info), info

    def step(self, action: dict[str, Any]) -> tuple[dict[str, Any], float, bool, bool,
                                                    dict[str, Any]]:
        """Step the env; the observation in this wrapper's mode."""
        obs, reward, terminated, truncated, info = self.env.step(action)
        return self.observe(obs, info), reward, terminated, truncated, info

    def close(self) -> None:
        """Free the cameras' GL contexts and close the env."""
        if self._rig is not None:
            self._rig.close()
            self._rig = None
        super().close()
