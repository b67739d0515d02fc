"""Things that start inside a drawer, shut or open (the reset's layout).

A drawer's cabinet is no obstacle to what lies in the drawer (the drawer stands a
gap below its bay's ceiling), so a block can start in a shut drawer, in the part
of it the open drawer shows (where a top-down robot reaches it); a thing too tall
for the drawer's bay is refused at once with its height and the bay's.
"""

from __future__ import annotations

import numpy as np
import pytest

from factask.library.builders import assemble, start_inside, use, var
from factask.library.catalog_articulated import TWO_DRAWERS, cabinet
from factask.library.conventions import ZONE
from factask.library.tasks import get_task
from factask.scene.cabinet import drawer_opening, drawer_shown_area
from factask.scene.objects import placement_area
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode
from factask.vocabulary.errors import FactaskError


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_block_starts_inside_a_shut_drawer(seed: int) -> None:
    env = FactaskEnv(get_task("take-block-out-of-shut-drawer"))
    try:
        env.reset(seed=seed)
        objs, poses = env.objects, env.object_poses()
        drawer, block = poses["top_drawer"], poses["red_block"]
        opening = drawer_opening(objs["cabinet"], poses["cabinet"], objs["top_drawer"],
                                 drawer)
        assert abs(opening) < 0.02
        # The block lies on the drawer's floor, where the open drawer will show it.
        local = block.pos - drawer.pos
        assert np.all(np.abs(local[:2]) < np.array(objs["top_drawer"].size[:2]) / 2)
        assert local[2] < 0.0
        shown = drawer_shown_area(objs["top_drawer"], drawer)
        assert shown.contains(block.pos[:2])[0]
        assert shown.half[0] < placement_area(objs["top_drawer"], drawer).half[0]
        assert not env.status().success
    finally:
        env.close()


@pytest.mark.parametrize("robot", ["floating", "arm"])
def test_the_oracle_opens_the_shut_drawer_and_takes_the_block_out(robot: str) -> None:
    assert run_episode(get_task("take-block-out-of-shut-drawer"), seed=3, robot=robot).success


def test_a_thing_too_tall_for_its_drawer_is_refused_naming_both_heights() -> None:
    box, drawers = cabinet(TWO_DRAWERS)
    tall = var("red_block", "block", "red", (0.04, 0.04, 0.12),
               initial=start_inside(drawers["top"]))
    zone = var("green_zone", "zone", "green", ZONE)
    graph = assemble("tall", "Take the tall red block out of the top drawer.",
                     use("open_drawer", drawer=drawers["top"]),
                     use("place_in_zone", objects=tall, zone=zone),
                     extra=[box, drawers["bottom"]])
    env = FactaskEnv(graph)
    try:
        with pytest.raises(FactaskError, match=r"12\.0 cm tall.*'top_drawer'.*would not close"):
            env.reset(seed=0)
    finally:
        env.close()
