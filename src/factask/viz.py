"""Pictures of task graphs (the bipartite variable/factor graph as a PNG) and
videos of episodes a user can choose (camera view, size, fps, a caption).

Variables are circles in their palette colour (left column); factors are squares
(right column) in their execution order, numbered, with the order numbers of the
factors each one waits for; a milestone (counts once achieved) is a diamond, a
final factor (must hold at the end) a square. Edges: solid to the variables a factor moves, dashed
to its anchors, dotted to the rest of its scope.

Uses :class:`matplotlib.figure.Figure` directly (no pyplot), so it works
headless and never touches the global backend. :class:`EpisodeVideo` imports
the simulator only when it records (drawing a graph needs no MuJoCo).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from factask.graph import GraphValidationError, TaskGraph, rgba

_X_VAR = 0.0
_X_FAC = 1.0
_ROW = 0.6  # inches per node row
_FONT = 8


def _factor_rows(graph: TaskGraph) -> dict[str, int]:
    """Factor name -> row, in dependency order (declaration order if cyclic)."""
    try:
        order = graph.factor_order()
    except GraphValidationError:  # a cyclic graph is still drawn, as declared
        order = graph.factor_names()
    return {name: i for i, name in enumerate(order)}


def _variable_rows(graph: TaskGraph, frow: dict[str, int]) -> dict[str, int]:
    """Variable name -> row: sorted by the mean row of their factors, which keeps
    edges short and mostly uncrossed (declaration order breaks ties)."""
    touching: dict[str, list[int]] = {v: [] for v in graph.variable_names()}
    for f in graph.factors:
        for v in f.scope_names:
            if v in touching:
                touching[v].append(frow.get(f.name, 0))
    n = max(len(frow), 1)

    def key(item: tuple[int, str]) -> tuple[float, int]:
        i, v = item
        rows = touching[v]
        return (sum(rows) / len(rows) if rows else float(n), i)

    ordered = sorted(enumerate(graph.variable_names()), key=key)
    return {v: i for i, (_, v) in enumerate(ordered)}


def _ys(count: int, rows: int) -> list[float]:
    """Vertical positions of ``count`` nodes centred in a column of ``rows`` rows."""
    offset = (rows - count) / 2.0
    return [rows - 1 - (offset + i) for i in range(count)]


def graph_figure(graph: TaskGraph, title: str | None = None) -> Figure:
    """A matplotlib figure of ``graph``'s bipartite structure.

    Args:
        graph: The task graph (need not be valid; unknown scope names are skipped).
        title: Figure title; default the task name and description.
    """
    frow = _factor_rows(graph)
    vrow = _variable_rows(graph, frow)
    rows = max(len(frow), len(vrow), 1)
    fig = Figure(figsize=(11.0, max(3.0, _ROW * rows + 1.4)), dpi=100)
    ax = fig.add_axes((0.0, 0.0, 1.0, 0.88 if rows > 2 else 0.8))
    ax.set_axis_off()
    ax.set_xlim(-0.6, 3.0)
    ax.set_ylim(-0.8, rows - 0.2)

    vy = dict(zip(sorted(vrow, key=vrow.__getitem__), _ys(len(vrow), rows), strict=True))
    fy = dict(zip(sorted(frow, key=frow.__getitem__), _ys(len(frow), rows), strict=True))
    variables = {v.name: v for v in graph.variables}

    # Edges first, so nodes sit on top of them.
    for f in graph.factors:
        moved, anchors = set(f.moved()), set(f.anchors())
        for v in f.scope_names:
            if v not in vy or f.name not in fy:
                continue
            style = "-" if v in moved else "--" if v in anchors else ":"
            ax.plot([_X_VAR, _X_FAC], [vy[v], fy[f.name]], style, color="0.45", lw=1.1,
                    zorder=1)

    for name, y in vy.items():
        v = variables[name]
        ax.scatter([_X_VAR], [y], s=420, marker="o", color=[rgba(v.color)],
                   edgecolors="black", linewidths=1.6 if v.is_fixed else 0.8, zorder=3)
        count = f" x{v.count}" if v.count > 1 else ""
        fixed = ", fixed" if v.is_fixed else ""
        ax.text(_X_VAR - 0.09, y, f"{name}\n{v.kind}{count} ({v.color}{fixed})",
                ha="right", va="center", fontsize=_FONT, zorder=4)

    deps = _dependencies(graph)
    for f in graph.factors:
        if f.name not in fy:
            continue
        y = fy[f.name]
        ax.scatter([_X_FAC], [y], s=480 if f.milestone else 380,
                   marker="D" if f.milestone else "s", color="#f3efe0", edgecolors="black",
                   linewidths=0.8, zorder=3)
        ax.text(_X_FAC, y, str(frow[f.name] + 1), ha="center", va="center",
                fontsize=_FONT, weight="bold", zorder=4)
        waits = sorted(frow[d] + 1 for d in deps.get(f.name, ()) if d in frow)
        after = f"  after {', '.join(map(str, waits))}" if waits else ""
        desc = f.description if len(f.description) <= 84 else f.description[:81] + "..."
        kind = ", milestone" if f.milestone else ""
        ax.text(_X_FAC + 0.09, y,
                f"{f.name}  [{f.goal.type}{kind}, w={f.weight:.2f}]{after}\n{desc}",
                ha="left", va="center", fontsize=_FONT, zorder=4)

    head = title if title is not None else graph.name
    sub = "" if title is not None or not graph.description else graph.description
    if len(sub) > 150:
        sub = sub[:147] + "..."
    fig.suptitle(head, fontsize=11, weight="bold", y=0.985)
    if sub:
        fig.text(0.5, 0.985 - 0.35 / fig.get_figheight(), sub, ha="center", va="top",
                 fontsize=_FONT, wrap=True)
    ax.legend(
        handles=[Line2D([], [], ls="-", color="0.45", label="moves"),
                 Line2D([], [], ls="--", color="0.45", label="anchored to"),
                 Line2D([], [], ls=":", color="0.45", label="other scope"),
                 Line2D([], [], ls="", marker="s", color="black", mfc="#f3efe0",
                        label="final: holds at the end"),
                 Line2D([], [], ls="", marker="D", color="black", mfc="#f3efe0",
                        label="milestone: counts once reached")],
        loc="lower left", fontsize=_FONT - 1, frameon=False, ncol=5,
    )
    return fig


def _dependencies(graph: TaskGraph) -> dict[str, list[str]]:
    """Factor -> the factors that must come before it (explicit and anchored)."""
    d = graph.dependency_graph()
    return {n: sorted(d.predecessors(n)) for n in d.nodes}


def draw_graph(graph: TaskGraph, path: str | Path, title: str | None = None) -> Path:
    """Draw ``graph`` to a PNG file at ``path`` (parent folders are created).

    The file carries no timestamp or software version, so the same graph gives
    the same bytes with the same matplotlib.

    Returns:
        The path written.
    """
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig = graph_figure(graph, title=title)
    fig.savefig(out, format="png", metadata={"Software": None})
    return out


# ------------------------------------------------------------------ episode videos
#: Simulated seconds one second of video shows: 2.4, so a frame every 0.12 s of
#: simulation at 20 fps (a higher fps gives smoother, not faster, video).
VIDEO_SPEED = 2.4
#: Frames per second a video may have.
FPS_RANGE = (1.0, 50.0)


def caption_text(graph: TaskGraph, status: Any) -> tuple[str, str, float]:
    """What the caption says now: the current factor, its language goal, its progress.

    The current factor is the first, in the graph's factor order, that is neither
    satisfied nor (a milestone) reached: the oracle works through them in that order.

    Args:
        graph: The task.
        status: Its :class:`~factask.sim.layout.checks.TaskStatus` now.

    Returns:
        (title "k/n name", the factor's language goal, its progress in [0, 1]);
        when every factor is done, ("done", the task's reward, 1.0).
    """
    order = graph.factor_order()
    for k, name in enumerate(order, 1):
        st = status.factors.get(name)
        if st is None or not (st.satisfied or name in status.reached):
            progress = float(st.progress) if st is not None else 0.0
            return f"{k}/{len(order)} {name}", graph.factor(name).description, progress
    return "done", f"every subtask done: reward {status.reward:.2f}", 1.0


def _fit(draw: Any, text: str, font: Any, width: float) -> str:
    """``text`` cut with an ellipsis to fit ``width`` pixels."""
    if draw.textlength(text, font=font) <= width:
        return text
    while text and draw.textlength(text + "...", font=font) > width:
        text = text[:-1]
    return text + "..."


def caption_band(width: int, title: str, text: str, progress: float) -> np.ndarray:
    """A caption strip (band height, width, 3) uint8 to stack under a frame.

    Two lines of white text on dark grey (the title with the progress in per cent
    at its right, then the language goal, cut to fit) over a thin progress bar.

    Args:
        width: Frame width in pixels.
        title: First line (e.g. "2/4 stack-middle").
        text: Second line (the language goal).
        progress: In [0, 1]; the bar's length and the per cent shown.
    """
    from PIL import Image, ImageDraw, ImageFont

    px = _caption_font_px(width)
    band_h = caption_height(width)
    try:
        font = ImageFont.load_default(size=px)
    except (TypeError, OSError):  # a Pillow without FreeType: the fixed bitmap font
        font = ImageFont.load_default()
    image = Image.new("RGB", (width, band_h), (24, 24, 24))
    draw = ImageDraw.Draw(image)
    pad = max(2, px // 3)
    share = f"{min(max(progress, 0.0), 1.0):.0%}"
    right = draw.textlength(share, font=font)
    draw.text((width - pad - right, pad), share, fill=(255, 255, 255), font=font)
    draw.text((pad, pad), _fit(draw, title, font, width - 3 * pad - right),
              fill=(255, 255, 255), font=font)
    draw.text((pad, pad + px + pad // 2), _fit(draw, text, font, width - 2 * pad),
              fill=(210, 210, 210), font=font)
    bar = max(2, px // 5)
    draw.rectangle((0, band_h - bar, round(width * min(max(progress, 0.0), 1.0)), band_h),
                   fill=(80, 200, 120))
    return np.asarray(image, dtype=np.uint8)


def _caption_font_px(width: int) -> int:
    """Caption font size: about 26 characters' height across the frame, 9 to 28 px."""
    return max(9, min(28, width // 26))


def caption_height(width: int) -> int:
    """Height in pixels of the caption band of a frame ``width`` pixels wide."""
    px = _caption_font_px(width)
    return 2 * px + 2 * max(2, px // 3) + max(2, px // 5) + px // 2


class EpisodeVideo:
    """Records an oracle episode as MP4 (H.264) or GIF, from a chosen camera, at a
    chosen size and fps, optionally with a caption of the current subtask.

    Attach it to an environment, run the episode on that environment, finish::

        video = EpisodeVideo("run.mp4", size=(640, 480), camera="front", caption=True)
        video.attach(env)
        try:
            run_episode(graph, seed, env=env)
        finally:
            info = video.finish()

    A framed view (:data:`factask.sim.render.offscreen.VIEWS`) is aimed once, at the first
    frame, from the scene's bounds (robot and objects whole); any other name is a
    camera of the model. Frames are taken every ``VIDEO_SPEED / fps`` simulated
    seconds while actions run, plus one of the final state. With a caption, the
    scene takes the top of the frame and the caption band the bottom, so the
    frame keeps the asked size and the caption hides nothing.

    Args:
        path: ``.mp4`` or ``.gif`` file.
        fps: Frames per second, within :data:`FPS_RANGE`.
        size: (width, height) of the frames.
        camera: A view name or a camera of the model.
        caption: Draw the current factor, its language goal and its progress.

    Raises:
        factask.sim.render.offscreen.RenderError: a bad suffix, fps or size (before any work).
    """

    def __init__(self, path: str | Path, fps: float = 20.0, size: tuple[int, int] = (320, 240),
                 camera: str = "front", caption: bool = False) -> None:
        from factask.sim.render.offscreen import RenderError, VideoRecorder

        if not FPS_RANGE[0] <= fps <= FPS_RANGE[1]:
            raise RenderError(f"fps {fps:g} outside {FPS_RANGE[0]:g}..{FPS_RANGE[1]:g}")
        width, height = size
        scene_h = height - (caption_height(width) if caption else 0)
        if width < 16 or scene_h < 16:
            raise RenderError(f"video size {width}x{height} too small"
                              + (" for a caption" if caption else "") + " (fix: a larger --size)")
        self.recorder = VideoRecorder(path, fps)
        self.fps, self.size = float(fps), (width, height)
        self.camera, self.caption = camera, caption
        self._scene_h = scene_h
        self._env: Any = None
        self._renderer: Any = None
        self._view: Any = None
        self._next_time = 0.0
        self._actions = -1
        self._band: np.ndarray | None = None
        self.frames = 0

    def attach(self, env: Any) -> None:
        """Record ``env``'s next actions (sets its ``frame_callback``).

        The renderer is made here, so a machine that cannot render says so
        before the episode runs.

        Raises:
            factask.sim.render.offscreen.RenderError: no GL context, or a size the model's
                offscreen buffer cannot hold.
        """
        from factask.sim.render.offscreen import SceneRenderer

        if self._renderer is None:
            self._renderer = SceneRenderer(env.model, self.size[0], self._scene_h)
        self._env = env
        env.frame_callback = self._on_step

    def _on_step(self) -> None:
        env = self._env
        if self._view is None or env.data.time + 1e-9 >= self._next_time:
            self._frame()

    def _frame(self) -> None:
        from factask.sim.render.offscreen import VIEWS, framed_camera

        env = self._env
        if self._view is None:  # aimed once, at the first frame: a steady picture
            self._view = (framed_camera(env.model, env.data, self.camera,
                                        self.size[0] / self._scene_h)
                          if self.camera in VIEWS else self.camera)
        frame = self._renderer.rgb(env.data, self._view)
        if self.caption:
            if self._band is None or env.actions_taken != self._actions:
                # The status changes only when an action ends: check once per action.
                self._actions = env.actions_taken
                self._band = caption_band(self.size[0], *caption_text(env.graph, env.status()))
            frame = np.concatenate([frame, self._band], axis=0)
        self.recorder.append(frame)
        self.frames += 1
        self._next_time = float(env.data.time) + VIDEO_SPEED / self.fps

    def finish(self) -> dict[str, Any]:
        """Add the final frame, detach, write the file.

        Returns:
            What was written: path, frames, fps, size [width, height], camera, caption.
        """
        try:
            if self._env is not None and self._renderer is not None:
                self._env.frame_callback = None
                self._actions = -1  # the final frame's caption: the final status
                self._frame()
        finally:
            if self._renderer is not None:
                self._renderer.close()
                self._renderer = None
            path = self.recorder.close()
        return {"path": str(path or self.recorder.path), "frames": self.frames, "fps": self.fps,
                "size": list(self.size), "camera": self.camera, "caption": self.caption}
