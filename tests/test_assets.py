"""Asset builders: geometry matches the declared size, objects rest stably, files stay fresh."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import mujoco
import numpy as np
import pytest

import factask.sim  # noqa: F401  (headless GL backend before MuJoCo's GL loads)
from factask.geometry import tilt_deg
from factask.sim.build.mjcf import (
    FIXTURE_CLEARANCE,
    MARKER_GROUP,
    AssetError,
    build_object,
    build_table,
    fixture_fits,
    fixture_size_for,
    kind_parts,
    new_root,
    parts_aabb,
)
from factask.vocabulary.kinds import ASSET_KINDS, KIND_NAMES

ROOT = Path(__file__).resolve().parent.parent
#: Sizes that differ on every axis (where the kind allows), so swapped axes show.
ODD_SIZES = {
    "block": (0.04, 0.05, 0.03),
    "box": (0.08, 0.05, 0.03),
    "cylinder": (0.03, 0.03, 0.08),
    "ball": (0.05, 0.05, 0.05),
    "log": (0.10, 0.03, 0.03),
    "bowl": (0.14, 0.14, 0.06),
    "container": (0.18, 0.12, 0.06),
    "zone": (0.15, 0.10, 0.001),
    "pallet": (0.30, 0.25, 0.0375),
    "stand": (0.15, 0.05, 0.005),
    "corner": (0.06, 0.05, 0.001),
    "line": (0.30, 0.01, 0.001),
    "ell": (0.08, 0.10, 0.04),
    "fixture": (0.13, 0.12, 0.04),
    "kit": (0.28, 0.20, 0.005),
    "holed_box": (0.10, 0.08, 0.06),
    "pile": (0.012, 0.01, 0.008),
    "rope": (0.016, 0.01, 0.008),
    "cabinet": (0.20, 0.26, 0.12),
    "drawer": (0.21, 0.22, 0.07),
    "stove": (0.24, 0.20, 0.05),
    "lamp": (0.14, 0.12, 0.06),
    "switch": (0.03, 0.03, 0.02),
    "microwave": (0.17, 0.21, 0.11),
    "door": (0.05, 0.21, 0.11),
    "shelf": (0.26, 0.30, 0.15),
    "shelf_level": (0.12, 0.28, 0.06),
}


def _rot(quat: np.ndarray) -> np.ndarray:
    m = np.zeros(9)
    mujoco.mju_quat2Mat(m, np.asarray(quat, dtype=float))
    return m.reshape(3, 3)


def geom_aabb(model: mujoco.MjModel, geoms: list[int]) -> tuple[np.ndarray, np.ndarray]:
    """AABB in the body frame, from the compiled model's geom types, sizes and poses
    (independent of the builders' own bookkeeping)."""
    lows, highs = [], []
    for g in geoms:
        t, s = model.geom_type[g], model.geom_size[g]
        if t == mujoco.mjtGeom.mjGEOM_BOX:
            half = s[:3]
        elif t == mujoco.mjtGeom.mjGEOM_CYLINDER:
            half = np.array([s[0], s[0], s[1]])  # MuJoCo: (radius, half-height)
        elif t == mujoco.mjtGeom.mjGEOM_SPHERE:
            half = np.full(3, s[0])
        else:
            raise AssertionError(f"unexpected geom type {t}")
        r = _rot(model.geom_quat[g])
        if t == mujoco.mjtGeom.mjGEOM_CYLINDER:
            # A round cross-section: its extent along world axis i is radius *
            # |in-plane part| + half-height * |axis component|.
            ax = r[:, 2]
            ext = s[0] * np.sqrt(np.maximum(0.0, 1 - ax**2)) + s[1] * np.abs(ax)
        else:
            ext = np.abs(r) @ half
        lows.append(model.geom_pos[g] - ext)
        highs.append(model.geom_pos[g] + ext)
    return np.min(lows, axis=0), np.max(highs, axis=0)


def _single(kind: str, size: tuple[float, float, float], fixed: bool | None = None,
            pos: tuple[float, float, float] = (0.5, 0.0, 0.0)) -> mujoco.MjModel:
    root = new_root(f"t_{kind}")
    root.option.timestep = 0.002
    root.option.cone = "elliptic"
    root.option.impratio = 10
    build_table(root.worldbody)
    build_object(root.worldbody, "obj", kind, size, "red", fixed=fixed,
                 pos=(pos[0], pos[1], pos[2] or size[2] / 2))
    return mujoco.MjModel.from_xml_string(root.to_xml_string())


def _object_geoms(model: mujoco.MjModel) -> list[int]:
    body = model.body("obj").id
    return [int(g) for g in np.flatnonzero(model.geom_bodyid == body)]


@pytest.mark.parametrize("kind", KIND_NAMES)
def test_parts_bounding_box_is_declared_size(kind: str) -> None:
    size = ODD_SIZES[kind]
    lo, hi = parts_aabb(kind_parts(kind, size))
    np.testing.assert_allclose(hi - lo, size, atol=1e-9)
    np.testing.assert_allclose((hi + lo) / 2, 0.0, atol=1e-9)


@pytest.mark.parametrize("kind", KIND_NAMES)
def test_compiled_geoms_match_size_and_collision_matches_visual(kind: str) -> None:
    size = ODD_SIZES[kind]
    model = _single(kind, size)
    geoms = _object_geoms(model)
    assert all(model.geom(g).name.startswith("obj:") for g in geoms)
    lo, hi = geom_aabb(model, geoms)
    np.testing.assert_allclose(hi - lo, size, atol=1e-6)
    np.testing.assert_allclose((hi + lo) / 2, 0.0, atol=1e-6)
    colliding = [g for g in geoms if model.geom_contype[g] or model.geom_conaffinity[g]]
    if ASSET_KINDS[kind].collides:
        # Every geom is both the visual and the collision shape.
        assert colliding == geoms
    else:
        assert colliding == []


def test_cylinder_radius_and_height_are_not_swapped() -> None:
    model = _single("cylinder", (0.03, 0.03, 0.08))
    (g,) = _object_geoms(model)
    np.testing.assert_allclose(model.geom_size[g][:2], [0.015, 0.04])


def _settle(model: mujoco.MjModel, seconds: float = 1.0) -> mujoco.MjData:
    data = mujoco.MjData(model)
    for _ in range(int(seconds / model.opt.timestep)):
        mujoco.mj_step(model, data)
    return data


@pytest.mark.parametrize("kind", [k for k in KIND_NAMES if ASSET_KINDS[k].collides])
def test_free_object_rests_on_table(kind: str) -> None:
    size = ASSET_KINDS[kind].default_size
    model = _single(kind, size, fixed=False)
    assert model.nmocap == 0 and model.njnt == 1
    data = _settle(model)
    pos, quat = data.xpos[model.body("obj").id], data.xquat[model.body("obj").id]
    assert np.all(np.isfinite(data.qpos))
    assert abs(pos[2] - size[2] / 2) < 0.002
    np.testing.assert_allclose(pos[:2], [0.5, 0.0], atol=0.002)
    assert tilt_deg(quat) < 1.0
    assert np.linalg.norm(data.qvel) < 0.01


@pytest.mark.parametrize("kind", KIND_NAMES)
def test_fixed_object_is_mocap_and_stays_put(kind: str) -> None:
    size = ASSET_KINDS[kind].default_size
    model = _single(kind, size, fixed=True, pos=(0.4, 0.1, 0.0))
    assert model.nmocap == 1 and model.njnt == 0
    data = _settle(model, 0.2)
    np.testing.assert_allclose(data.xpos[model.body("obj").id], [0.4, 0.1, size[2] / 2])


def test_marker_kinds_are_never_free() -> None:
    model = _single("zone", (0.1, 0.1, 0.001), fixed=False)
    assert model.nmocap == 1 and model.njnt == 0


@pytest.mark.parametrize("ell_size", [(0.08, 0.08, 0.04), (0.09, 0.06, 0.04)])
def test_ell_fits_its_fixture_with_clearance(ell_size: tuple[float, float, float]) -> None:
    fixture = fixture_size_for(ell_size)
    np.testing.assert_allclose(fixture_fits(fixture), ell_size)
    root = new_root("fit")
    build_object(root.worldbody, "fix", "fixture", fixture, "gray", pos=(0.5, 0, 0.02))
    build_object(root.worldbody, "ell", "ell", ell_size, "red", pos=(0.5, 0, 0.02))
    model = mujoco.MjModel.from_xml_string(root.to_xml_string())
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    fix_body, ell_body = model.body("fix").id, model.body("ell").id
    gaps = []
    for g1 in np.flatnonzero(model.geom_bodyid == fix_body):
        for g2 in np.flatnonzero(model.geom_bodyid == ell_body):
            gaps.append(mujoco.mj_geomDistance(model, data, int(g1), int(g2), 0.05, None))
    # The piece touches nothing; the closest wall is the clearance away.
    assert min(gaps) == pytest.approx(FIXTURE_CLEARANCE, abs=1e-6)


def test_default_ell_fits_default_fixture() -> None:
    fits = fixture_fits(ASSET_KINDS["fixture"].default_size)
    ell = ASSET_KINDS["ell"].default_size
    assert fits[0] >= ell[0] and fits[1] >= ell[1]


def test_square_fixture_is_four_walls() -> None:
    parts = kind_parts("fixture", (0.1, 0.1, 0.04), hollow="square")
    assert len(parts) == 4
    lo, hi = parts_aabb(parts)
    np.testing.assert_allclose(hi - lo, (0.1, 0.1, 0.04))


@pytest.mark.parametrize(
    ("kind", "size", "words"),
    [
        ("cylinder", (0.04, 0.05, 0.06), "round footprint"),
        ("ball", (0.04, 0.04, 0.05), "diameter"),
        ("log", (0.12, 0.04, 0.05), "both its diameter"),
        ("container", (0.015, 0.1, 0.05), "no room"),
        ("block", (0.04, 0.0, 0.04), "positive"),
        ("ell", (0.04, 0.01, 0.04), "bar width"),
        ("holed_box", (0.08, 0.03, 0.05), "no room for its hole"),
        ("teapot", (0.1, 0.1, 0.1), "unknown asset kind"),
    ],
)
def test_bad_sizes_raise_asset_error_naming_the_object(
    kind: str, size: tuple[float, float, float], words: str
) -> None:
    root = new_root("bad")
    with pytest.raises(AssetError, match=words) as info:
        build_object(root.worldbody, "thing", kind, size, "red")
    assert info.value.name == "thing"
    assert "fix:" in str(info.value)


def test_unknown_colour_and_bad_mass_raise() -> None:
    root = new_root("bad")
    with pytest.raises(AssetError, match="unknown colour"):
        build_object(root.worldbody, "a", "block", (0.04, 0.04, 0.04), "chartreuse")
    with pytest.raises(AssetError, match="mass"):
        build_object(root.worldbody, "b", "block", (0.04, 0.04, 0.04), "red", mass=-1.0)


def test_fixed_object_needs_worldbody_parent() -> None:
    root = new_root("bad")
    holder = root.worldbody.add("body", name="holder")
    with pytest.raises(AssetError, match="worldbody"):
        build_object(holder, "z", "zone", (0.1, 0.1, 0.001), "red")


def test_visual_only_build_has_no_collision_or_mass() -> None:
    root = new_root("vis")
    build_object(root.worldbody, "m", "ell", (0.08, 0.08, 0.04), "red", visual_only=True,
                 alpha=0.3)
    model = mujoco.MjModel.from_xml_string(root.to_xml_string())
    geoms = np.flatnonzero(model.geom_bodyid == model.body("m").id)
    assert np.all(model.geom_contype[geoms] == 0) and np.all(model.geom_conaffinity[geoms] == 0)
    assert np.all(model.geom_group[geoms] == MARKER_GROUP)
    np.testing.assert_allclose(model.geom_rgba[geoms, 3], 0.3)


def test_object_mass_is_the_given_mass() -> None:
    root = new_root("mass")
    build_object(root.worldbody, "c", "container", (0.16, 0.16, 0.05), "red", mass=0.3,
                 fixed=False)
    model = mujoco.MjModel.from_xml_string(root.to_xml_string())
    assert model.body_mass[model.body("c").id] == pytest.approx(0.3)


def _load_export_script():  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location("export_assets",
                                                  ROOT / "scripts" / "export_assets.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_committed_asset_files_are_fresh() -> None:
    expected = _load_export_script().expected_files()
    assert set(expected) == {f"{k}.xml" for k in KIND_NAMES} | {"table.xml"}
    for name, text in expected.items():
        path = ROOT / "mjcf_assets" / name
        assert path.exists(), f"{path} missing: run scripts/export_assets.py"
        assert path.read_text(encoding="utf-8") == text, (
            f"{path} is stale: run scripts/export_assets.py")
        mujoco.MjModel.from_xml_string(text)


def test_holed_box_has_an_open_square_hole_in_the_middle_of_its_x_side() -> None:
    from factask.vocabulary.kinds import side_hole

    size = ODD_SIZES["holed_box"]
    side, centre = side_hole(size)
    assert side == pytest.approx(0.5 * min(size[1], size[2])) and centre == size[2] / 2
    parts = kind_parts("holed_box", size)

    def solid(point: tuple[float, float, float]) -> bool:
        return any(bool(np.all(np.abs(np.asarray(point) - p.pos) <= p.half_extents + 1e-12))
                   for p in parts)

    face = size[0] / 2 - 0.001  # inside the +x wall
    assert not solid((face, 0.0, 0.0))  # the hole: open through the wall
    assert not solid((0.0, 0.0, 0.0))  # the box is hollow behind it
    for dy, dz in ((0.6 * side, 0.0), (-0.6 * side, 0.0), (0.0, 0.6 * side), (0.0, -0.6 * side)):
        assert solid((face, dy, dz)), (dy, dz)  # the wall round the hole
    assert solid((-face, 0.0, 0.0))  # the other sides are closed
