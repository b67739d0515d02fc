"""Measure the suction robots: wall and simulated time per pick-and-place, IK speed, reach.

Run: ``.venv/bin/python benchmarks/bench_robot.py [--repeats N]``. Wall times
depend on the machine and its load; simulated times do not.
"""

from __future__ import annotations

import argparse
import itertools
import statistics
import time

import mujoco
import numpy as np

from factask.geometry import Pose
from factask.sim.robots.attach import attach_robot, make_robot
from factask.sim.robots.ik import TopDownIK, top_down_pose
from factask.sim.robots.registry import ROBOTS

BLOCK = 0.04
#: (pick xy, place xy) pairs spread over the workspace.
MOVES = (((0.4, 0.2), (0.65, -0.3)), ((0.3, -0.4), (0.7, 0.4)), ((0.6, 0.0), (0.35, 0.35)))


def _scene(kind: str, xy: tuple[float, float]):
    spec = mujoco.MjSpec()
    spec.modelname = "bench"
    spec.option.timestep = 0.002
    table = spec.worldbody.add_body(name="table")
    table.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.6, 0.7, 0.02], pos=[0.5, 0, -0.02])
    body = spec.worldbody.add_body(name="block", pos=[xy[0], xy[1], BLOCK / 2])
    body.add_freejoint()
    body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[BLOCK / 2] * 3, mass=0.1)
    attach_robot(spec, kind)
    model = spec.compile()
    data = mujoco.MjData(model)
    robot = make_robot(kind, model, data)
    for _ in range(50):
        mujoco.mj_step(model, data)
    return model, data, robot


def bench_primitive(kind: str, repeats: int) -> None:
    """Print wall / simulated seconds per pick-and-place and the placement error."""
    walls, sims, errs = [], [], []
    for _, (src, dst) in itertools.product(range(repeats), MOVES):
        model, data, robot = _scene(kind, src)
        t0 = time.perf_counter()
        res = robot.pick_and_place(
            Pose.from_xyz_yaw(*src, BLOCK), Pose.from_xyz_yaw(*dst, BLOCK + 0.002)
        )
        walls.append(time.perf_counter() - t0)
        sims.append(res.sim_steps * model.opt.timestep)
        errs.append(float(np.linalg.norm(data.xpos[model.body("block").id][:2] - dst)))
        assert res.ok, res.reason
    print(
        f"{kind:9s} wall {statistics.median(walls):.3f} s (max {max(walls):.3f})  "
        f"sim {statistics.median(sims):.2f} s  xy error max {max(errs) * 1000:.2f} mm  "
        f"n={len(walls)}"
    )


def bench_ik() -> None:
    """Print IK time per QP solve and top-down reach over the workspace grid."""
    for arm in (entry.arm for entry in ROBOTS.values() if entry.arm is not None):
        ik = TopDownIK(arm)
        worst, misses = 0.0, []
        t0 = time.perf_counter()
        for x, y, z in itertools.product((0.25, 0.5, 0.75), (-0.5, 0.0, 0.5), (0.0, 0.15, 0.3)):
            ik.set_q(ik.home)
            _, pos_err, _ = ik.solve(top_down_pose([x, y, z], 0.0), max_iterations=400)
            worst = max(worst, pos_err)
            if pos_err > 0.002:
                misses.append((x, y, z, round(pos_err, 3)))
        per = (time.perf_counter() - t0) / ik.solve_calls * 1000
        print(f"{arm.name}: {per:.3f} ms per IK solve, worst error {worst * 1000:.1f} mm, "
              f"misses {misses}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=2)
    args = parser.parse_args()
    bench_ik()
    for kind in ROBOTS:  # every registered robot
        bench_primitive(kind, args.repeats)


if __name__ == "__main__":
    main()
