"""Unit tests of the graph model's error messages, templates and the validate CLI."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from factask.cli import app
from factask.graph import (
    COLOR_NAMES,
    CompositionError,
    GraphValidationError,
    InZone,
    On,
    Stack,
    StateVariable,
    SubtaskFactor,
    SubtaskTemplate,
    TaskGraph,
    TemplateSlot,
    compose,
    parse_graph,
)
from factask.relations import RELATION_TYPES

runner = CliRunner()


def _graph(**overrides) -> dict:
    data = {
        "name": "place-red-in-green",
        "description": "put the red block in the green zone",
        "variables": [
            {"name": "red_block", "kind": "block", "color": "red"},
            {"name": "green_zone", "kind": "zone", "color": "green"},
        ],
        "factors": [
            {"name": "place", "description": "put it there",
             "goal": {"type": "in_zone", "objects": ["red_block"], "zone": "green_zone"}},
        ],
    }
    data.update(overrides)
    return data


def test_valid_graph_parses_and_fills_defaults() -> None:
    g = parse_graph(json.dumps(_graph()))
    assert g.variable("red_block").size == (0.04, 0.04, 0.04)
    assert g.variable("green_zone").is_fixed
    assert g.factor("place").scope == ["red_block", "green_zone"]


def test_missing_scope_variable_names_factor_and_variable() -> None:
    data = _graph()
    data["factors"][0]["goal"]["zone"] = "blue_zone"
    with pytest.raises(GraphValidationError) as info:
        parse_graph(data)
    text = str(info.value)
    assert "place" in text and "blue_zone" in text
    assert info.value.nodes == {"place"}


def test_all_problems_are_reported_at_once() -> None:
    data = _graph()
    data["factors"].append({"name": "again", "weight": 0.5, "after": ["nothing"],
                            "goal": {"type": "stack", "objects": ["red_block"]}})
    with pytest.raises(GraphValidationError) as info:
        parse_graph(data)
    messages = [p.message for p in info.value.problems]
    assert any("unknown factor 'nothing'" in m for m in messages)
    assert any("moved by factors" in m for m in messages)
    assert any("weights sum to 1.5" in m for m in messages)


def test_unknown_colour_lists_the_palette() -> None:
    data = _graph()
    data["variables"][0]["color"] = "ultraviolet"
    with pytest.raises(GraphValidationError) as info:
        parse_graph(data)
    assert "red_block" in str(info.value)
    assert all(c in str(info.value) for c in COLOR_NAMES)


def test_unknown_kind_names_variable_and_lists_kinds() -> None:
    data = _graph()
    data["variables"][1]["kind"] = "hologram"
    with pytest.raises(GraphValidationError) as info:
        parse_graph(data)
    assert "green_zone.kind" in str(info.value) and "'container'" in str(info.value)


@pytest.mark.parametrize("text", ["", "not json", "[1, 2]", '{"name": 3}', "{"])
def test_junk_input_is_a_typed_error(text: str) -> None:
    with pytest.raises(GraphValidationError):
        parse_graph(text)


def test_anchor_kind_must_fit_the_relation() -> None:
    data = _graph()
    data["variables"].append({"name": "ball", "kind": "ball"})
    data["factors"][0]["goal"] = {"type": "on", "objects": ["red_block"], "support": "ball"}
    with pytest.raises(GraphValidationError, match="cannot serve as support"):
        parse_graph(data)


@pytest.mark.parametrize("relation", sorted(
    k for k, cls in RELATION_TYPES.items() if cls.moves_kinds is not None))
def test_a_relation_that_moves_only_some_kinds_names_the_object_and_the_fix(
        relation: str) -> None:
    """Every relation with ``moves_kinds`` refuses a block as its object, naming the
    field, the object's kind and the relation's own fix (one rule, in the base)."""
    cls = RELATION_TYPES[relation]
    variables, goal = cls.example()
    data = goal.model_dump(mode="json", exclude_defaults=True)
    data["type"] = relation
    data["objects"] = ["odd_block"]
    graph = {"name": "t", "description": "t",
             "variables": [*variables, {"name": "odd_block", "kind": "block"}],
             "factors": [{"name": "f", "description": "f", "goal": data}]}
    with pytest.raises(GraphValidationError) as err:
        parse_graph(graph)
    text = str(err.value)
    assert "goal.objects" in text and "'odd_block' is a block" in text
    assert cls.other_kinds_fix in text


def test_cycle_in_order_is_reported() -> None:
    data = _graph()
    data["variables"].append({"name": "blue_block", "kind": "block", "color": "blue"})
    data["factors"] = [
        {"name": "a", "weight": 0.5, "after": ["b"],
         "goal": {"type": "on", "objects": ["red_block"], "support": "blue_block"}},
        {"name": "b", "weight": 0.5,
         "goal": {"type": "on", "objects": ["blue_block"], "support": "red_block"}},
    ]
    with pytest.raises(GraphValidationError, match="cycle"):
        parse_graph(data)


def test_implied_order_puts_support_first() -> None:
    red = StateVariable(name="red", kind="block", color="red")
    blue = StateVariable(name="blue", kind="block", color="blue")
    zone = StateVariable(name="zone", kind="zone", color="green")
    g = TaskGraph(name="t", variables=[red, blue, zone], factors=[
        SubtaskFactor(name="top", weight=0.5, goal=On(objects=["blue"], support="red")),
        SubtaskFactor(name="bottom", weight=0.5, goal=InZone(objects=["red"], zone="zone")),
    ]).ensure_valid()
    assert g.factor_order() == ["bottom", "top"]


STACK = SubtaskTemplate(
    name="stack_column",
    description="stack the {layers}",
    slots=[TemplateSlot(name="layers", many=True, kinds=["block", "box"], movable=True)],
    factors=[SubtaskFactor(name="stack", description="stack the {layers} into a column",
                           goal=Stack(objects=["layers"]))],
)


def test_one_template_used_by_two_tasks_with_different_bindings() -> None:
    red = StateVariable(name="red", kind="block", color="red")
    blue = StateVariable(name="blue", kind="block", color="blue")
    boxes = StateVariable(name="boxes", kind="box", count=3, size=(0.07, 0.07, 0.07))
    t1 = compose(STACK.instantiate(layers=[red, blue]), name="two-blocks").ensure_valid()
    t2 = compose(STACK.instantiate(layers=boxes), name="three-boxes").ensure_valid()
    assert t1.factors[0].goal.objects == ["red", "blue"]
    assert t1.factors[0].description == "stack the red and blue into a column"
    assert t2.factors[0].goal.objects == ["boxes"]
    assert t1.factors[0].template == t2.factors[0].template == "stack_column"


def test_template_binding_errors_name_the_slot() -> None:
    zone = StateVariable(name="zone", kind="zone")
    with pytest.raises(CompositionError, match="layers"):
        STACK.instantiate(layers=[zone])
    with pytest.raises(CompositionError, match="not bound"):
        STACK.instantiate()
    with pytest.raises(CompositionError, match="no such slot"):
        STACK.instantiate(layers=[StateVariable(name="b", kind="block")], tower=[])


def test_compose_rejects_conflicting_shared_variable() -> None:
    a = TaskGraph(name="a", variables=[StateVariable(name="x", kind="block", color="red")])
    b = TaskGraph(name="b", variables=[StateVariable(name="x", kind="block", color="blue")])
    with pytest.raises(CompositionError, match=r"'x'.*color"):
        compose(a, b)
    assert compose(a, b, renames=[None, {"x": "y"}]).variable_names() == ["x", "y"]


def test_cli_validate_missing_variable_exits_1_naming_both(tmp_path: Path) -> None:
    data = _graph()
    data["factors"][0]["goal"]["zone"] = "blue_zone"
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(data))
    result = runner.invoke(app, ["validate", str(path)])
    assert result.exit_code == 1
    assert "place" in result.output and "blue_zone" in result.output


def test_cli_validate_accepts_a_valid_file(tmp_path: Path) -> None:
    path = tmp_path / "ok.json"
    path.write_text(json.dumps(_graph()))
    result = runner.invoke(app, ["validate", str(path)])
    assert result.exit_code == 0, result.output
    assert "valid" in result.output


@pytest.mark.parametrize("content", ["hello", "[]", '{"variables": 5}'])
def test_cli_validate_junk_is_a_clear_error(tmp_path: Path, content: str) -> None:
    path = tmp_path / "junk.json"
    path.write_text(content)
    result = runner.invoke(app, ["validate", str(path)])
    assert result.exit_code == 1
    assert "invalid" in result.output


def test_cli_validate_missing_file_exit_2(tmp_path: Path) -> None:
    result = runner.invoke(app, ["validate", str(tmp_path / "nope.json")])
    assert result.exit_code == 2


def test_cli_schema_is_the_graph_schema() -> None:
    result = runner.invoke(app, ["schema"])
    assert result.exit_code == 0
    schema = json.loads(result.output)
    assert schema == TaskGraph.json_schema()
    assert "StateVariable" in json.dumps(schema)


def test_field_errors_and_graph_errors_come_in_one_round() -> None:
    data = _graph()
    data["variables"][0]["color"] = "ultraviolet"  # a field error on red_block
    data["variables"].append({"name": "blue_block", "kind": "block", "color": "blue"})
    data["factors"][0]["weight"] = 0.5
    data["factors"].append({"name": "on_top", "weight": 0.5,
                            "goal": {"type": "on", "objects": ["blue_block"],
                                     "support": "ghost"}})
    with pytest.raises(GraphValidationError) as info:
        parse_graph(data)
    assert info.value.nodes == {"red_block", "on_top"}
    assert any("ghost" in p.message for p in info.value.problems)
    # Nothing is reported only because red_block was left out of the check.
    assert not any("red_block" in p.message for p in info.value.problems
                   if p.node == "place")


def test_every_public_error_class_of_the_package_is_a_factask_error() -> None:
    """Callers catch ``FactaskError`` for anything factask raises on purpose."""
    import importlib
    import inspect
    import pkgutil

    import factask
    from factask.vocabulary.errors import FactaskError

    stray = []
    for info in pkgutil.walk_packages(factask.__path__, "factask."):
        if info.name.endswith("__main__"):
            continue
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if (inspect.isclass(obj) and issubclass(obj, BaseException)
                    and obj.__module__ == module.__name__ and not name.startswith("_")
                    and not issubclass(obj, FactaskError)):
                stray.append(f"{info.name}.{name}")
    assert not stray, f"not FactaskError subclasses: {stray}"
    from factask.vocabulary.kinds import UnknownKindError
    from factask.vocabulary.palette import UnknownColorError

    assert issubclass(UnknownKindError, ValueError) and issubclass(UnknownColorError, ValueError)


def test_the_package_raises_no_bare_builtin_error() -> None:
    """Every error factask raises is a FactaskError subclass (keeping ValueError,
    KeyError or RuntimeError as a second base where callers rely on it). Exempt:
    AttributeError from module/class ``__getattr__`` (the attribute protocol) and
    SystemExit from a script's entry point."""
    import ast
    import builtins

    exempt = {"AttributeError", "SystemExit"}
    builtin_errors = {name for name, obj in vars(builtins).items()
                      if isinstance(obj, type) and issubclass(obj, BaseException)} - exempt
    root = Path(__file__).resolve().parents[1] / "src" / "factask"
    bare = []
    for path in sorted(root.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Raise) and node.exc is not None:
                exc = node.exc.func if isinstance(node.exc, ast.Call) else node.exc
                if isinstance(exc, ast.Name) and exc.id in builtin_errors:
                    bare.append(f"{path.relative_to(root)}:{node.lineno} raises {exc.id}")
    assert not bare, "\n".join(bare)
