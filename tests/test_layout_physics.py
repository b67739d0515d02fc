"""Layouts and solved targets checked in MuJoCo (sampling, solving, compile, checks).

The pure-geometry tests of the sampler live in test_layout.py; here the compiled
scene (``robot=None``) is the judge: sampled initial layouts have no penetrating
contacts, objects put exactly at their solved targets satisfy every factor and
stay there under gravity, initial layouts satisfy nothing, and an impossible
layout fails quickly.
"""

from __future__ import annotations

import time
from functools import cache

import mujoco
import numpy as np
import pytest
from helpers import make_graph
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.geometry import Pose
from factask.graph import TaskGraph
from factask.library import get_task, task_names
from factask.scene.collision import LayoutError
from factask.scene.objects import objects_by_name
from factask.sim.build.compile import (
    CompiledScene,
    compile_graph,
    get_object_pose,
    set_object_poses,
)
from factask.sim.layout.checks import check_task
from factask.sim.layout.reset import reset_layout
from factask.sim.layout.sampling import sample_layout

#: Deepest allowed penetration between two geoms (MuJoCo contact.dist, metres).
#: Resting contacts (an object on another, on its floor, on the table) have dist ~ 0.
PENETRATION = -1e-3
#: Simulated seconds the scene runs from the solved targets.
SETTLE_SECONDS = 0.5
#: How far (metres) an object may drift while settling at its target.
DRIFT = 0.005

#: Library tasks checked by default: every initial placement kind (table, pose,
#: region, on a stand, inside a container) and every receptacle kind.
DEFAULT_TASKS = [
    "towers-of-hanoi", "color-sorted-container-stack", "block-insertion", "put-block-in-bowl",
    "packing-boxes", "align-spheres-in-colored-zones", "insertion-in-color-sequenced-zones",
    "color-coordinated-block-corner-alignment",
]


def relation_graphs() -> dict[str, TaskGraph]:
    """Small graphs that together use every relation (and both aligned modes)."""
    return {
        "at_pose": make_graph(
            [{"name": "blocks", "kind": "block", "count": 2},
             {"name": "pallet", "kind": "pallet"},
             {"name": "cube", "kind": "block", "color": "red"}],
            [{"name": "on_pallet", "goal": {"type": "at_pose", "objects": ["blocks"],
                                            "frame": "pallet",
                                            "poses": [{"x": 0.0, "y": 0.04},
                                                      {"x": 0.0, "y": -0.04, "yaw_deg": 30}]}},
             {"name": "world", "goal": {"type": "at_pose", "objects": ["cube"],
                                        "poses": [{"x": 0.4, "y": 0.3, "yaw_deg": 45}]}}],
            name="at-pose"),
        "in_zone": make_graph(
            [{"name": "blocks", "kind": "block", "count": 3},
             {"name": "zone", "kind": "zone", "size": [0.15, 0.15, 0.001]}],
            [{"name": "f", "goal": {"type": "in_zone", "objects": ["blocks"], "zone": "zone"}}],
            name="in-zone"),
        "on": make_graph(
            [{"name": "box", "kind": "box", "size": [0.1, 0.1, 0.05]},
             {"name": "plate", "kind": "kit"},
             {"name": "cubes", "kind": "block", "count": 2},
             {"name": "pillars", "kind": "box", "size": [0.04, 0.04, 0.06], "count": 2},
             {"name": "bar", "kind": "box", "size": [0.16, 0.04, 0.02]}],
            [{"name": "box_on_plate", "goal": {"type": "on", "objects": ["box"],
                                               "support": "plate"}},
             {"name": "cubes_on_box", "goal": {"type": "on", "objects": ["cubes"],
                                               "support": "box"}},
             {"name": "pillar_row", "goal": {"type": "row", "objects": ["pillars"],
                                          "spacing": 0.1}},
             {"name": "bridge", "goal": {"type": "on", "objects": ["bar"],
                                         "support": "pillars"}}],
            name="on"),
        "inside": make_graph(
            [{"name": "bowl", "kind": "bowl"}, {"name": "balls", "kind": "ball", "count": 2},
             {"name": "cont", "kind": "container"},
             {"name": "cyl", "kind": "cylinder", "count": 3}],
            [{"name": "balls_in_bowl", "goal": {"type": "inside", "objects": ["balls"],
                                                "container": "bowl"}},
             {"name": "cyl_in_cont", "goal": {"type": "inside", "objects": ["cyl"],
                                              "container": "cont"}}],
            name="inside"),
        "inside_roomy": make_graph(
            [{"name": "bowl", "kind": "bowl"}, {"name": "ball", "kind": "ball"},
             {"name": "cont", "kind": "container"},
             {"name": "cyl", "kind": "cylinder", "count": 2}],
            [{"name": "ball_in_bowl", "goal": {"type": "inside", "objects": ["ball"],
                                               "container": "bowl"}},
             {"name": "cyl_in_cont", "goal": {"type": "inside", "objects": ["cyl"],
                                              "container": "cont"}}],
            name="inside-roomy"),
        "stack": make_graph(
            [{"name": "a", "kind": "block"}, {"name": "b", "kind": "block"},
             {"name": "c", "kind": "block"},
             {"name": "z", "kind": "zone"},
             {"name": "tower", "kind": "box", "size": [0.05, 0.05, 0.04], "count": 2}],
            [{"name": "column", "goal": {"type": "stack", "objects": ["a", "b", "c"]}},
             {"name": "on_zone", "goal": {"type": "stack", "objects": ["tower"], "base": "z",
                                          "ordered": False}}],
            name="stack"),
        "row": make_graph(
            [{"name": "line", "kind": "line"},
             {"name": "low", "kind": "block", "count": 3},
             {"name": "top", "kind": "block", "count": 2, "color": "red"}],
            [{"name": "along", "goal": {"type": "row", "objects": ["low"], "along": "line"}},
             {"name": "pyramid", "goal": {"type": "row", "objects": ["top"], "on": "low"}}],
            name="row"),
        "circle": make_graph(
            [{"name": "blocks", "kind": "block", "count": 5}, {"name": "zone", "kind": "zone"},
             {"name": "cyls", "kind": "cylinder", "count": 3, "color": "blue"}],
            [{"name": "around_zone", "goal": {"type": "circle", "objects": ["blocks"],
                                              "center": "zone"}},
             {"name": "free_circle", "goal": {"type": "circle", "objects": ["cyls"]}}],
            name="circle"),
        "aligned": make_graph(
            [{"name": "ell", "kind": "ell"}, {"name": "fix", "kind": "fixture"},
             {"name": "box", "kind": "box", "size": [0.08, 0.05, 0.04]},
             {"name": "corner", "kind": "corner"},
             {"name": "cube", "kind": "block", "color": "yellow"},
             {"name": "mark", "kind": "zone", "size": [0.06, 0.06, 0.001]}],
            [{"name": "ell_in_fixture", "goal": {"type": "aligned", "objects": ["ell"],
                                                 "reference": "fix"}},
             {"name": "box_in_corner", "goal": {"type": "aligned", "objects": ["box"],
                                                "reference": "corner", "mode": "corner"}},
             {"name": "cube_on_mark", "goal": {"type": "aligned", "objects": ["cube"],
                                               "reference": "mark", "mode": "center"}}],
            name="aligned"),
    }


GRAPHS = relation_graphs()
RELATIONS = {"at_pose", "in_zone", "on", "inside", "stack", "row", "circle", "aligned"}


@cache
def _scene(key: str) -> tuple[TaskGraph, CompiledScene]:
    """A relation graph (by GRAPHS key) or a library task, compiled without robot."""
    graph = GRAPHS[key] if key in GRAPHS else get_task(key)
    return graph, compile_graph(graph, robot=None)


def _load(scene: CompiledScene, poses: dict[str, Pose]) -> mujoco.MjData:
    """Fresh data with every object at ``poses``, forward-computed."""
    data = mujoco.MjData(scene.model)
    set_object_poses(scene.model, data, scene.objects, poses)
    mujoco.mj_forward(scene.model, data)
    return data


def _penetrations(scene: CompiledScene, data: mujoco.MjData) -> list[str]:
    """Contacts deeper than :data:`PENETRATION` involving at least one object."""
    names = scene.object_names
    out = []
    for c in data.contact[:data.ncon]:
        a, b = int(scene.geom_object[c.geom1]), int(scene.geom_object[c.geom2])
        if a < 0 and b < 0:
            continue
        if c.dist < PENETRATION:
            na = names[a] if a >= 0 else scene.model.geom(c.geom1).name or "static"
            nb = names[b] if b >= 0 else scene.model.geom(c.geom2).name or "static"
            out.append(f"{na} / {nb}: {c.dist * 1000:.1f} mm")
    return out


def _current(scene: CompiledScene, data: mujoco.MjData) -> dict[str, Pose]:
    return {n: get_object_pose(data, h) for n, h in scene.objects.items()}


def _at_targets(graph: TaskGraph, layout: dict[str, Pose], solved: dict) -> dict[str, Pose]:
    """The initial layout with every moved object at its solved target."""
    poses = dict(layout)
    objs = objects_by_name(graph)
    for s in solved.values():
        poses.update(s.targets(objs))
    return poses


# ------------------------------------------------------------ coverage
def test_graphs_cover_every_relation_and_aligned_mode() -> None:
    """The target tests below exercise every relation type and both aligned modes."""
    seen = {f.goal.type for g in GRAPHS.values() for f in g.factors}
    assert seen == RELATIONS
    modes = {f.goal.mode for g in GRAPHS.values() for f in g.factors
             if f.goal.type == "aligned"}
    assert modes == {"center", "corner"}


# ------------------------------------------------------------ initial layouts
def _check_layout_contacts(key: str, seed: int) -> None:
    graph, scene = _scene(key)
    layout = sample_layout(graph, np.random.default_rng(seed))
    data = _load(scene, layout)
    bad = _penetrations(scene, data)
    assert not bad, f"{key} seed {seed}: penetrating contacts {bad}"


@pytest.mark.parametrize("key", DEFAULT_TASKS)
@settings(max_examples=15, deadline=None)
@given(seed=st.integers(0, 2**31 - 1))
def test_sampled_layout_has_no_penetration(key: str, seed: int) -> None:
    """No MuJoCo contact of a sampled initial layout penetrates deeper than 1 mm.

    Objects that deliberately start on or inside another (disks on a stand, blocks in
    a container) only rest on it (dist ~ 0), so they need no exemption."""
    _check_layout_contacts(key, seed)


@pytest.mark.parametrize(("key", "seed"), [
    ("assembling-kits-seq", 13143),  # a table start inside an ell fixture's frame
    ("align-balls-in-colored-boxes", 665209),  # a ball's rim past 8 sampled rim points
])
def test_layouts_that_once_penetrated(key: str, seed: int) -> None:
    """Seeds on which sampling once put objects 1-4 mm into others (found by the
    whole-library test below)."""
    _check_layout_contacts(key, seed)


@pytest.mark.slow
@pytest.mark.parametrize("key", [n for n in task_names() if n not in DEFAULT_TASKS])
@settings(max_examples=15, deadline=None)
@given(seed=st.integers(0, 2**31 - 1))
def test_sampled_layout_has_no_penetration_whole_library(key: str, seed: int) -> None:
    """The same for every other library task."""
    _check_layout_contacts(key, seed)


@pytest.mark.parametrize("key", sorted(GRAPHS))
@settings(max_examples=5, deadline=None)
@given(seed=st.integers(0, 2**31 - 1))
def test_relation_layouts_have_no_penetration_and_satisfy_nothing(key: str, seed: int) -> None:
    """reset_layout's initial layout: no penetration, and no factor has any progress,
    neither as sampled nor after settling under gravity."""
    graph, scene = _scene(key)
    layout, solved = reset_layout(graph, np.random.default_rng(seed))
    data = _load(scene, layout)
    assert not _penetrations(scene, data)
    status = check_task(graph, solved, layout)
    assert not any(s.satisfied for s in status.factors.values()), status
    assert status.reward == 0.0, {n: s.detail for n, s in status.factors.items()}
    for _ in range(round(0.3 / scene.model.opt.timestep)):
        mujoco.mj_step(scene.model, data)
    settled = check_task(graph, solved, _current(scene, data))
    assert settled.reward == 0.0 and not settled.success


# ------------------------------------------------------------ solved targets
@pytest.mark.parametrize("key", sorted(GRAPHS))
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_objects_at_targets_satisfy_everything_and_stay(key: str, seed: int) -> None:
    """Every object put at its solved target: reward 1 and success; no penetration;
    after 0.5 s of physics every object is still there and the task still succeeds."""
    graph, scene = _scene(key)
    layout, solved = reset_layout(graph, np.random.default_rng(seed))
    poses = _at_targets(graph, layout, solved)
    data = _load(scene, poses)
    status = check_task(graph, solved, _current(scene, data))
    assert status.success, {n: s.detail for n, s in status.factors.items()}
    assert status.reward == pytest.approx(1.0)
    assert not _penetrations(scene, data)
    for _ in range(round(SETTLE_SECONDS / scene.model.opt.timestep)):
        mujoco.mj_step(scene.model, data)
    after = _current(scene, data)
    assert np.all(np.isfinite(data.qpos))
    drift = {n: float(np.linalg.norm(after[n].pos - poses[n].pos)) for n in poses}
    moved = {n: f"{d * 1000:.1f} mm" for n, d in drift.items() if d > DRIFT}
    assert not moved, f"objects drift from their targets: {moved}"
    settled = check_task(graph, solved, after)
    assert settled.success, {n: s.detail for n, s in settled.factors.items()}
    assert settled.reward == pytest.approx(1.0)


# ------------------------------------------------------------ impossible layouts
def test_impossible_layout_fails_quickly() -> None:
    """100 boxes of 10 cm (the most a scene may have) cannot fit: LayoutError within
    a few seconds, no hang."""
    groups = [f"boxes{k}" for k in range(2)]  # count is at most 64 per variable
    graph = make_graph(
        [{"name": g, "kind": "box", "size": [0.1, 0.1, 0.1], "count": 50} for g in groups],
        [{"name": "row", "goal": {"type": "row", "objects": groups}}], name="crowded")
    assert sum(len(graph.variable(g).instances) for g in groups) == 100
    for fn in (lambda: sample_layout(graph, np.random.default_rng(0)),
               lambda: reset_layout(graph, np.random.default_rng(0))):
        start = time.perf_counter()
        with pytest.raises(LayoutError) as info:
            fn()
        assert time.perf_counter() - start < 5.0
        assert info.value.retryable is False
        assert "boxes" in str(info.value) or "crowded" in str(info.value)
