"""Observation cameras: pinhole intrinsics, poses, and RGB / depth / segmentation images.

The default rig mirrors Ravens/CLIPort (RealSense D415-like): three cameras, front
at (1.0, 0, 0.75) tilted pi/4 down, left at (0, 0.5, 0.75) and right at
(0, -0.5, 0.75) tilted pi/4.5, all 640 x 480 with fx = fy = 450, cx = 320,
cy = 240. Their orientations are Ravens' PyBullet Euler angles; the camera frame
is OpenCV's (x right, y down, z forward), which is what the height-map fusion
back-projects through.

These cameras are not in the compiled model: each image is rendered from the
free camera after overwriting the renderer's GL camera (pose and frustum), so any
camera and intrinsics can be rendered from any scene (and from a replayed state)
without recompiling. Depth is metres along the optical axis (MuJoCo's near and
far planes are kept, so ``mujoco.Renderer``'s linearisation stays right).
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass, replace
from types import TracebackType

import mujoco
import numpy as np
from scipy.spatial.transform import Rotation

from factask.sim.build.parts import MARKER_GROUP
from factask.vocabulary.errors import FactaskError

#: Ravens' image size (width, height) and intrinsics (fx, fy, cx, cy) in pixels.
RAVENS_SIZE = (640, 480)
RAVENS_INTRINSICS = (450.0, 450.0, 320.0, 240.0)
#: Segmentation value of pixels that show no object (table, floor, robot).
BACKGROUND = 0


class CameraError(FactaskError, ValueError):
    """A camera asked for wrongly (bad size, unknown name)."""


@dataclass(frozen=True)
class CameraSpec:
    """One pinhole camera.

    Attributes:
        name: Camera name (image keys use it).
        position: Optical centre in the world (m).
        rotation: 3x3 camera-to-world rotation, columns = the OpenCV camera axes
            (x right, y down, z forward) in world coordinates.
        width: Image width (pixels).
        height: Image height (pixels).
        fx: Focal length along x (pixels).
        fy: Focal length along y (pixels).
        cx: Principal point x (pixels from the left edge).
        cy: Principal point y (pixels from the top edge).
    """

    name: str
    position: tuple[float, float, float]
    rotation: tuple[tuple[float, float, float], ...]
    width: int = RAVENS_SIZE[0]
    height: int = RAVENS_SIZE[1]
    fx: float = RAVENS_INTRINSICS[0]
    fy: float = RAVENS_INTRINSICS[1]
    cx: float = RAVENS_INTRINSICS[2]
    cy: float = RAVENS_INTRINSICS[3]

    @property
    def matrix(self) -> np.ndarray:
        """The 3x3 camera-to-world rotation as an array."""
        return np.asarray(self.rotation, dtype=float)

    @property
    def intrinsics(self) -> np.ndarray:
        """The 3x3 intrinsic matrix K."""
        return np.array([[self.fx, 0.0, self.cx], [0.0, self.fy, self.cy], [0.0, 0.0, 1.0]])

    def resized(self, width: int, height: int) -> CameraSpec:
        """The same camera at another resolution (intrinsics scaled, field of view kept).

        Raises:
            CameraError: width or height not positive.
        """
        if width <= 0 or height <= 0:
            raise CameraError(f"camera {self.name!r}: size must be positive, got "
                              f"{width}x{height} (fix: e.g. width=64, height=48)")
        sx, sy = width / self.width, height / self.height
        return replace(self, width=int(width), height=int(height), fx=self.fx * sx,
                       fy=self.fy * sy, cx=self.cx * sx, cy=self.cy * sy)


def _ravens_rotation(euler: tuple[float, float, float]) -> tuple[tuple[float, ...], ...]:
    # PyBullet's getQuaternionFromEuler is scipy's extrinsic "xyz".
    m = Rotation.from_euler("xyz", euler).as_matrix()
    return tuple(tuple(float(v) for v in row) for row in m)


def ravens_cameras(width: int = RAVENS_SIZE[0], height: int = RAVENS_SIZE[1]
                   ) -> tuple[CameraSpec, ...]:
    """Ravens' front, left and right cameras, at ``width`` x ``height``.

    Raises:
        CameraError: width or height not positive.
    """
    cams = (
        CameraSpec("front", (1.0, 0.0, 0.75), _ravens_rotation((np.pi / 4, np.pi, -np.pi / 2))),
        CameraSpec("left", (0.0, 0.5, 0.75), _ravens_rotation((np.pi / 4.5, np.pi, np.pi / 4))),
        CameraSpec("right", (0.0, -0.5, 0.75),
                   _ravens_rotation((np.pi / 4.5, np.pi, 3 * np.pi / 4))),
    )
    return tuple(c.resized(width, height) for c in cams)


def segmentation_table(geom_object: np.ndarray) -> np.ndarray:
    """Geom id -> segmentation id: object index + 1, :data:`BACKGROUND` elsewhere."""
    table = np.asarray(geom_object, dtype=np.int64)
    return np.where(table >= 0, table + 1, BACKGROUND).astype(np.int32)


class CameraRig:
    """Renders :class:`CameraSpec` images of one model (one GL context per image size).

    Args:
        model: The compiled model.
        cameras: The cameras.
        geom_object: Geom id -> object index (``CompiledScene.geom_object``); the
            segmentation shows object index + 1, 0 elsewhere.
        show_markers: Draw the translucent goal markers in RGB images.

    Raises:
        CameraError: no camera, duplicate names, or a size beyond the model's
            offscreen buffer.
    """

    def __init__(self, model: mujoco.MjModel, cameras: tuple[CameraSpec, ...],
                 geom_object: np.ndarray, show_markers: bool = False) -> None:
        if not cameras:
            raise CameraError("cameras: give at least one camera")
        names = [c.name for c in cameras]
        if len(set(names)) != len(names):
            raise CameraError(f"cameras: names must differ, got {names}")
        max_w, max_h = int(model.vis.global_.offwidth), int(model.vis.global_.offheight)
        for c in cameras:
            if not (0 < c.width <= max_w and 0 < c.height <= max_h):
                raise CameraError(f"camera {c.name!r}: {c.width}x{c.height} outside the "
                                  f"offscreen buffer {max_w}x{max_h} (fix: a smaller size)")
        self.model = model
        self.cameras = tuple(cameras)
        self._seg_table = segmentation_table(geom_object)
        self._renderers: dict[tuple[int, int], mujoco.Renderer] = {}
        self._option = mujoco.MjvOption()
        self._option.geomgroup[MARKER_GROUP] = 1 if show_markers else 0
        self._hidden = mujoco.MjvOption()
        self._hidden.geomgroup[MARKER_GROUP] = 0

    def camera(self, name: str) -> CameraSpec:
        """The camera called ``name``.

        Raises:
            CameraError: no such camera.
        """
        for c in self.cameras:
            if c.name == name:
                return c
        raise CameraError(f"no camera {name!r}; cameras: {[c.name for c in self.cameras]}")

    def _renderer(self, cam: CameraSpec) -> mujoco.Renderer:
        key = (cam.width, cam.height)
        if key not in self._renderers:
            from factask.sim.render.offscreen import ensure_headless_gl

            ensure_headless_gl()
            self._renderers[key] = mujoco.Renderer(self.model, height=cam.height,
                                                   width=cam.width)
            if len(self._renderers) == 1:
                # Registered after the GL backend's own exit hook (made with the first
                # context), so contexts are freed before interpreter shutdown tears EGL down.
                weakref.finalize(self, CameraRig._close_all, self._renderers)
        return self._renderers[key]

    def _update(self, r: mujoco.Renderer, data: mujoco.MjData, cam: CameraSpec,
                option: mujoco.MjvOption) -> None:
        r.update_scene(data, -1, option)
        rot = cam.matrix
        forward, up = rot[:, 2], -rot[:, 1]
        for gl in (r.scene.camera[0], r.scene.camera[1]):
            near = gl.frustum_near
            gl.pos[:] = cam.position
            gl.forward[:] = forward
            gl.up[:] = up
            # The frustum at the near plane from the pinhole intrinsics (row 0 is top).
            left, right = -near * cam.cx / cam.fx, near * (cam.width - cam.cx) / cam.fx
            gl.frustum_top = near * cam.cy / cam.fy
            gl.frustum_bottom = -near * (cam.height - cam.cy) / cam.fy
            gl.frustum_center = 0.5 * (left + right)
            gl.frustum_width = 0.5 * (right - left)
            gl.orthographic = 0

    def rgb(self, data: mujoco.MjData, name: str) -> np.ndarray:
        """RGB image (height, width, 3) uint8 of camera ``name``."""
        cam = self.camera(name)
        r = self._renderer(cam)
        self._update(r, data, cam, self._option)
        return r.render().copy()

    def depth(self, data: mujoco.MjData, name: str) -> np.ndarray:
        """Depth (height, width) float32, metres along the optical axis."""
        cam = self.camera(name)
        r = self._renderer(cam)
        r.enable_depth_rendering()
        try:
            self._update(r, data, cam, self._hidden)
            return r.render().astype(np.float32)
        finally:
            r.disable_depth_rendering()

    def segmentation(self, data: mujoco.MjData, name: str) -> np.ndarray:
        """Segmentation (height, width) int32: object index + 1, 0 elsewhere."""
        cam = self.camera(name)
        r = self._renderer(cam)
        r.enable_segmentation_rendering()
        try:
            self._update(r, data, cam, self._hidden)
            seg = r.render()
        finally:
            r.disable_segmentation_rendering()
        ids, types = seg[..., 0].astype(np.int64), seg[..., 1]
        geom = np.where(types == mujoco.mjtObj.mjOBJ_GEOM, ids, -1)
        table = self._seg_table
        return np.where(geom >= 0, table[np.clip(geom, 0, len(table) - 1)],
                        BACKGROUND).astype(np.int32)

    @staticmethod
    def _close_all(renderers: dict[tuple[int, int], mujoco.Renderer]) -> None:
        for r in renderers.values():
            r.close()
        renderers.clear()

    def close(self) -> None:
        """Free every GL context (safe to call twice)."""
        CameraRig._close_all(self._renderers)

    def __enter__(self) -> CameraRig:
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        self.close()


def points_from_depth(depth: np.ndarray, cam: CameraSpec) -> np.ndarray:
    """World points (height, width, 3) of every pixel of a depth image of ``cam``.

    Pixel (u, v) is taken at its centre (u + 0.5, v + 0.5): the GL frustum puts the
    principal point on pixel edges.
    """
    h, w = depth.shape
    u, v = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
    z = depth.astype(np.float64)
    pts = np.stack([(u - cam.cx) * z / cam.fx, (v - cam.cy) * z / cam.fy, z], axis=-1)
    return pts @ cam.matrix.T + np.asarray(cam.position)
