"""Headless rendering: RGB, depth and object segmentation images, and videos.

Backend: MuJoCo reads ``MUJOCO_GL`` once, when ``mujoco`` is first imported.
Importing :mod:`factask.sim` sets it (EGL, else OSMesa) unless the user did;
if MuJoCo was imported earlier without it, :func:`ensure_headless_gl` swaps the
GLFW context (which needs an X display) for EGL or OSMesa before the first
renderer is made. Software rendering speed is dominated by the shadow map size,
which the compiled scenes keep at 1024 (:data:`factask.sim.build.mjcf.SHADOW_SIZE`).

Renderers hold an OpenGL context: use :class:`SceneRenderer` as a context
manager (or call ``close``) so contexts are freed deterministically.
"""

from __future__ import annotations

import colorsys
import hashlib
import importlib
import math
import os
from collections.abc import Sequence
from pathlib import Path
from types import TracebackType

import mujoco
import numpy as np

from factask.sim.build.parts import MARKER_GROUP
from factask.sim.build.stage import OFFSCREEN_SIZE, TOP_CAMERA
from factask.vocabulary.errors import FactaskError
from factask.vocabulary.world import WORKSPACE_X, WORKSPACE_Y, WORKSPACE_Z

#: Default image size (width, height) in pixels.
DEFAULT_SIZE = (320, 240)
#: Segmentation value of pixels that show no object (table, robot, background).
BACKGROUND_ID = -1
#: Default frames per second of videos.
DEFAULT_FPS = 20
#: Headless backends in order of preference.
HEADLESS_BACKENDS = ("egl", "osmesa")
#: Views :func:`framed_camera` frames, name -> (azimuth, elevation) in degrees, in
#: MuJoCo's free-camera convention (the azimuth is the direction the camera looks
#: along; a negative elevation looks down). The robot stands at x = 0 facing +x.
VIEWS: dict[str, tuple[float, float]] = {
    "front": (180.0, -35.0),  # from beyond the workspace, facing the robot
    "top": (0.0, -89.0),  # straight down, the robot at the bottom (-90 leaves "up" undefined)
    "left": (-90.0, -35.0),  # from the robot's left (+y)
    "right": (90.0, -35.0),  # from the robot's right (-y)
    "back": (0.0, -30.0),  # from behind the robot, over its base
}
#: Colour of segmentation pixels that show no object.
SEGMENTATION_BACKGROUND = (30, 30, 30)

#: A camera: its name, its id (-1: the free camera) or a ``mujoco.MjvCamera``.
Camera = str | int | mujoco.MjvCamera


class RenderError(FactaskError):
    """Rendering is impossible or was asked for wrongly (no GL, bad camera, size)."""


# ------------------------------------------------------------------ backend
def active_gl_backend() -> str:
    """Name of the GL context MuJoCo's renderer will use: "egl", "osmesa", "glfw",
    or "none" (rendering disabled)."""
    from mujoco.rendering.classic import gl_context

    ctx = getattr(gl_context, "GLContext", None)
    if ctx is None:
        return "none"
    module = ctx.__module__
    for name in ("egl", "osmesa", "glfw", "cgl", "wgl"):
        if f".{name}" in module or module.endswith(name):
            return name
    return module


def ensure_headless_gl() -> str:
    """Make sure MuJoCo renders without a display; return the backend in use.

    Respects an explicit ``MUJOCO_GL``. Otherwise, if MuJoCo was imported before
    a headless backend was chosen and there is no X display, swaps its GLFW
    context class for EGL (or OSMesa).

    Returns:
        The backend name (see :func:`active_gl_backend`).
    """
    backend = active_gl_backend()
    explicit = os.environ.get("MUJOCO_GL", "").lower()
    if backend != "glfw" or os.environ.get("DISPLAY") or explicit == "glfw":
        return backend
    from mujoco.rendering.classic import gl_context

    for name in HEADLESS_BACKENDS:
        try:
            module = importlib.import_module(f"mujoco.{name}")
        except (ImportError, OSError, RuntimeError, AttributeError):
            continue
        gl_context.GLContext = module.GLContext
        return name
    return backend


# ----------------------------------------------------------------- renderer
def _camera_id(model: mujoco.MjModel, camera: Camera) -> int | mujoco.MjvCamera:
    if isinstance(camera, mujoco.MjvCamera):
        return camera
    if isinstance(camera, str):
        cam = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, camera)
        if cam < 0:
            names = [model.camera(i).name for i in range(model.ncam)]
            raise RenderError(f"no camera {camera!r} in the model; cameras: {names}")
        return int(cam)
    if not -1 <= int(camera) < model.ncam:
        raise RenderError(f"camera id {camera} out of range [-1, {model.ncam})")
    return int(camera)


class SceneRenderer:
    """One offscreen renderer (one GL context) of a model at a fixed image size.

    Args:
        model: The compiled model.
        width: Image width in pixels.
        height: Image height in pixels.
        geom_object: Optional geom id -> object index map (see
            ``CompiledScene.geom_object``) used by :meth:`segmentation`.

    Raises:
        RenderError: the size exceeds the model's offscreen buffer, or no GL
            context can be created.
    """

    def __init__(self, model: mujoco.MjModel, width: int = DEFAULT_SIZE[0],
                 height: int = DEFAULT_SIZE[1], geom_object: np.ndarray | None = None) -> None:
        max_w, max_h = int(model.vis.global_.offwidth), int(model.vis.global_.offheight)
        if not (0 < width <= max_w and 0 < height <= max_h):
            raise RenderError(
                f"image size {width}x{height} outside the model's offscreen buffer "
                f"{max_w}x{max_h} (fix: use a smaller size, at most {OFFSCREEN_SIZE})")
        ensure_headless_gl()
        try:
            self._renderer = mujoco.Renderer(model, height=height, width=width)
        except Exception as exc:  # GL errors come as many types; name the fix.
            raise RenderError(
                f"cannot create an OpenGL context ({type(exc).__name__}: {exc}); "
                f"backend {active_gl_backend()!r} (fix: install libegl1 libegl-mesa0 "
                "libgl1-mesa-dri, or libosmesa6 and set MUJOCO_GL=osmesa)") from exc
        self.model = model
        self.width, self.height = width, height
        self.geom_object = geom_object

    def _option(self, show_markers: bool) -> mujoco.MjvOption:
        opt = mujoco.MjvOption()
        opt.geomgroup[MARKER_GROUP] = 1 if show_markers else 0
        return opt

    def rgb(self, data: mujoco.MjData, camera: Camera = TOP_CAMERA,
            show_markers: bool = True) -> np.ndarray:
        """RGB image (height, width, 3) uint8 from ``camera``.

        Args:
            data: The model's data (positions must be current: ``mj_forward``).
            camera: Camera name, id (-1: the free camera) or ``mujoco.MjvCamera``.
            show_markers: Draw the translucent goal markers.
        """
        r = self._renderer
        r.update_scene(data, _camera_id(self.model, camera), self._option(show_markers))
        return r.render().copy()

    def depth(self, data: mujoco.MjData, camera: Camera = TOP_CAMERA) -> np.ndarray:
        """Depth image (height, width) float32, metres from the camera plane
        (goal markers hidden)."""
        r = self._renderer
        r.enable_depth_rendering()
        try:
            r.update_scene(data, _camera_id(self.model, camera), self._option(False))
            return r.render().astype(np.float32)
        finally:
            r.disable_depth_rendering()

    def segmentation(self, data: mujoco.MjData, camera: Camera = TOP_CAMERA) -> np.ndarray:
        """Object segmentation (height, width) int64 (goal markers hidden).

        Each pixel holds the object index of the geom it shows (through
        ``geom_object``), or :data:`BACKGROUND_ID`; without ``geom_object``, the
        raw geom id (or -1).
        """
        r = self._renderer
        r.enable_segmentation_rendering()
        try:
            r.update_scene(data, _camera_id(self.model, camera), self._option(False))
            seg = r.render()
        finally:
            r.disable_segmentation_rendering()
        ids, types = seg[..., 0].astype(np.int64), seg[..., 1]
        geom = np.where(types == mujoco.mjtObj.mjOBJ_GEOM, ids, -1)
        if self.geom_object is None:
            return geom
        table = np.asarray(self.geom_object, dtype=np.int64)
        return np.where(geom >= 0, table[np.clip(geom, 0, len(table) - 1)], BACKGROUND_ID)

    def close(self) -> None:
        """Free the GL context (safe to call twice)."""
        renderer = getattr(self, "_renderer", None)
        if renderer is not None:
            renderer.close()
            self._renderer = None

    def __enter__(self) -> SceneRenderer:
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        self.close()


def render_rgb(model: mujoco.MjModel, data: mujoco.MjData, camera: Camera = TOP_CAMERA,
               width: int = DEFAULT_SIZE[0], height: int = DEFAULT_SIZE[1]) -> np.ndarray:
    """One RGB image (height, width, 3) uint8 (opens and closes a renderer).

    Raises:
        RenderError: see :class:`SceneRenderer`.
    """
    with SceneRenderer(model, width, height) as r:
        return r.rgb(data, camera)


def render_depth(model: mujoco.MjModel, data: mujoco.MjData, camera: Camera = TOP_CAMERA,
                 width: int = DEFAULT_SIZE[0], height: int = DEFAULT_SIZE[1]) -> np.ndarray:
    """One depth image (height, width) float32 in metres (opens and closes a renderer)."""
    with SceneRenderer(model, width, height) as r:
        return r.depth(data, camera)


def render_segmentation(model: mujoco.MjModel, data: mujoco.MjData,
                        camera: Camera = TOP_CAMERA, width: int = DEFAULT_SIZE[0],
                        height: int = DEFAULT_SIZE[1],
                        geom_object: np.ndarray | None = None) -> np.ndarray:
    """One segmentation image (height, width) int64 of object indices, -1 elsewhere
    (see :meth:`SceneRenderer.segmentation`)."""
    with SceneRenderer(model, width, height, geom_object) as r:
        return r.segmentation(data, camera)


# ------------------------------------------------------------------ framing
def _scene_points(model: mujoco.MjModel, data: mujoco.MjData) -> np.ndarray:
    """Points (n, 3) whose convex hull holds what a framed view must show whole.

    Every geom of a moving or placed body (objects, fixtures, goal markers, the
    robot with its base) counts by the cube around its bounding sphere: an arm's
    links turn about their joints while it moves, and the sphere holds more of
    where they go than the geom's own box. The workspace counts from the table up
    to the top of the scene (the robot reaches over all of it). The world body's
    own geoms (table, floor) are left out: the table may run off the picture.
    """
    keep = np.flatnonzero((model.geom_bodyid != 0)
                          & (model.geom_type != mujoco.mjtGeom.mjGEOM_PLANE))
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    cubes = (np.asarray(data.geom_xpos)[keep][:, None]
             + np.asarray(model.geom_rbound)[keep][:, None, None] * signs[None]).reshape(-1, 3)
    top = max(WORKSPACE_Z[1], float(cubes[:, 2].max()) if len(cubes) else 0.0)
    corners = np.array([[x, y, z] for x in WORKSPACE_X for y in WORKSPACE_Y
                        for z in (WORKSPACE_Z[0], top)])
    return np.concatenate([cubes, corners])


def framed_camera(model: mujoco.MjModel, data: mujoco.MjData, view: str = "front",
                  aspect: float = 4 / 3, margin: float = 0.1) -> mujoco.MjvCamera:
    """A free camera looking from ``view`` that shows the whole scene as it is now.

    The scene is every object, fixture, goal marker and the robot (its base
    included) plus the workspace; the camera is aimed at their centre and pulled
    back until every geom's bounding sphere fits the image, so nothing is cut at an
    edge whatever the robot or the layout. Compute it once per episode (after
    the reset) for a steady video.

    Args:
        model: The compiled model.
        data: Its data (positions current, e.g. after ``reset``).
        view: A name of :data:`VIEWS`.
        aspect: Image width / height.
        margin: Extra distance, as a fraction, around the tightest fit (room
            for an arm swinging its elbow out while it moves).

    Returns:
        A ``mujoco.MjvCamera`` to pass as ``camera`` to :class:`SceneRenderer`.

    Raises:
        RenderError: ``view`` is not a name of :data:`VIEWS`.
    """
    if view not in VIEWS:
        raise RenderError(f"no view {view!r} (use one of {', '.join(VIEWS)})")
    az, el = (math.radians(a) for a in VIEWS[view])
    forward = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az),
                        math.sin(el)])
    right = np.array([math.sin(az), -math.cos(az), 0.0])
    up = np.cross(right, forward)
    tan_v = math.tan(math.radians(float(model.vis.global_.fovy)) / 2)
    tan_h = tan_v * aspect
    points = _scene_points(model, data)
    lookat = (points.min(0) + points.max(0)) / 2
    distance = 1.0
    # Fit, then shift the aim so the picture's extremes sit symmetrically (a
    # perspective view of a centred box is not centred); a few rounds settle it.
    for _ in range(4):
        rel = points - lookat
        x, y, z = rel @ right, rel @ up, rel @ forward
        # Point i is in the picture when |x| <= tan_h * (distance + z) (and so for y).
        distance = float(max((np.abs(x) / tan_h - z).max(), (np.abs(y) / tan_v - z).max()))
        depth = np.maximum(distance + z, 1e-6)
        u_mid = ((x / depth).max() + (x / depth).min()) / 2
        v_mid = ((y / depth).max() + (y / depth).min()) / 2
        lookat = lookat + (u_mid * right + v_mid * up) * distance
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    cam.lookat[:] = lookat
    cam.distance = distance * (1.0 + margin)
    cam.azimuth, cam.elevation = VIEWS[view]
    return cam


# ------------------------------------------------------------- segmentation
def segmentation_color(variable: str, index: int = 0) -> tuple[int, int, int]:
    """The fixed RGB colour of instance ``index`` of a variable in segmentation pictures.

    The hue comes from a hash of the variable's name (not Python's ``hash``,
    which changes from run to run), so a variable has the same colour in every
    run, seed and task; its instances are shades of it.
    """
    digest = hashlib.sha256(variable.encode("utf-8")).digest()
    hue = int.from_bytes(digest[:2], "big") / 65536.0
    saturation = 0.55 + 0.4 * digest[2] / 255.0
    value = 0.95 - 0.12 * (index % 4)
    r, g, b = colorsys.hsv_to_rgb(hue, saturation, value)
    return round(r * 255), round(g * 255), round(b * 255)


def colorize_segmentation(seg: np.ndarray, objects: Sequence[tuple[str, int]]) -> np.ndarray:
    """An RGB picture (height, width, 3) uint8 of a segmentation image.

    Args:
        seg: Object indices per pixel (:meth:`SceneRenderer.segmentation`).
        objects: (variable name, instance index) of each object index, in the
            scene's object order (``[(o.variable, o.index) for o in ...]``).

    Returns:
        Each object in :func:`segmentation_color` of its variable, the rest in
        :data:`SEGMENTATION_BACKGROUND`.
    """
    table = np.array([SEGMENTATION_BACKGROUND]
                     + [segmentation_color(v, i) for v, i in objects], dtype=np.uint8)
    seg = np.asarray(seg, dtype=np.int64)
    return table[np.where((seg >= 0) & (seg < len(objects)), seg + 1, 0)]


# -------------------------------------------------------------------- video
class VideoRecorder:
    """Collects RGB frames and writes them as an animated GIF or an H.264 MP4.

    The suffix decides: ``.gif`` (Pillow, through imageio) or ``.mp4`` (H.264 in
    yuv420p through PyAV, which any player reads; an odd width or height is
    padded by one black row or column). The file is written on :meth:`close`
    (or leaving the ``with`` block).

    Args:
        path: Output file (``.gif`` or ``.mp4``).
        fps: Frames per second.

    Raises:
        RenderError: unsupported suffix or fps not positive.
    """

    def __init__(self, path: str | Path, fps: float = DEFAULT_FPS) -> None:
        path = Path(path)
        if path.suffix.lower() not in (".gif", ".mp4"):
            raise RenderError(f"video path {str(path)!r} must end in .gif or .mp4")
        if not fps > 0:
            raise RenderError(f"fps must be positive, got {fps}")
        self.path = path
        self.fps = float(fps)
        self.frames: list[np.ndarray] = []

    def append(self, frame: np.ndarray) -> None:
        """Add one RGB frame (height, width, 3) uint8; all frames must share a shape.

        Raises:
            RenderError: the frame's shape differs from the first frame's.
        """
        frame = np.asarray(frame)
        if frame.ndim != 3 or frame.shape[2] != 3:
            raise RenderError(f"a frame must be (height, width, 3), got {frame.shape}")
        if self.frames and frame.shape != self.frames[0].shape:
            raise RenderError(f"frame shape {frame.shape} differs from the first "
                              f"{self.frames[0].shape}")
        self.frames.append(frame.astype(np.uint8, copy=True))

    def close(self) -> Path | None:
        """Write the file (nothing if no frame was added).

        Returns:
            The path written, or None.
        """
        if not self.frames:
            return None
        import imageio.v3 as iio

        self.path.parent.mkdir(parents=True, exist_ok=True)
        if self.path.suffix.lower() == ".gif":
            # Pillow's GIF writer: duration per frame in ms; loop forever.
            iio.imwrite(self.path, np.stack(self.frames), duration=1000.0 / self.fps, loop=0)
        else:
            _write_mp4(self.path, self.frames, self.fps)
        self.frames = []
        return self.path

    def __enter__(self) -> VideoRecorder:
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        self.close()


def _write_mp4(path: Path, frames: list[np.ndarray], fps: float) -> None:
    """H.264 (yuv420p) MP4 of ``frames`` through PyAV; odd sizes padded to even."""
    from fractions import Fraction

    import av

    height, width = frames[0].shape[:2]
    even_h, even_w = height + height % 2, width + width % 2
    with av.open(str(path), mode="w") as container:
        stream = container.add_stream("libx264", rate=Fraction(fps).limit_denominator(1000))
        stream.width, stream.height, stream.pix_fmt = even_w, even_h, "yuv420p"
        for frame in frames:
            if (even_h, even_w) != (height, width):
                frame = np.pad(frame, ((0, even_h - height), (0, even_w - width), (0, 0)))
            for packet in stream.encode(av.VideoFrame.from_ndarray(frame, format="rgb24")):
                container.mux(packet)
        for packet in stream.encode():
            container.mux(packet)
