"""Headless rendering: RGB, depth, segmentation and video files."""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import imageio.v3 as iio
import mujoco
import numpy as np
import pytest

import factask.sim  # noqa: F401  (headless GL backend before MuJoCo's GL loads)
from factask.geometry import Pose
from factask.graph import TaskGraph
from factask.sim.build.compile import CompiledScene, compile_graph, set_object_pose
from factask.sim.build.mjcf import FRONT_CAMERA, TOP_CAMERA, TOP_CAMERA_HEIGHT
from factask.sim.render.offscreen import (
    BACKGROUND_ID,
    RenderError,
    SceneRenderer,
    VideoRecorder,
    active_gl_backend,
    render_depth,
    render_rgb,
    render_segmentation,
)

WIDTH, HEIGHT = 160, 120


@pytest.fixture(scope="module")
def scene() -> CompiledScene:
    graph = TaskGraph.model_validate({
        "name": "render-test",
        "variables": [
            {"name": "blocks", "kind": "block", "color": "red", "count": 2},
            {"name": "bowl", "kind": "bowl", "color": "green"},
            {"name": "pad", "kind": "kit", "color": "blue"},
        ],
        "factors": [{"name": "blocks_in_bowl",
                     "goal": {"type": "inside", "objects": ["blocks"], "container": "bowl"}}],
    })
    return compile_graph(graph, robot=None)


@pytest.fixture(scope="module")
def renderer(scene: CompiledScene) -> Iterator[SceneRenderer]:
    try:
        r = SceneRenderer(scene.model, WIDTH, HEIGHT, scene.geom_object)
    except RenderError as exc:  # pragma: no cover - machines without any GL
        pytest.skip(f"no headless GL here: {exc}")
    with r:
        yield r


def test_backend_is_headless() -> None:
    assert active_gl_backend() in ("egl", "osmesa")


_LATE_IMPORT = """
import mujoco  # before factask.sim: MuJoCo picks GLFW, which needs a display
import factask.sim
from factask.sim.render.offscreen import active_gl_backend, render_rgb
m = mujoco.MjModel.from_xml_string('<mujoco><worldbody><light pos="0 0 1"/>'
    '<geom type="sphere" size=".1" rgba="1 0 0 1"/></worldbody></mujoco>')
d = mujoco.MjData(m); mujoco.mj_forward(m, d)
img = render_rgb(m, d, -1, 32, 24)
print(active_gl_backend(), img.shape, int(img.max()))
"""


def test_renders_even_if_mujoco_was_imported_first() -> None:
    env = {k: v for k, v in os.environ.items() if k not in ("MUJOCO_GL", "DISPLAY")}
    out = subprocess.run([sys.executable, "-c", _LATE_IMPORT], env=env, capture_output=True,
                         text=True, timeout=120, check=False)
    assert out.returncode == 0, out.stderr
    backend, *rest = out.stdout.split()
    assert backend in ("egl", "osmesa")
    assert "(24, 32, 3)" in " ".join(rest)


@pytest.mark.parametrize("camera", [TOP_CAMERA, FRONT_CAMERA])
def test_rgb_has_shape_and_content(scene: CompiledScene, renderer: SceneRenderer,
                                   camera: str) -> None:
    img = renderer.rgb(scene.make_data(), camera)
    assert img.shape == (HEIGHT, WIDTH, 3) and img.dtype == np.uint8
    assert img.std() > 5.0
    assert len(np.unique(img.reshape(-1, 3), axis=0)) > 10


def test_depth_is_plausible(scene: CompiledScene, renderer: SceneRenderer) -> None:
    depth = renderer.depth(scene.make_data(), TOP_CAMERA)
    assert depth.shape == (HEIGHT, WIDTH)
    # Top camera looks straight down from TOP_CAMERA_HEIGHT: the table is that far,
    # objects a few centimetres nearer.
    assert np.median(depth) == pytest.approx(TOP_CAMERA_HEIGHT, abs=0.01)
    assert TOP_CAMERA_HEIGHT - 0.1 < depth.min() < TOP_CAMERA_HEIGHT - 0.001


def test_segmentation_shows_every_object(scene: CompiledScene,
                                         renderer: SceneRenderer) -> None:
    seg = renderer.segmentation(scene.make_data(), TOP_CAMERA)
    assert seg.shape == (HEIGHT, WIDTH)
    ids = set(np.unique(seg).tolist())
    assert BACKGROUND_ID in ids
    assert ids - {BACKGROUND_ID} == set(range(len(scene.objects)))


def test_segmentation_pixels_match_rgb_colour(scene: CompiledScene,
                                              renderer: SceneRenderer) -> None:
    data = scene.make_data()
    seg = renderer.segmentation(data, TOP_CAMERA)
    rgb = renderer.rgb(data, TOP_CAMERA, show_markers=False).astype(float)
    bowl = scene.object_names.index("bowl")
    mean = rgb[seg == bowl].mean(axis=0)
    assert mean[1] > mean[0] and mean[1] > mean[2]  # the bowl is green


def test_one_shot_helpers(scene: CompiledScene) -> None:
    data = scene.make_data()
    assert render_rgb(scene.model, data, TOP_CAMERA, 64, 48).shape == (48, 64, 3)
    assert render_depth(scene.model, data, TOP_CAMERA, 64, 48).shape == (48, 64)
    seg = render_segmentation(scene.model, data, TOP_CAMERA, 64, 48, scene.geom_object)
    assert seg.min() >= BACKGROUND_ID


def test_bad_camera_and_size(scene: CompiledScene, renderer: SceneRenderer) -> None:
    with pytest.raises(RenderError, match="no camera 'side'"):
        renderer.rgb(scene.make_data(), "side")
    with pytest.raises(RenderError, match="offscreen buffer"):
        SceneRenderer(scene.model, 5000, 100)


def test_video_gif_is_written(tmp_path: Path, scene: CompiledScene,
                              renderer: SceneRenderer) -> None:
    path = tmp_path / "clip.gif"
    data = scene.make_data()
    block = scene.objects["blocks__0"]
    with VideoRecorder(path, fps=10) as video:
        for i in range(3):
            # Frames must differ: GIF writers merge identical consecutive frames.
            set_object_pose(scene.model, data, block, Pose.from_xyz_yaw(0.4 + 0.1 * i, 0, 0.02))
            mujoco.mj_forward(scene.model, data)
            video.append(renderer.rgb(data))
    frames = iio.imread(path, index=None)
    assert frames.shape[0] == 3 and frames.shape[1:3] == (HEIGHT, WIDTH)


def test_mp4_is_h264_and_its_frames_read_back(tmp_path: Path) -> None:
    import av

    path = tmp_path / "clip.mp4"
    with VideoRecorder(path, fps=12) as video:
        for shade in (0, 128, 255):
            video.append(np.full((15, 21, 3), shade, np.uint8))  # odd sizes: padded
    with av.open(str(path)) as container:
        stream = container.streams.video[0]
        assert stream.codec_context.name == "h264"
        frames = [f.to_ndarray(format="rgb24") for f in container.decode(stream)]
    assert len(frames) == 3 and frames[0].shape == (16, 22, 3)
    assert [round(float(f[:15, :21].mean())) for f in frames] == pytest.approx(
        [0, 128, 255], abs=3)


def test_video_rejects_bad_input(tmp_path: Path) -> None:
    with pytest.raises(RenderError, match=r"\.gif or \.mp4"):
        VideoRecorder(tmp_path / "clip.avi")
    video = VideoRecorder(tmp_path / "clip.gif")
    video.append(np.zeros((8, 8, 3), np.uint8))
    with pytest.raises(RenderError, match="differs"):
        video.append(np.zeros((4, 8, 3), np.uint8))
    assert VideoRecorder(tmp_path / "empty.gif").close() is None


@pytest.mark.parametrize("robot", ["ur10e", "floating"])
def test_framed_views_show_the_robot_and_every_object_whole(robot: str) -> None:
    from factask.library import get_task
    from factask.sim.env import FactaskEnv
    from factask.sim.render.offscreen import VIEWS, framed_camera

    env = FactaskEnv(get_task("stack-block-pyramid"), robot=robot)
    try:
        env.reset(seed=0)
        model = env.model
        moving = {g for g in range(model.ngeom) if model.geom_bodyid[g] != 0}
        robot_geoms = {g for g in moving if model.body(model.geom_bodyid[g]).name
                       not in env.scene.objects and not model.body(model.geom_bodyid[g])
                       .name.startswith("goal:")}
        with SceneRenderer(model, 96, 72) as r:  # raw geom ids per pixel
            for view in VIEWS:
                seg = r.segmentation(env.data, framed_camera(model, env.data, view, 96 / 72))
                border = np.concatenate([seg[0], seg[-1], seg[:, 0], seg[:, -1]])
                cut = {int(g) for g in border if g in moving}
                assert not cut, f"{view}: geoms {cut} run off the picture"
                seen = set(np.unique(seg).tolist())
                assert robot_geoms & seen, f"{view}: no robot in the picture"
                objects = {g for g in moving if env.scene.geom_object[g] >= 0}
                assert len(objects & seen) >= len(env.object_names) // 2, view
    finally:
        env.close()


def test_framed_camera_rejects_an_unknown_view(scene: CompiledScene) -> None:
    from factask.sim.render.offscreen import framed_camera

    with pytest.raises(RenderError, match="no view 'side'"):
        framed_camera(scene.model, scene.make_data(), "side")


_SEG_COLOUR = ("from factask.sim.render.offscreen import segmentation_color as c; "
               "print(c('bowl'), c('b', 1))")


def test_segmentation_colours_are_fixed_per_variable_across_runs_and_seeds(
        tmp_path: Path) -> None:
    from typer.testing import CliRunner

    from factask.cli import app
    from factask.library import get_task
    from factask.sim.render.offscreen import colorize_segmentation, segmentation_color

    runs = {subprocess.run([sys.executable, "-c", _SEG_COLOUR], capture_output=True, text=True,
                           check=True, env={**os.environ, "PYTHONHASHSEED": str(k)}).stdout
            for k in (1, 2)}
    assert len(runs) == 1  # not Python's salted hash
    assert segmentation_color("bowl") != segmentation_color("blocks")
    assert segmentation_color("blocks", 1) != segmentation_color("blocks", 0)
    image = colorize_segmentation(np.array([[-1, 0, 1]]), [("bowl", 0), ("blocks", 0)])
    assert [tuple(p) for p in image[0][1:]] == [segmentation_color("bowl"),
                                              segmentation_color("blocks")]
    colours = []
    for seed in (0, 1):
        out = tmp_path / f"seg{seed}.png"
        result = CliRunner().invoke(app, ["render", "put-block-in-bowl", "-o", str(out),
                                          "--segmentation", "--size", "96x72", "--camera",
                                          "top", "--seed", str(seed)])
        assert result.exit_code == 0, result.output
        colours.append({tuple(p) for p in iio.imread(out).reshape(-1, 3).tolist()})
    expected = {segmentation_color(v.name) for v in get_task("put-block-in-bowl").variables}
    assert colours[0] == colours[1] and expected <= colours[0]


def test_the_arm_stays_whole_in_every_view_while_it_works() -> None:
    from factask.library import get_task
    from factask.sim.env import FactaskEnv
    from factask.sim.episode import run_episode
    from factask.sim.render.offscreen import VIEWS, framed_camera

    task = get_task("put-block-in-bowl")
    env = FactaskEnv(task, robot="ur10e")
    model, cams, cut, calls = env.model, {}, set(), [0]
    moving = np.flatnonzero(model.geom_bodyid != 0)
    with SceneRenderer(model, 48, 36) as r:

        def look() -> None:
            calls[0] += 1
            if not cams:  # aimed once, after the reset, as a video is
                cams.update({v: framed_camera(model, env.data, v, 48 / 36) for v in VIEWS})
            if calls[0] % 8:
                return
            for view, cam in cams.items():
                seg = r.segmentation(env.data, cam)
                border = np.concatenate([seg[0], seg[-1], seg[:, 0], seg[:, -1]])
                cut.update(f"{view}:{g}" for g in set(border.tolist()) & set(moving.tolist()))

        env.frame_callback = look
        try:
            assert run_episode(task, 0, robot="ur10e", env=env).success
        finally:
            env.close()
    assert calls[0] > 8 and not cut, f"geoms at the picture's edge: {sorted(cut)}"
