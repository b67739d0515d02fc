"""Task-graph pictures (factask.viz)."""

from __future__ import annotations

import struct
from pathlib import Path

from matplotlib.image import imread

from factask.graph import InZone, SubtaskFactor, TaskGraph
from factask.library import get_task
from factask.library.builders import var
from factask.viz import draw_graph, graph_figure

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == PNG_MAGIC
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def test_draw_graph_writes_a_valid_png(tmp_path: Path) -> None:
    out = draw_graph(get_task("stack-block-pyramid"), tmp_path / "sub" / "g.png")
    assert out == tmp_path / "sub" / "g.png"
    data = out.read_bytes()
    width, height = _png_size(data)
    assert width == 1100 and 300 <= height <= 1200
    pixels = imread(out)
    assert pixels.shape[:2] == (height, width)
    assert pixels.std() > 0.01  # something was drawn


def test_draw_graph_is_deterministic(tmp_path: Path) -> None:
    g = get_task("build-house")
    a = draw_graph(g, tmp_path / "a.png").read_bytes()
    b = draw_graph(g, tmp_path / "b.png", title=None).read_bytes()
    assert a == b


def test_figure_shows_every_node_and_the_order() -> None:
    g = get_task("stack-block-pyramid-seq")
    fig = graph_figure(g)
    texts = [t.get_text() for t in fig.axes[0].texts]
    for v in g.variable_names():
        assert any(t.startswith(v + "\n") for t in texts), v
    order = g.factor_order()
    for i, name in enumerate(order, 1):
        assert str(i) in texts
        label = next(t for t in texts if t.startswith(name + " "))
        if i > 1:
            assert f"after {i - 1}" in label
    # One edge line per (factor, scope variable) pair.
    n_edges = sum(len(f.scope_names) for f in g.factors)
    assert len(fig.axes[0].lines) == n_edges


def test_title_override_and_cyclic_graph_still_drawn(tmp_path: Path) -> None:
    red = var("red_block", "block", "red", (0.04, 0.04, 0.04))
    zone = var("zone", "zone", "green", (0.12, 0.12, 0.001))
    blue = var("blue_block", "block", "blue", (0.04, 0.04, 0.04))
    g = TaskGraph(
        name="cyclic",
        variables=[red, zone, blue],
        factors=[
            SubtaskFactor(name="a", description="a", goal=InZone(objects=["red_block"],
                                                                   zone="zone"),
                          weight=0.5, after=["b"]),
            SubtaskFactor(name="b", description="b", goal=InZone(objects=["blue_block"],
                                                                   zone="zone"),
                          weight=0.5, after=["a"]),
        ],
    )
    assert g.problems()  # invalid: the order has a cycle
    out = draw_graph(g, tmp_path / "c.png")
    _png_size(out.read_bytes())
    # A title given replaces the name and the description line.
    house = get_task("build-house")
    heads = [t.get_text() for t in graph_figure(house, title="my title").texts]
    assert "my title" in heads and house.description[:40] not in " ".join(heads)
    heads = [t.get_text() for t in graph_figure(house).texts]
    assert "build-house" in heads and any(house.description[:40] in h for h in heads)


def test_the_caption_names_the_first_unfinished_factor_and_its_progress() -> None:
    from types import SimpleNamespace as NS

    from factask.library import get_task
    from factask.viz import caption_text

    graph = get_task("towers-of-hanoi")
    order = graph.factor_order()
    status = NS(reward=0.3, reached=frozenset(order[:2]),
                factors={n: NS(satisfied=False, progress=0.25 if k == 2 else 0.0)
                         for k, n in enumerate(order)})
    title, goal, progress = caption_text(graph, status)
    assert title == f"3/{len(order)} {order[2]}" and progress == 0.25
    assert goal == graph.factor(order[2]).description
    done = NS(reward=1.0, reached=frozenset(order),
              factors={n: NS(satisfied=True, progress=1.0) for n in order})
    assert caption_text(graph, done)[0] == "done"


def test_episode_video_options_are_checked_before_any_work(tmp_path) -> None:
    import pytest

    from factask.sim.render.offscreen import RenderError
    from factask.viz import EpisodeVideo

    for kwargs, says in (({"fps": 0}, "fps"), ({"size": (64, 30), "caption": True}, "caption"),
                         ({"path": tmp_path / "v.webm"}, ".gif or .mp4")):
        with pytest.raises(RenderError, match=says):
            EpisodeVideo(**{"path": tmp_path / "v.mp4", **kwargs})
