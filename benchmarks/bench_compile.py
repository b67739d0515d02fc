"""Measure compile time (graph -> MJCF -> MuJoCo model) against the number of objects.

Run: ``.venv/bin/python benchmarks/bench_compile.py [--quick] [--repeats N]``.

Graphs are built programmatically: ``n`` red blocks to put into one green zone,
written two ways:

- ``group``: one ``in_zone`` factor over count variables (one variable of count
  ``n``; above the count limit of 64, several variables of at most 50 each);
- ``separate``: ``n`` single-block variables, one ``in_zone`` factor each.

Both give ``n`` free bodies plus ``n`` goal markers plus the floating robot.
For each ``n`` (up to 200) the best of a few repeats of
:func:`~factask.sim.build.compile.compile_graph` on a validated graph
(``validate=False``) is printed, split into building the ``MjSpec``
(:func:`~factask.sim.build.compile.build_spec`) and MuJoCo's compiler
(``spec.compile()``); beside it the graph's own validation
(``graph.ensure_valid()``, which ``compile_graph`` runs first by default; the
graph model's cost, not the compiler's) and, up to 100 objects, the export path
that compile used before (``build_mjcf`` + ``to_xml_string`` +
``MjModel.from_xml_string``, dm_control) and the speed-up, both sides
validating. The curve is saved as ``benchmarks/out/compile_vs_objects.png``. Wall
times depend on the machine and its load; nothing here asserts a time.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import dataclass
from pathlib import Path

import mujoco

import factask as ft
from factask.sim.build.compile import build_mjcf, build_spec, compile_graph
from factask.sim.build.mjcf import XML_PRECISION

#: Object counts measured by default and with ``--quick``.
SIZES = (1, 2, 5, 10, 20, 50, 98, 150, 200)
QUICK_SIZES = (1, 10, 50, 98, 200)
#: From this many blocks on, a graph exceeds the graph model's object limit.
VALID_MAX = 99
#: The slow MJCF path is timed up to this many objects (it only serves as the "before").
MJCF_MAX = 100
#: Where the compile-vs-objects plot goes.
PLOT = Path(__file__).resolve().parent / "out" / "compile_vs_objects.png"
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
    fields = {"name": f"blocks-{layout}-{n}", "description": f"{n} blocks into a zone",
              "variables": [*blocks, zone], "factors": factors}
    if n < VALID_MAX:
        return ft.TaskGraph(**fields).ensure_valid()
    # Above the graph model's size limits the graph is assembled unchecked: the
    # curve measures the compiler, not what a task may hold.
    return ft.TaskGraph.model_construct(**fields)


@dataclass(frozen=True)
class CompileTiming:
    """Best wall times (s) of one graph's compile and its parts.

    Attributes:
        n: Objects (blocks).
        layout: Graph layout.
        total: The whole :func:`compile_graph` of a graph already validated
            (``validate=False``; MjSpec path, the one factask uses).
        spec: Building the ``MjSpec`` (:func:`build_spec`).
        mujoco: ``spec.compile()``.
        mjcf: The export path for comparison: ``build_mjcf`` + ``to_xml_string`` +
            ``MjModel.from_xml_string`` (no robot; it validates the graph too), 0
            when not measured.
        nbody: Bodies of the compiled model.
        ngeom: Geoms of the compiled model.
        validate: ``graph.ensure_valid()`` (the graph model's check, which
            ``compile_graph`` runs first by default), 0 when not measured.
        total_cpu: ``total`` in this thread's CPU time (``time.thread_time``): what
            other jobs on a shared machine cannot add to.
    """

    n: int
    layout: str
    total: float
    spec: float
    mujoco: float
    mjcf: float
    nbody: int
    ngeom: int
    validate: float = 0.0
    total_cpu: float = 0.0


def time_compile(graph: ft.TaskGraph, n: int, layout: str, repeats: int,
                 robot: str = "floating", mjcf: bool = True) -> CompileTiming:
    """Best of ``repeats`` of compile_graph, of its two halves, of the graph's
    validation and of the MJCF path (the best: the run least disturbed by other jobs)."""
    totals, cpus, specs, mjs, mjcfs, checks = [], [], [], [], [], []
    model = None
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.thread_time()
        scene = compile_graph(graph, robot=robot, validate=False)
        cpus.append(time.thread_time() - c0)
        totals.append(time.perf_counter() - t0)
        model = scene.model
        t0 = time.perf_counter()
        spec = build_spec(graph, robot, validate=False)[0]
        t1 = time.perf_counter()
        spec.compile()
        mjs.append(time.perf_counter() - t1)
        specs.append(t1 - t0)
        if n < VALID_MAX:
            t0 = time.perf_counter()
            graph.ensure_valid()
            checks.append(time.perf_counter() - t0)
        if mjcf and n < VALID_MAX:
            t0 = time.perf_counter()
            root, _ = build_mjcf(graph)
            mujoco.MjModel.from_xml_string(root.to_xml_string(precision=XML_PRECISION))
            mjcfs.append(time.perf_counter() - t0)
    assert model is not None
    return CompileTiming(n, layout, min(totals), min(specs), min(mjs),
                         min(mjcfs) if mjcfs else 0.0, model.nbody, model.ngeom,
                         min(checks) if checks else 0.0, min(cpus))


def plot(rows: list[CompileTiming], path: Path) -> None:
    """Save compile time against objects (both paths, both layouts) as a PNG.

    Args:
        rows: Timings from :func:`run`.
        path: Where the picture goes.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=110)
    for layout, style in zip(LAYOUTS, ("-", "--"), strict=True):
        sel = [r for r in rows if r.layout == layout]
        if not sel:
            continue
        ns = [r.n for r in sel]
        ax.plot(ns, [1000 * r.total for r in sel], "o" + style, color="tab:blue",
                label=f"compile_graph (MjSpec), {layout}")
        ax.plot(ns, [1000 * r.mujoco for r in sel], "." + style, color="tab:green",
                label=f"of which spec.compile(), {layout}")
        mj = [(r.n, 1000 * r.mjcf) for r in sel if r.mjcf]
        if mj:
            ax.plot(*zip(*mj, strict=True), "s" + style, color="tab:red",
                    label=f"dm_control MJCF + XML parse (before), {layout}")
    ax.set_xlabel("objects (blocks; each also has a goal marker)")
    ax.set_ylabel("wall ms (best of several)")
    ax.set_title("Compile time vs objects (floating robot)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)


def run(quick: bool = False, repeats: int | None = None,
        layouts: tuple[str, ...] = LAYOUTS, plot_path: Path | None = PLOT) -> list[CompileTiming]:
    """Measure and print the table (and save the plot); return the timings."""
    sizes = QUICK_SIZES if quick else SIZES
    repeats = repeats or (5 if quick else 9)
    # Warm-up: the first compile pays for imports and caches.
    compile_graph(blocks_in_zone(1), robot="floating")
    build_mjcf(blocks_in_zone(1))
    print(f"compile time vs objects (robot floating, best of {repeats}; milliseconds; total "
          "= compile_graph of a validated graph (wall), cpu = the same in CPU time, "
          "validate = graph.ensure_valid)")
    print(f"{'layout':9s} {'n':>4s} {'bodies':>6s} {'geoms':>6s} {'total':>7s} {'cpu':>7s} "
          f"{'spec':>7s} {'compile':>7s} {'ms/obj':>6s} {'validate':>8s} {'mjcf path':>9s} "
          f"{'speed-up':>8s}")
    out = []
    for layout in layouts:
        for n in sizes:
            t = time_compile(blocks_in_zone(n, layout), n, layout, repeats,
                             mjcf=n <= MJCF_MAX)
            out.append(t)
            # Speed-up: both sides validate the graph.
            mj = (f"{1000 * t.mjcf:9.2f} {t.mjcf / (t.total + t.validate):7.1f}x" if t.mjcf
                  else f"{'-':>9s}")
            check = f"{1000 * t.validate:8.2f}" if t.validate else f"{'-':>8s}"
            print(f"{layout:9s} {n:4d} {t.nbody:6d} {t.ngeom:6d} {1000 * t.total:7.2f} "
                  f"{1000 * t.total_cpu:7.2f} {1000 * t.spec:7.2f} {1000 * t.mujoco:7.2f} "
                  f"{1000 * t.total / n:6.3f} "
                  f"{check} {mj}")
    for layout in layouts:
        rows = [t for t in out if t.layout == layout]
        if len(rows) >= 2:
            a, b = rows[0], rows[-1]
            slope = (b.total - a.total) / (b.n - a.n) * 1000
            print(f"{layout}: marginal cost {slope:.3f} ms per extra object "
                  f"(n={a.n} -> {b.n}: {b.total / a.total:.1f}x the time)")
    if plot_path is not None:
        plot(out, plot_path)
        print(f"plot: {plot_path}")
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="fewer sizes and repeats")
    parser.add_argument("--repeats", type=int, default=None)
    parser.add_argument("--layout", choices=[*LAYOUTS, "both"], default="both")
    parser.add_argument("--plot", type=Path, default=PLOT, help="where the PNG goes")
    args = parser.parse_args()
    layouts = LAYOUTS if args.layout == "both" else (args.layout,)
    run(args.quick, args.repeats, layouts, args.plot)


if __name__ == "__main__":
    main()
