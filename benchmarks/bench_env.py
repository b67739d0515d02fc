"""Measure the environment's overhead over bare MuJoCo on the same compiled model.

Run: ``.venv/bin/python benchmarks/bench_env.py [--quick] [--task NAME] [--robot ...]``.

For each robot ("floating" mocap cup, "arm" suction arm) on one library task:

- **settled us**: ``mujoco.mj_step`` alone on the environment's own model, from a
  copy of its state just after ``reset`` (a settled scene: no contacts changing);
- **bare us**: ``mujoco.mj_step`` alone from the very states the actions went
  through (:mod:`physics_floor`: the same actions are replayed and every 10th
  state is kept; each is stepped twice right after every timed run of the
  actions below, and its least time over the runs kept: both sides measured
  under the same load), the physics lower bound of a step;
- **env us**: wall time of the ``env.step`` calls (whole pick-and-places chosen
  by the oracle; the oracle's planning is not timed; the same actions run 5
  times from the same reset, each action's least time kept) divided by the
  physics steps they took, and **ratio** = env / bare: the price of everything
  around the physics (motion planning, IK for the arm, contact tests during
  guarded moves, health checks, the goal checks after each action);
- **bare cpu**, **env cpu**, **cpu ratio**: the same in this thread's CPU time
  (``time.thread_time``), which other jobs on a shared machine cannot inflate
  (a long ``env.step`` is preempted, a 30 us bare step rarely is): the ratio to
  read on a loaded machine;
- **wall s per pick-and-place** (median over the episode's actions) and the
  simulated seconds it stood for (real-time factor = simulated / wall);
- **reset**: median wall time of ``env.reset(seed=k)`` (layout sampling, relation
  solving and the settling physics, until the objects rest);
- **replay cpu**: CPU time per step of the same run replayed with nothing around
  the physics (:func:`physics_floor.replay_time`: from the run's start state, each
  ``mj_step`` call with the inputs it had -- controls, mocap poses, the suction
  weld -- restored by one ``mj_setState``); **seq** = replay / bare: what the steps
  cost in sequence over the bare step from a restored state (caches, the inputs'
  writes), **around** = env / replay: what ``env.step`` adds around those steps
  (cpu ratio = seq x around).

Wall times depend on the machine and its load; nothing here asserts a time.
"""

from __future__ import annotations

import argparse
import copy
import math
import statistics
import time
from dataclasses import dataclass

import mujoco
import numpy as np
import physics_floor

from factask.library import get_task
from factask.sim.env import FactaskEnv
from factask.sim.oracle.scripted import Oracle

#: Default task: six stacking pick-and-places of blocks.
DEFAULT_TASK = "rainbow-stack"
#: The fast robot and the default arm (two names of :data:`factask.sim.robots.registry.ROBOTS`).
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
    env_cpu_us: float
    bare_cpu_us: float
    cpu_ratio: float
    inner_step_us: float
    physics_share: float
    replay_cpu_us: float
    replay_drift: float
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
               bare_steps: int, repeats: int = 5) -> EnvTiming:
    """Measure one task with one robot (see the module docstring).

    The oracle's actions are chosen once; then the same actions are timed
    ``repeats`` times from the same reset (deterministic physics: the same steps)
    and each action's least wall and CPU time kept.
    """
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
        actions = []
        for _ in range(max_actions):
            action = oracle.act()
            if action is None:
                break
            actions.append(action)
            _, _, terminated, truncated, _ = env.step(action)
            if terminated or truncated:
                break
        # The same actions once more, recording the states they pass through: the
        # bare mj_step of exactly those states.
        env.reset(seed=0)
        with physics_floor.record() as rec:
            for action in actions:
                env.step(action)
        # ... and once recording each mj_step call's inputs: the same steps replayed
        # with nothing around them (physics_floor.replay_time).
        env.reset(seed=0)
        with physics_floor.record_inputs(env.model, env.data) as inputs:
            for action in actions:
                env.step(action)
        walls = [math.inf] * len(actions)
        cpus = [math.inf] * len(actions)
        bare_w = bare_c = None
        replay_cpu, drift = math.inf, 0.0
        for _ in range(repeats):
            env.reset(seed=0)
            for i, action in enumerate(actions):
                w0, c0 = time.perf_counter(), time.thread_time()
                env.step(action)
                cpus[i] = min(cpus[i], time.thread_time() - c0)
                walls[i] = min(walls[i], time.perf_counter() - w0)
            # Right after each round, the bare steps (least per state over the rounds):
            # both sides measured under the same load, as far as a shared machine allows.
            w, c = physics_floor.bare_step_times(rec, repeats=2)
            bare_w = w if bare_w is None else np.minimum(bare_w, w)
            bare_c = c if bare_c is None else np.minimum(bare_c, c)
            replay, drift = physics_floor.replay_time(inputs)
            replay_cpu = min(replay_cpu, replay.cpu)
        sims = [h.sim_steps * env.model.opt.timestep for h in env.history]
        cost = physics_floor.StepCost(float(bare_w.mean()), float(bare_c.mean()))
        steps = rec.steps
        env_us = sum(walls) / steps * 1e6 if steps else float("nan")
        env_cpu_us = sum(cpus) / steps * 1e6 if steps else float("nan")
        return EnvTiming(
            task=task, robot=robot, bare_steps_per_s=bare, env_step_us=env_us,
            bare_step_us=cost.wall * 1e6, ratio=env_us / (cost.wall * 1e6),
            env_cpu_us=env_cpu_us, bare_cpu_us=cost.cpu * 1e6,
            cpu_ratio=env_cpu_us / (cost.cpu * 1e6),
            inner_step_us=1e6 / bare, physics_share=cost.cpu * 1e6 / env_cpu_us,
            replay_cpu_us=replay_cpu * 1e6, replay_drift=drift,
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
    print(f"env step cost vs bare mujoco.mj_step (task {task}; best of 5 runs of the same "
          "actions; medians over the actions)")
    print(f"{'robot':9s} {'settled us':>10s} {'bare us':>8s} {'env us':>7s} {'ratio':>6s} "
          f"{'bare cpu':>8s} {'env cpu':>7s} {'cpu ratio':>9s} {'wall s/p&p':>10s} "
          f"{'sim s/p&p':>9s} {'x realtime':>10s} {'actions':>7s} {'reset s':>8s} "
          f"{'replay cpu':>10s} {'seq':>5s} {'around':>6s}")
    for t in out:
        print(f"{t.robot:9s} {t.inner_step_us:10.1f} {t.bare_step_us:8.1f} "
              f"{t.env_step_us:7.1f} {t.ratio:6.2f} {t.bare_cpu_us:8.1f} {t.env_cpu_us:7.1f} "
              f"{t.cpu_ratio:9.2f} {t.pick_place_s:10.3f} "
              f"{t.pick_place_sim_s:9.2f} {t.realtime_factor:10.1f} {t.actions:7d} "
              f"{t.reset_s:8.3f} {t.replay_cpu_us:10.1f} "
              f"{t.replay_cpu_us / t.bare_cpu_us:5.2f} {t.env_cpu_us / t.replay_cpu_us:6.2f}")
        if t.replay_drift > 1e-3:
            print(f"  ({t.robot}: the replay ended {t.replay_drift * 1000:.1f} mm/mrad from the "
                  "run: an input it does not restore)")
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
