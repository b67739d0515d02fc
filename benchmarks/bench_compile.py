"""Measure compile time (graph -> MJCF -> MuJoCo model) against the number of objects.

Run: ``.venv/bin/python benchmarks/bench_compile.py [--quick] [--repeats N]``.

Graphs are built programmatically: ``n`` red blocks to put into one green zone,
written two ways:

- ``group``: one ``in_zone`` factor over count variables (one variable of count
  ``n``; above the count limit of 64, several variables of at most 50 each);
- ``separate``: ``n`` single-block variables, one ``in_zone`` factor each.

Both give ``n`` free bodies plus ``n`` goal markers plus the floating robot.
For each ``n`` the median of a few repeats is printed, split into the MJCF build
(:func:`~factask.sim.compile.build_mjcf` plus ``to_xml_string``) and the MuJoCo
compile (``MjModel.from_xml_string``). Wall times depend on the machine and its
load; nothing here asserts a time.
"""

from __future__ import annotations

import argparse
import statistics
import time
from dataclasses import dataclass

import mujoco

import factask as ft
from factask.sim.assets import XML_PRECISION
from factask.sim.compile import build_mjcf, compile_graph

#: Object counts measured by default and with ``--quick``.
SIZES = (1, 2, 5, 10, 20, 50, 100)
QUICK_SIZES = (1, 10, 50)
#: Largest count per variable in the ``group`` layout (the model allows 64).
GROUP_MAX = 50
LAYOUTS = ("group", "separate")


def blocks_in_zone(n: int, layout: str = "group") -> ft.TaskGraph:
    """A valid graph that puts ``n`` blocks into one zone.

    Args:
        n: Number of block instances (>= 1).
        layout: "group" (count variables, one factor) or "separate" (one variable
            and one factor per block).

    Returns:
        The validated graph.
    """
    zone = ft.StateVariable(name="zone", kind="zone", color="green", size=(0.3, 0.3, 0.001))
    if layout == "group":
        counts = [GROUP_MAX] * (n // GROUP_MAX) + ([n % GROUP_MAX] if n % GROUP_MAX else [])
        blocks = [ft.StateVariable(name=f"blocks_{i}", kind="block", color="red", count=c)
                  for i, c in enumerate(counts)]
        factors = [ft.SubtaskFactor(name="place", description=f"put the {n} blocks in the zone",
                                    goal=ft.InZone(objects=[b.name for b in blocks],
                                                   zone="zone"))]
    elif layout == "separate":
        blocks = [ft.StateVariable(name=f"block_{i}", kind="block", color="red")
                  for i in range(n)]
        factors = [ft.SubtaskFactor(name=f"place_{i}", description=f"put block {i} in the zone",
                                    goal=ft.InZone(objects=[b.name], zone="zone"), weight=1 / n)
                   for i, b in enumerate(blocks)]
    else:
        raise ValueError(f"layout must be one of {LAYOUTS}, got {layout!r}")
    return ft.TaskGraph(name=f"blocks-{layout}-{n}", description=f"{n} blocks into a zone",
                        variables=[*blocks, zone], factors=factors).ensure_valid()


@dataclass(frozen=True)
class CompileTiming:
    """Median wall times (s) of one graph's compile and its parts."""

    n: int
    layout: str
    total: float
    mjcf: float
    mujoco: float
    nbody: int
    ngeom: int


def time_compile(graph: ft.TaskGraph, n: int, layout: str, repeats: int,
                 robot: str = "floating") -> CompileTiming:
    """Median over ``repeats`` of compile_graph and of its two halves."""
    totals, mjcfs, mjs = [], [], []
    model = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        scene = compile_graph(graph, robot=robot)
        totals.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        root, _ = build_mjcf(graph, robot)
        xml = root.to_xml_string(precision=XML_PRECISION)
        t1 = time.perf_counter()
        model = mujoco.MjModel.from_xml_string(xml)
        t2 = time.perf_counter()
        mjcfs.append(t1 - t0)
        mjs.append(t2 - t1)
        del scene
    assert model is not None
    return CompileTiming(n, layout, statistics.median(totals), statistics.median(mjcfs),
                         statistics.median(mjs), model.nbody, model.ngeom)


def run(quick: bool = False, repeats: int | None = None,
        layouts: tuple[str, ...] = LAYOUTS) -> list[CompileTiming]:
    """Measure and print the table; return the timings."""
    sizes = QUICK_SIZES if quick else SIZES
    repeats = repeats or (3 if quick else 5)
    # Warm-up: the first compile pays for imports and asset caches.
    compile_graph(blocks_in_zone(1), robot="floating")
    print(f"compile time vs objects (robot floating, median of {repeats}; seconds)")
    print(f"{'layout':9s} {'n':>4s} {'bodies':>6s} {'geoms':>6s} {'total':>8s} "
          f"{'mjcf+xml':>9s} {'mujoco':>8s} {'mjcf %':>7s} {'ms/object':>9s}")
    out = []
    for layout in layouts:
        for n in sizes:
            t = time_compile(blocks_in_zone(n, layout), n, layout, repeats)
            out.append(t)
            share = 100 * t.mjcf / (t.mjcf + t.mujoco)
            print(f"{layout:9s} {n:4d} {t.nbody:6d} {t.ngeom:6d} {t.total:8.3f} "
                  f"{t.mjcf:9.3f} {t.mujoco:8.3f} {share:6.0f}% {1000 * t.total / n:9.1f}")
    for layout in layouts:
        rows = [t for t in out if t.layout == layout]
        if len(rows) >= 2:
            a, b = rows[0], rows[-1]
            slope = (b.total - a.total) / (b.n - a.n) * 1000
            print(f"{layout}: marginal cost {slope:.1f} ms per extra object "
                  f"(n={a.n} -> {b.n}: {b.total / a.total:.1f}x the time)")
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="fewer sizes and repeats")
    parser.add_argument("--repeats", type=int, default=None)
    parser.add_argument("--layout", choices=[*LAYOUTS, "both"], default="both")
    args = parser.parse_args()
    layouts = LAYOUTS if args.layout == "both" else (args.layout,)
    run(args.quick, args.repeats, layouts)


if __name__ == "__main__":
    main()
