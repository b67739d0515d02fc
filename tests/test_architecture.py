"""The package map (docs/architecture.md) against the code: every module named,
imports only downwards through the layers, no import cycle."""

from __future__ import annotations

import ast
import functools
import re
from pathlib import Path

import networkx as nx

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "factask"
MAP = ROOT / "docs" / "architecture.md"


#: Package data that happens to be Python: other people's task files, never imported.
DATA = PACKAGE / "data"


def _modules() -> dict[str, Path]:
    out = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        if DATA in path.parents:
            continue
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


MODULES = _modules()


def _imports(path: Path) -> set[str]:
    """factask modules a module imports, at run time or for annotations alone
    (``TYPE_CHECKING`` blocks count: an annotation that names a class above is an arrow
    up all the same)."""
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name.startswith("factask"))
        elif isinstance(node, ast.ImportFrom) and node.module and \
                node.module.startswith("factask"):
            for a in node.names:
                sub = f"{node.module}.{a.name}"
                found.add(sub if sub in MODULES else node.module)
    return found


@functools.cache
def import_graph() -> nx.DiGraph:
    """Every module and the factask modules it imports (built once: callers only read it)."""
    g = nx.DiGraph()
    for name, path in MODULES.items():
        g.add_node(name)
        for target in _imports(path):
            assert target in MODULES, f"{name} imports {target}, which does not exist"
            if target != name:
                g.add_edge(name, target)
    return g


def _layer_table() -> dict[str, int]:
    table: dict[str, int] = {}
    for line in MAP.read_text().splitlines():
        m = re.match(r"^\|\s*(\d+)\s*\|(.*)\|\s*$", line)
        if m:
            for name in re.findall(r"`([\w.]+)`", m.group(2)):
                table[name] = int(m.group(1))
    return table


def layer_of(module: str, table: dict[str, int]) -> int:
    """The layer of the most specific table entry naming the module or a parent."""
    parts = module.split(".")
    for k in range(len(parts), 0, -1):
        prefix = ".".join(parts[:k])
        if prefix in table:
            return table[prefix]
    raise AssertionError(f"{module} is in no layer of docs/architecture.md")


def test_the_map_names_every_module_and_no_other() -> None:
    named = set(re.findall(r"^- `([\w.]+)` — ", MAP.read_text(), flags=re.MULTILINE))
    missing = sorted(set(MODULES) - named)
    stale = sorted(named - set(MODULES))
    assert not missing, f"docs/architecture.md does not name: {missing}"
    assert not stale, f"docs/architecture.md names modules that do not exist: {stale}"


def test_there_is_no_import_cycle() -> None:
    g = import_graph()
    cycles = list(nx.simple_cycles(g))
    assert not cycles, f"import cycles: {cycles[:5]}"


def test_imports_run_downwards_through_the_layers() -> None:
    table = _layer_table()
    assert table, "docs/architecture.md has no layer table"
    upward = []
    for a, b in import_graph().edges:
        la, lb = layer_of(a, table), layer_of(b, table)
        if lb > la:
            upward.append(f"{a} (layer {la}) imports {b} (layer {lb})")
    assert not upward, "\n".join(upward)


def test_the_graph_model_relations_and_scene_import_no_simulator_or_llm() -> None:
    """The layers up to the reset's layout stay pure: no MuJoCo, dm_control or litellm
    import anywhere in them."""
    table = _layer_table()
    heavy = ("mujoco", "dm_control", "litellm")
    for name, path in MODULES.items():
        if layer_of(name, table) > table["factask.sim.layout"]:
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            roots = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                     [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            bad = [r for r in roots if r.split(".")[0] in heavy]
            assert not bad, f"{name} imports {bad}"


#: No module is longer than this (lines).
MAX_MODULE_LINES = 600


def test_no_module_is_longer_than_the_limit() -> None:
    long = [f"{name} ({path.read_text().count(chr(10))} lines)" for name, path in MODULES.items()
            if path.read_text().count("\n") > MAX_MODULE_LINES]
    assert not long, f"split these: {long}"


def unit_of(module: str) -> str:
    """The package a module lives in (a module directly under ``factask`` is a unit of its
    own: ``factask.geometry``; a package's ``__init__`` belongs to that package)."""
    path = MODULES[module]
    if path.name == "__init__.py" or module.count(".") == 1:
        return module
    return module.rsplit(".", 1)[0]


def test_packages_import_each_other_without_a_circle() -> None:
    """The house by rooms: with every module folded into its package, the arrows between
    packages form no circle either (``factask.sim.robots`` never imports from
    ``factask.sim``'s own modules, which import it)."""
    units = nx.DiGraph()
    for a, b in import_graph().edges:
        if unit_of(a) != unit_of(b):
            units.add_edge(unit_of(a), unit_of(b))
    cycles = list(nx.simple_cycles(units))
    assert not cycles, f"package cycles: {cycles[:5]}"
