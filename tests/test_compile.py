"""Graph -> MJCF -> MjModel compilation."""

from __future__ import annotations

import importlib.util
from typing import Any

import mujoco
import numpy as np
import pytest

import factask.sim  # noqa: F401  (headless GL backend before MuJoCo's GL loads)
from factask.geometry import Pose
from factask.graph import GraphValidationError, TaskGraph
from factask.sim.build.compile import (
    CompileError,
    compile_graph,
    fixture_hollows,
    get_object_pose,
    set_marker,
    set_object_pose,
)
from factask.sim.build.mjcf import MARKER_GROUP


def _graph(**overrides: Any) -> TaskGraph:
    data: dict[str, Any] = {
        "name": "blocks-in-bowl",
        "variables": [
            {"name": "blocks", "kind": "block", "color": "red", "count": 3},
            {"name": "bowl", "kind": "bowl", "color": "green"},
            {"name": "cyl", "kind": "cylinder", "color": "blue"},
            {"name": "zone", "kind": "zone", "color": "yellow"},
        ],
        "factors": [
            {"name": "blocks_in_bowl", "weight": 0.5,
             "goal": {"type": "inside", "objects": ["blocks"], "container": "bowl"}},
            {"name": "cyl_in_zone", "weight": 0.5,
             "goal": {"type": "in_zone", "objects": ["cyl"], "zone": "zone"}},
        ],
    }
    data.update(overrides)
    return TaskGraph.model_validate(data)


def test_objects_and_markers_are_mapped() -> None:
    scene = compile_graph(_graph(), robot=None)
    assert list(scene.objects) == ["blocks__0", "blocks__1", "blocks__2", "bowl", "cyl", "zone"]
    model = scene.model
    for name, h in scene.objects.items():
        assert model.body(h.body_id).name == name
        assert h.geom_ids and all(model.geom_bodyid[g] == h.body_id for g in h.geom_ids)
        assert all(scene.geom_object[g] == scene.object_names.index(name) for g in h.geom_ids)
    assert not scene.objects["blocks__0"].fixed and scene.objects["blocks__0"].qpos_adr is not None
    assert scene.objects["bowl"].fixed and scene.objects["bowl"].qpos_adr is None
    assert scene.geom_object[model.geom("table").id] == -1
    assert set(scene.markers) == {("blocks_in_bowl", 0), ("blocks_in_bowl", 1),
                                  ("blocks_in_bowl", 2), ("cyl_in_zone", 0)}
    assert scene.marker_objects[("cyl_in_zone", 0)] == "cyl"


def test_markers_do_not_collide() -> None:
    scene = compile_graph(_graph(), robot=None)
    model = scene.model
    marker_bodies = [b for b in range(model.nbody) if model.body(b).name.startswith("goal:")]
    assert len(marker_bodies) == len(scene.markers)
    assert sorted(int(model.body_mocapid[b]) for b in marker_bodies) == sorted(
        scene.markers.values())
    geoms = np.flatnonzero(np.isin(model.geom_bodyid, marker_bodies))
    assert len(geoms) > 0
    assert np.all(model.geom_contype[geoms] == 0) and np.all(model.geom_conaffinity[geoms] == 0)
    assert np.all(model.geom_group[geoms] == MARKER_GROUP)
    assert np.all(model.geom_rgba[geoms, 3] < 1)


def test_scene_settles_without_nan() -> None:
    scene = compile_graph(_graph(), robot=None)
    data = scene.make_data()
    for _ in range(250):
        mujoco.mj_step(scene.model, data)
    assert np.all(np.isfinite(data.qpos))
    for h in scene.objects.values():
        assert get_object_pose(data, h).pos[2] == pytest.approx(h.size[2] / 2, abs=0.002)


def test_options() -> None:
    model = compile_graph(_graph(), robot=None, timestep=0.004).model
    assert model.opt.timestep == pytest.approx(0.004)
    assert model.opt.integrator == mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    assert model.opt.cone == mujoco.mjtCone.mjCONE_ELLIPTIC
    assert model.opt.impratio == pytest.approx(10.0)
    assert model.vis.quality.shadowsize <= 1024


def test_compile_is_deterministic() -> None:
    a = compile_graph(_graph(), robot=None).xml
    b = compile_graph(_graph(), robot=None).xml
    assert a == b
    other = _graph()
    other.variables[0].color = "blue"
    assert compile_graph(other, robot=None).xml != a
    assert "unnamed" not in a


def test_pose_helpers_round_trip() -> None:
    scene = compile_graph(_graph(), robot=None)
    data = scene.make_data()
    pose = Pose.from_xyz_yaw(0.6, 0.2, 0.02, 0.7)
    for name in ("blocks__1", "bowl"):
        h = scene.objects[name]
        set_object_pose(scene.model, data, h, pose)
        got = get_object_pose(data, h)
        np.testing.assert_allclose(got.pos, pose.pos)
        np.testing.assert_allclose(got.quat, pose.quat)
        mujoco.mj_forward(scene.model, data)
        np.testing.assert_allclose(data.xpos[h.body_id], pose.pos, atol=1e-9)
    mocap = scene.markers[("cyl_in_zone", 0)]
    set_marker(data, mocap, pose)
    np.testing.assert_allclose(data.mocap_pos[mocap], pose.pos)


def test_size_the_kind_cannot_have_names_the_variable() -> None:
    graph = _graph()
    graph.variables[2].size = (0.04, 0.05, 0.06)  # a cylinder with an oval footprint
    with pytest.raises(GraphValidationError) as info:
        compile_graph(graph, robot=None)
    assert info.value.nodes == {"cyl"}
    assert "cyl.size" in str(info.value) and "fix:" in str(info.value)


def test_fixture_too_small_for_an_ell_hollow_is_a_compile_error() -> None:
    graph = TaskGraph.model_validate({
        "name": "narrow-fixture",
        "variables": [{"name": "piece", "kind": "ell", "color": "red"},
                      {"name": "frame", "kind": "fixture", "size": [0.12, 0.034, 0.04]}],
        "factors": [{"name": "insert", "goal": {"type": "aligned", "objects": ["piece"],
                                                "reference": "frame"}}],
    }).ensure_valid()  # walls fit, so the graph is valid; an ell hollow does not
    with pytest.raises(CompileError) as info:
        compile_graph(graph, robot=None)
    assert info.value.variable == "frame"
    assert str(info.value).count("frame:") == 1 and "fix:" in str(info.value)


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [({"robot": "hexapod"}, "unknown robot"), ({"timestep": 0.0}, "timestep"),
     ({"timestep": float("nan")}, "timestep")],
)
def test_bad_arguments_raise_compile_error(kwargs: dict[str, Any], words: str) -> None:
    args = {"robot": None, **kwargs}
    with pytest.raises(CompileError, match=words):
        compile_graph(_graph(), **args)


def test_graph_without_factors_is_rejected() -> None:
    with pytest.raises(CompileError, match="no factors"):
        compile_graph(_graph(factors=[]), robot=None)


def test_invalid_graph_raises_validation_error() -> None:
    graph = _graph()
    graph.factors[0].weight = 0.9
    with pytest.raises(GraphValidationError):
        compile_graph(graph, robot=None)


def test_fixture_hollow_follows_what_goes_in() -> None:
    graph = _graph(
        variables=[
            {"name": "ell", "kind": "ell", "color": "red"},
            {"name": "cube", "kind": "block", "color": "blue"},
            {"name": "frame_a", "kind": "fixture", "color": "gray"},
            {"name": "frame_b", "kind": "fixture", "color": "gray"},
        ],
        factors=[
            {"name": "ell_in", "weight": 0.5,
             "goal": {"type": "aligned", "objects": ["ell"], "reference": "frame_a"}},
            {"name": "cube_in", "weight": 0.5,
             "goal": {"type": "inside", "objects": ["cube"], "container": "frame_b"}},
        ],
    )
    assert fixture_hollows(graph) == {"frame_a": "ell", "frame_b": "square"}
    scene = compile_graph(graph, robot=None)
    assert len(scene.objects["frame_a"].geom_ids) == 5
    assert len(scene.objects["frame_b"].geom_ids) == 4


@pytest.mark.skipif(importlib.util.find_spec("factask.sim.robots.attach") is None,
                    reason="factask.sim.robots.attach not written yet")
@pytest.mark.parametrize("robot", ["floating", "arm"])
def test_compiles_with_robot(robot: str) -> None:
    scene = compile_graph(_graph(), robot=robot)
    assert scene.robot == robot
    assert scene.model.nbody > len(scene.objects) + len(scene.markers) + 1


@pytest.mark.parametrize("task", ["blocks-in-bowl", "library"])
def test_mjspec_and_mjcf_export_build_the_same_model(task: str) -> None:
    """The compile path (MjSpec) and the export path (dm_control MJCF) agree on every
    body, geom and site: counts, types, sizes, placements, masses, contact settings."""
    from factask.library import get_task, task_names
    from factask.sim.build.compile import build_mjcf
    from factask.sim.build.mjcf import XML_PRECISION
    from factask.vocabulary.kinds import JOINTED_KINDS

    # Jointed parts are built at compile time only (a drawer inside its cabinet's body,
    # a door inside its microwave's, a button inside its host's, each on its joint);
    # the MJCF export has their stand-alone assets, not a scene's.
    graphs = [_graph()] if task == "blocks-in-bowl" else [
        g for g in map(get_task, task_names())
        if not any(v.kind in JOINTED_KINDS for v in g.variables)]
    for graph in graphs:
        spec_model = compile_graph(graph, robot=None).model
        root, _ = build_mjcf(graph)
        xml_model = mujoco.MjModel.from_xml_string(root.to_xml_string(precision=XML_PRECISION))
        for count in ("nbody", "ngeom", "nsite", "njnt", "nmocap", "ncam", "nlight"):
            assert getattr(spec_model, count) == getattr(xml_model, count), count
        for name in ("body_mass", "body_inertia", "body_ipos", "body_pos", "body_quat",
                     "body_mocapid", "geom_type", "geom_size", "geom_pos", "geom_quat",
                     "geom_rgba", "geom_group", "geom_contype", "geom_conaffinity",
                     "geom_friction", "geom_solref", "geom_solimp", "geom_condim",
                     "geom_bodyid", "cam_pos", "cam_quat", "light_dir"):
            np.testing.assert_allclose(getattr(spec_model, name), getattr(xml_model, name),
                                       atol=1e-9, err_msg=f"{graph.name}: {name}")
        for i in range(spec_model.ngeom):
            assert spec_model.geom(i).name == xml_model.geom(i).name
        assert spec_model.opt.timestep == xml_model.opt.timestep
        assert spec_model.opt.impratio == xml_model.opt.impratio
        assert spec_model.opt.integrator == xml_model.opt.integrator
        assert spec_model.opt.cone == xml_model.opt.cone


@pytest.mark.parametrize("robot", ["floating", "arm", "ur5e"])
def test_scene_xml_round_trips(robot: str) -> None:
    """The MJCF text of a compiled scene (robot included) loads into the same model."""
    scene = compile_graph(_graph(), robot=robot)
    again = mujoco.MjModel.from_xml_string(scene.xml)
    for count in ("nbody", "ngeom", "nsite", "njnt", "nu", "neq"):
        assert getattr(again, count) == getattr(scene.model, count), count
    # spec.to_xml() writes numbers with about six significant digits.
    np.testing.assert_allclose(again.body_mass, scene.model.body_mass, rtol=1e-5)
    np.testing.assert_allclose(again.geom_size, scene.model.geom_size, rtol=1e-5)
