"""Measure the environment's overhead over bare MuJoCo on the same compiled model.

Run: ``.venv/bin/python benchmarks/bench_env.py [--quick] [--task NAME] [--robot ...]``.

For each robot ("floating" mocap cup, "arm" suction arm) on one library task:

- **settled us**: ``mujoco.mj_step`` alone on the environment's own model, from a
  copy of its state just after ``reset`` (a settled scene: no contacts changing);
- **bare us/step**: ``mujoco.mj_step`` alone from the very states the actions
  went through (:mod:`physics_floor`: the same actions are replayed and every
  10th state is kept), the physics lower bound of a step;
- **env us/step**: wall time of the ``env.step`` calls (whole pick-and-places
  chosen by the oracle; the oracle's planning is not timed) divided by the
  physics steps they took, and **ratio** = env / bare: the price of everything
  around the physics (motion planning, IK for the arm, contact tests during
  guarded moves, health checks, the goal checks after each action);
  **physics %** = bare / env;
- **wall s per pick-and-place** (median over the episode's actions) and the
  simulated seconds it stood for (real-time factor = simulated / wall);
- **reset**: median wall time of ``env.reset(seed=k)`` (layout sampling, relation
  solving and 0.3 s of settling physics).

Wall times depend on the machine and its load; nothing here asserts a time.
"""

from __future__ import annotations

import argparse
import copy
import statistics
import time
from dataclasses import dataclass

import mujoco
import physics_floor

from factask.library import get_task
from factask.sim.env import FactaskEnv
from factask.sim.oracle import Oracle

#: Default task: six stacking pick-and-places of blocks.
DEFAULT_TASK = "rainbow-stack"
#: The fast robot and the default arm (two names of :data:`factask.sim.robots.ROBOTS`).
ROBOTS = ("floating", "arm")


@dataclass(frozen=True)
class EnvTiming:
    """Figures of one (task, robot) pair (wall seconds unless named otherwise)."""

    task: str
    robot: str
    bare_steps_per_s: float
    env_step_us: float
    bare_step_us: float
    ratio: float
    inner_step_us: float
    physics_share: float
    pick_place_s: float
    pick_place_sim_s: float
    actions: int
    reset_s: float

    @property
    def realtime_factor(self) -> float:
        """Simulated seconds per wall second inside env.step."""
        return self.pick_place_sim_s / self.pick_place_s if self.pick_place_s else 0.0


def bare_steps_per_second(model: mujoco.MjModel, data: mujoco.MjData, steps: int) -> float:
    """Physics steps per second of ``mj_step`` alone, on a copy of ``data``."""
    d = copy.copy(data)
    mujoco.mj_step(model, d)  # warm-up
    t0 = time.perf_counter()
    for _ in range(steps):
        mujoco.mj_step(model, d)
    return steps / (time.perf_counter() - t0)


def bench_task(task: str, robot: str, max_actions: int, resets: int,
               bare_steps: int) -> EnvTiming:
    """Measure one task with one robot (see the module docstring)."""
    env = FactaskEnv(get_task(task), robot=robot)
    try:
        reset_times = []
        for seed in range(1, resets + 1):
            t0 = time.perf_counter()
            env.reset(seed=seed)
            reset_times.append(time.perf_counter() - t0)
        env.reset(seed=0)
        bare = bare_steps_per_second(env.model, env.data, bare_steps)
        oracle = Oracle(env, seed=0)
        actions, walls, sims = [], [], []
        for _ in range(max_actions):
            action = oracle.act()
            if action is None:
                break
            t0 = time.perf_counter()
            _, _, terminated, truncated, _ = env.step(action)
            walls.append(time.perf_counter() - t0)
            actions.append(action)
            sims.append(env.history[-1].sim_steps * env.model.opt.timestep)
            if terminated or truncated:
                break
        # The same actions again from the same reset (deterministic physics), recording
        # the states they pass through: the bare mj_step of exactly those states.
        env.reset(seed=0)
        with physics_floor.record() as rec:
            for action in actions:
                env.step(action)
        step_s = physics_floor.bare_step_seconds(rec)
        steps = sum(h.sim_steps for h in env.history)
        env_us = sum(walls) / steps * 1e6 if steps else float("nan")
        bare_us = step_s * 1e6
        return EnvTiming(
            task=task, robot=robot, bare_steps_per_s=bare, env_step_us=env_us,
            bare_step_us=bare_us, ratio=env_us / bare_us,
            inner_step_us=1e6 / bare, physics_share=bare_us / env_us,
            pick_place_s=statistics.median(walls) if walls else float("nan"),
            pick_place_sim_s=statistics.median(sims) if sims else float("nan"),
            actions=len(walls), reset_s=statistics.median(reset_times),
        )
    finally:
        env.close()


def run(quick: bool = False, task: str = DEFAULT_TASK,
        robots: tuple[str, ...] = ROBOTS) -> list[EnvTiming]:
    """Measure every robot on ``task`` and print the table; return the timings."""
    max_actions = 3 if quick else 6
    resets = 2 if quick else 5
    bare_steps = 2000 if quick else 10000
    out = [bench_task(task, r, max_actions, resets, bare_steps) for r in robots]
    print(f"env step cost vs bare mujoco.mj_step (task {task}; medians over the actions)")
    print(f"{'robot':9s} {'settled us':>10s} {'bare us/step':>12s} {'env us/step':>11s} "
          f"{'ratio':>6s} {'physics %':>9s} {'wall s/p&p':>10s} "
          f"{'sim s/p&p':>9s} {'x realtime':>10s} {'actions':>7s} {'reset s':>8s}")
    for t in out:
        print(f"{t.robot:9s} {t.inner_step_us:10.1f} {t.bare_step_us:12.1f} "
              f"{t.env_step_us:11.1f} {t.ratio:6.2f} "
              f"{t.physics_share:9.0%} {t.pick_place_s:10.3f} "
              f"{t.pick_place_sim_s:9.2f} {t.realtime_factor:10.1f} {t.actions:7d} "
              f"{t.reset_s:8.3f}")
    by_robot = {t.robot: t for t in out}
    if {"floating", "arm"} <= set(by_robot):
        f, a = by_robot["floating"], by_robot["arm"]
        print(f"arm / floating: {a.pick_place_s / f.pick_place_s:.2f}x wall per pick-and-place, "
              f"{a.env_step_us / f.env_step_us:.2f}x env cost per physics step, "
              f"{a.bare_step_us / f.bare_step_us:.2f}x bare mj_step cost")
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="fewer actions, resets, steps")
    parser.add_argument("--task", default=DEFAULT_TASK, help="library task name")
    parser.add_argument("--robot", choices=[*ROBOTS, "both"], default="both")
    args = parser.parse_args()
    robots = ROBOTS if args.robot == "both" else (args.robot,)
    run(args.quick, args.task, robots)


if __name__ == "__main__":
    main()
