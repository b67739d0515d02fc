"""The CLIPort layer keeps what the task's author gave: places on hosts, fixtures set
in the air or tilted (lowered with their targets), containers filled to their edge
(walls moved out), GenSim's box splitting (utils.TreeNode / utils.KDTree)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from factask.compat.cliport import import_cliport
from factask.compat.cliport import utils as cutils
from factask.compat.cliport.errors import Unsupported
from factask.graph import GraphValidationError, StartOn, StateVariable, TaskGraph
from factask.sim.env import FactaskEnv
from factask.vocabulary.kinds import WALL_THICKNESS

TASKS = Path(__file__).parent / "cliport_tasks"


def _split(bbox: tuple[float, ...], min_dim: float, margin: float, seed: int) -> list:
    np.random.seed(seed)
    boxes: list = []
    cutils.KDTree(cutils.TreeNode(None, [], bbox=np.array(bbox)), min_dim, margin, boxes)
    return boxes


@settings(max_examples=40, deadline=None)
@given(sx=st.floats(0.05, 0.4), sy=st.floats(0.05, 0.4), sz=st.floats(0.02, 0.2),
       min_dim=st.floats(0.02, 0.08), margin=st.floats(0.0, 0.02), seed=st.integers(0, 999))
def test_kdtree_leaves_tile_the_box_margin_apart(sx: float, sy: float, sz: float,
                                                 min_dim: float, margin: float,
                                                 seed: int) -> None:
    root = (0.0, 0.0, 0.0, sx, sy, sz)
    boxes = _split(root, min_dim, margin, seed)
    assert boxes and len(boxes) == len(_split(root, min_dim, margin, seed))  # seeded
    lo, hi = np.array(root[:3]), np.array(root[3:])
    for b in boxes:
        size = b[3:] - b[:3]
        assert np.all(b[:3] >= lo - 1e-9) and np.all(b[3:] <= hi + 1e-9)
        assert np.all(size <= 2 * min_dim + 1e-9)  # nothing left to split
    for i, a in enumerate(boxes):  # pairwise separated along some axis by the margin
        for b in boxes[i + 1:]:
            gaps = np.maximum(b[:3] - a[3:], a[:3] - b[3:])
            assert gaps.max() >= margin - 1e-9


def test_kdtree_refuses_absurd_splits() -> None:
    with pytest.raises(Unsupported, match="min_object_dim"):
        _split((0, 0, 0, 1, 1, 1), 0.0, 0.0, 0)
    with pytest.raises(Unsupported, match="more than"):
        _split((0, 0, 0, 2, 2, 2), 0.002, 0.0, 0)


def test_a_container_filled_to_its_edge_gets_its_walls_moved_out() -> None:
    r = import_cliport(TASKS / "pack_split_boxes.py", seed=0)
    container = r.graph.variable("container_brown_0")
    assert any("grown" in w for w in r.warnings)
    (f,) = r.graph.factors
    assert f.goal.poses is not None and len(f.goal.poses) == len(f.goal.objects) >= 2
    cx, cy = container.initial.x, container.initial.y
    for name, pose in zip(f.goal.objects, f.goal.poses, strict=True):
        half = np.array(r.graph.variable(name).extents[:2]) / 2
        reach = np.abs([pose.x - cx, pose.y - cy]) + half
        inner = np.array(container.extents[:2]) / 2 - WALL_THICKNESS
        assert np.all(reach < inner)  # every author's box clears the walls


def test_a_fixture_in_the_air_is_lowered_with_its_target() -> None:
    r = import_cliport(TASKS / "tilted_fixture.py", seed=0)
    assert any("above the table" in w for w in r.warnings)
    assert any("tilted" in w for w in r.warnings)
    (f,) = r.graph.factors
    assert f.goal.poses[0].z is None  # resting on the table, inside the lowered fixture
    # Ravens' goal keeps the author's own pose (it ignores z).
    assert r.goals[0].targets[0][2] == pytest.approx(0.1)


def test_disks_start_where_the_author_stacked_them() -> None:
    r = import_cliport(TASKS / "towers_of_hanoi_seq.py", seed=0)
    env = FactaskEnv(r.graph)
    try:
        env.reset(seed=3)
        poses = env.object_poses()
    finally:
        env.close()
    disks = [v for v in r.graph.variables if v.kind == "cylinder"]
    assert all(isinstance(d.initial, StartOn) and d.initial.offset is not None for d in disks)
    xy = {tuple(np.round(poses[d.name].pos[:2], 4)) for d in disks}
    assert len(xy) == 1  # one column, on the author's peg, every seed
    stand = r.graph.variable("stand_brown_0")
    peg = np.array(xy.pop())
    assert np.linalg.norm(peg - [stand.initial.x, stand.initial.y]) > 0.05  # not centred


def test_one_given_place_for_several_objects_is_refused() -> None:
    host = StateVariable(name="stand", kind="stand")
    blocks = StateVariable(name="blocks", kind="block", count=2,
                           initial=StartOn(support="stand", offset=(0.0, 0.0)))
    with pytest.raises(GraphValidationError, match="one place given for 2 objects"):
        TaskGraph(name="t", variables=[host, blocks]).ensure_valid()


def test_a_refusal_the_task_catches_is_still_reported(tmp_path: Path) -> None:
    task = tmp_path / "swallows.py"
    task.write_text('''
import numpy as np
from cliport.tasks.task import Task


class Swallows(Task):
    def reset(self, env):
        super().reset(env)
        ids = []
        try:
            ids.append(env.add_object("google/object-template.urdf",
                                      ((0.5, 0.0, 0.02), (0, 0, 0, 1))))
        except Exception:
            pass
        np.random.randint(1, len(ids) + 1 - 1 or 1)  # fails later, as GenSim code does
''')
    with pytest.raises(Unsupported, match=r"refused .*Google scanned objects"):
        import_cliport(task, seed=0)


@settings(max_examples=60, deadline=None)
@given(roll=st.floats(-np.pi, np.pi), pitch=st.floats(-np.pi / 2, np.pi / 2),
       yaw=st.floats(-np.pi, np.pi))
def test_a_tilted_target_is_placed_upright_with_a_warning(roll: float, pitch: float,
                                                          yaw: float) -> None:
    from factask.compat.cliport.goals import TARGET_TILT_WARN_DEG, target_pose
    from factask.geometry import tilt_deg

    quat = np.asarray(cutils.eulerXYZ_to_quatXYZW((roll, pitch, yaw)))
    warnings: list[str] = []
    pose = target_pose(np.array([0.5, 0.1, 0.02]), quat, 0.04, None, "goal 0 target 0",
                       warnings.append)
    tilt = tilt_deg(np.array([quat[3], quat[0], quat[1], quat[2]]))
    off = min(tilt, 180.0 - tilt)
    if off > TARGET_TILT_WARN_DEG + 1e-6:
        assert len(warnings) == 1 and "tilted" in warnings[0] and "goal 0 target 0" in warnings[0]
    elif off < TARGET_TILT_WARN_DEG - 1e-6:
        assert not warnings
    assert pose.x == 0.5 and pose.y == 0.1 and -180.0 <= pose.yaw_deg <= 180.0


def test_boxes_added_at_their_targets_start_at_random_spots(tmp_path: Path) -> None:
    result = import_cliport(TASKS / "boxes_added_at_their_targets.py")
    assert any("start at the targets the goal gives them" in w for w in result.warnings)
    starts = [v.initial for v in result.graph.variables if v.kind == "box"]
    assert len(starts) == 2 and all(type(s).__name__ == "OnTable" for s in starts)
    # one box left out of its planned pose: the goal is not met at the start, and the
    # author's starts stand
    src = (TASKS / "boxes_added_at_their_targets.py").read_text()
    moved = tmp_path / "one_moved_out.py"
    moved.write_text(src.replace(
        "            targs.append(pose)\n",
        "            targs.append(pose)\n"
        "            if k == 1:\n"
        "                p.resetBasePositionAndOrientation(boxes[-1], (0.3, 0.4, 0.02),"
        " (0, 0, 0, 1))\n").replace("import numpy as np\n",
                                    "import numpy as np\nimport pybullet as p\n"))
    other = import_cliport(moved)
    assert not any("start at the targets" in w for w in other.warnings)


def test_the_palette_iterates_gensims_colours_and_looks_up_factasks() -> None:
    names = list(cutils.COLORS)
    assert len(cutils.COLORS) == 16 and names == cutils.COLORS_NAMES
    assert names[:11] == ["blue", "red", "green", "orange", "yellow", "purple", "pink",
                          "cyan", "brown", "white", "gray"]
    assert cutils.COLORS["olive"] and "olive" not in cutils.COLORS  # looked up, not iterated
    assert cutils.COLORS.get("no-such-colour") is None
    with pytest.raises(KeyError):
        cutils.COLORS["no-such-colour"]
    assert cutils.get_colors_names("train") == cutils.TRAIN_COLORS
    assert cutils.get_colors_names("test") == cutils.EVAL_COLORS
    assert cutils.get_colors_names("full") == cutils.TRAIN_COLORS + cutils.EVAL_COLORS
    rgb, picked = cutils.get_colors("train", n_colors=3)
    assert len(set(picked)) == 3 and set(picked) <= set(cutils.TRAIN_COLORS) and len(rgb) == 3
