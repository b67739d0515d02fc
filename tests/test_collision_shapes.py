"""The layout's collision rule against exact shapes: a round footprint is a disk, a
box's a turned rectangle; they collide when their gap is under the clearance."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import assume, given
from hypothesis import strategies as st

from factask.geometry import Pose
from factask.scene.collision import CLEARANCE, Occupancy
from factask.scene.objects import SceneObject


def _obj(name: str, kind: str, size: tuple[float, float, float]) -> SceneObject:
    return SceneObject(name=name, variable=name, index=0, kind=kind, size=size, color="red",
                       fixed=False, symmetry_deg=90.0, mass=0.1, collides=True)


BLOCK = _obj("block", "block", (0.04, 0.04, 0.04))
CYLINDER = _obj("cylinder", "cylinder", (0.12, 0.12, 0.04))


def _exact_gap(x: float, y: float, yaw: float) -> float:
    """Gap between the cylinder's disk at the origin and the block at (x, y, yaw)."""
    c, s = math.cos(-yaw), math.sin(-yaw)
    local = np.abs([c * -x - s * -y, s * -x + c * -y])
    outside = np.maximum(local - 0.02, 0.0)
    return float(np.linalg.norm(outside)) - 0.06


def _free(x: float, y: float, yaw: float) -> bool:
    occ = Occupancy()
    occ.put("cylinder", CYLINDER, Pose.from_xyz_yaw(0.0, 0.0, 0.02, 0.0))
    return bool(occ.free_mask(BLOCK, [Pose.from_xyz_yaw(x, y, 0.02, yaw)])[0])


def test_a_turned_block_beside_a_disk_where_its_square_would_reach_is_free() -> None:
    # On the diagonal, turned 45 degrees: the block's corner is inside the disk's
    # bounding square but 1.2 cm clear of the disk itself.
    corner = 0.06 + 0.012  # the block's nearest corner, on the diagonal
    assert corner < 0.06 * math.sqrt(2)  # inside the disk's square
    x = y = (corner + 0.02 * math.sqrt(2)) / math.sqrt(2)
    assert _exact_gap(x, y, math.pi / 4) > CLEARANCE
    assert _free(x, y, math.pi / 4)


def test_a_block_touching_the_disk_collides() -> None:
    assert not _free(0.08 + 0.005, 0.0, 0.0)  # 5 mm gap, under the 1 cm clearance
    assert _free(0.08 + 0.011, 0.0, 0.0)


@given(st.floats(-0.2, 0.2), st.floats(-0.2, 0.2), st.floats(-math.pi, math.pi))
def test_disk_and_box_collide_exactly_when_their_gap_is_under_the_clearance(
        x: float, y: float, yaw: float) -> None:
    gap = _exact_gap(x, y, yaw)
    assume(abs(gap - CLEARANCE) > 1e-6)
    assert _free(x, y, yaw) == (gap >= CLEARANCE)
