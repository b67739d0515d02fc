"""CLIPort's public API, name by name: each name of GenSim's ``cliport.utils.utils`` and
of its ``Task`` base class is provided by factask's stand-ins or refused with a reason,
and docs/compat.md's table says which (issue 35, item 3)."""

from __future__ import annotations

import inspect
import re
from pathlib import Path

import numpy as np
import pytest

from factask.compat.cliport import utils
from factask.compat.cliport.errors import Unsupported
from factask.compat.cliport.task import Task

DOCS = Path(__file__).resolve().parents[1] / "docs" / "compat.md"

#: Every public name of GenSim's cliport/utils/utils.py (functions, classes, constants).
UTILS_NAMES = (
    "get_heightmap", "get_pointcloud", "transform_pointcloud", "reconstruct_heightmaps",
    "pix_to_xyz", "xyz_to_pix", "unproject_vectorized", "unproject_depth_vectorized",
    "sample_distribution", "invert", "multiply", "apply", "eulerXYZ_to_quatXYZW",
    "quatXYZW_to_eulerXYZ", "apply_transform", "preprocess", "map_kit_scale", "deprocess",
    "get_fused_heightmap", "get_image_transform", "check_transform",
    "get_se3_from_image_transform", "get_random_image_transform_params", "q_mult", "perturb",
    "apply_perturbation", "ImageRotator", "TreeNode", "KDTree", "COLORS", "COLORS_NAMES",
    "TRAIN_COLORS", "EVAL_COLORS", "get_colors", "get_colors_names", "get_random_color",
    "solve_hanoi_all", "plot", "create_visualizer", "make_frame", "meshcat_visualize",
    "set_seed", "load_cfg", "load_hydra_config")
#: Every public method of GenSim's Task, then the attributes its __init__ sets.
TASK_NAMES = (
    "reset", "additional_reset", "oracle", "reward", "done", "is_match", "get_true_image",
    "get_random_pose", "get_lang_goal", "get_reward", "add_corner_anchor_for_pose",
    "get_target_sample_surface_points", "check_require_obj", "fill_template",
    "get_random_size", "get_box_object_points", "get_sphere_object_points",
    "get_mesh_object_points", "color_random_brown", "set_assets_root", "zip_obj_ids",
    "add_goal", "make_piles", "make_rope", "make_ropes", "get_kitting_shapes",
    "make_kitting_objects", "spawn_box", "get_asset_full_path",
    "ee", "mode", "sixdof", "primitive", "oracle_cams", "rng", "pos_eps", "rot_eps",
    "num_blocks", "pix_size", "bounds", "zone_bounds", "goals", "lang_goals",
    "obj_points_cache", "task_completed_desc", "progress", "train_set", "test_set",
    "assets_root", "homogeneous")


def _table(title: str) -> dict[str, tuple[str, str]]:
    """name -> (provided | refused, why) from the docs' table after ``title``."""
    text = DOCS.read_text()
    start = text.index(title)
    rows: dict[str, tuple[str, str]] = {}
    for line in text[start:].splitlines()[1:]:
        if rows and not line.startswith("|"):
            break
        match = re.match(r"\|\s*`([^`]+)`\s*\|\s*(provided|refused)\s*\|(.*)\|\s*$", line)
        if match:
            rows[match.group(1)] = (match.group(2), match.group(3).strip())
    return rows


@pytest.mark.parametrize("name", UTILS_NAMES)
def test_every_utils_name_is_provided_or_refused_with_its_reason(name: str) -> None:
    status, why = _table("`cliport.utils.utils`:")[name]
    if status == "provided":
        assert name in vars(utils), name  # defined, not answered by the module's refusal
        return
    assert why, f"{name} refused with no reason in docs/compat.md"
    with pytest.raises(Unsupported, match=re.escape(name)) as info:
        getattr(utils, name)
    assert why.split(":")[0][:30] in str(info.value).replace("`", "")


@pytest.mark.parametrize("name", TASK_NAMES)
def test_every_task_name_is_provided_or_refused_with_its_reason(name: str) -> None:
    status, why = _table("`cliport.tasks.task.Task`:")[name]
    task = Task()
    assert hasattr(task, name), name
    if status == "provided":
        return
    assert why, f"Task.{name} refused with no reason in docs/compat.md"
    method = getattr(task, name)
    required = [p for p in inspect.signature(method).parameters.values()
                if p.default is inspect.Parameter.empty
                and p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    with pytest.raises(Unsupported, match=name):
        method(*[None] * len(required))


def test_the_docs_tables_hold_exactly_these_names() -> None:
    assert set(_table("`cliport.utils.utils`:")) == set(UTILS_NAMES)
    assert set(_table("`cliport.tasks.task.Task`:")) == set(TASK_NAMES)


def test_map_kit_scale_and_image_normalisation_work_as_in_gensim() -> None:
    assert utils.map_kit_scale((1.0, 2.0, 3.0)) == pytest.approx((0.1, 0.2, 0.3))
    img = np.zeros((2, 2, 4))
    img[..., :3] = 255 * 0.18877631
    img[..., 3] = 0.00509261
    out = utils.preprocess(img.copy())
    assert np.allclose(out, 0.0)  # the transporter means map to zero
    back = utils.deprocess(out)
    assert np.allclose(back[..., :3], int(0.18877631 * 255), atol=1)
