"""Every registered robot (and alias) builds through compile_graph, FactaskEnv and
``factask run --robot``: the registry is the one list of robots."""

from __future__ import annotations

import json

import pytest
from helpers import make_graph
from typer.testing import CliRunner

from factask.cli import app
from factask.sim.build.compile import CompileError, compile_graph
from factask.sim.env import FactaskEnv
from factask.sim.robots.registry import ALIASES, ROBOT_NAMES, ROBOTS, RobotError, robot_entry
from factask.vocabulary.errors import FactaskError

GRAPH = make_graph([{"name": "red_block", "kind": "block", "color": "red"},
                    {"name": "zone", "kind": "zone"}],
                   [{"name": "place", "goal": {"type": "in_zone", "objects": ["red_block"],
                                               "zone": "zone"}}])


def test_names_and_aliases() -> None:
    assert set(ROBOTS) == {"floating", "ur10e", "ur5e"}
    assert (*ROBOTS, *ALIASES) == ROBOT_NAMES
    for alias, target in ALIASES.items():
        assert robot_entry(alias) is ROBOTS[target]
    for name, entry in ROBOTS.items():
        assert entry.name == name and entry.models
        assert (entry.arm is None) == (name == "floating")
        if entry.arm is not None:
            assert entry.arm.name == name, "an arm entry is named after the arm it models"


def test_unknown_robot_is_a_typed_error_naming_every_robot() -> None:
    with pytest.raises(RobotError) as err:
        robot_entry("gripper")
    assert isinstance(err.value, FactaskError)
    assert all(n in str(err.value) for n in ROBOT_NAMES)
    with pytest.raises(CompileError, match="ur10e"):
        compile_graph(GRAPH, robot="gripper")


@pytest.mark.parametrize("name", ROBOT_NAMES)
def test_every_robot_compiles_and_runs_in_the_env(name: str) -> None:
    scene = compile_graph(GRAPH, robot=name)
    assert scene.model.site("suction_tip").id >= 0
    env = FactaskEnv(GRAPH, robot=name)
    try:
        _, info = env.reset(seed=0)
        assert info["failure"] is None
        assert env.robot.grasped() is None
    finally:
        env.close()


@pytest.mark.parametrize("name", list(ROBOTS))
def test_every_robot_runs_from_the_command_line(name: str, tmp_path) -> None:
    path = tmp_path / "task.json"
    path.write_text(GRAPH.to_json())
    result = CliRunner().invoke(app, ["run", str(path), "--robot", name, "--json"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.output.strip().splitlines()[-1])["episodes"][0]["success"]


def test_the_command_line_rejects_an_unknown_robot(tmp_path) -> None:
    path = tmp_path / "task.json"
    path.write_text(GRAPH.to_json())
    result = CliRunner().invoke(app, ["run", str(path), "--robot", "gripper"])
    assert result.exit_code == 2
    assert "ur10e" in result.output


@pytest.mark.parametrize("command", ["generate", "benchmark"])
def test_the_generation_commands_reject_an_unknown_robot(command: str, tmp_path) -> None:
    """Checked before any LLM is configured or called."""
    args = [command, "x: y"] if command == "generate" else [command, "--out", str(tmp_path)]
    tasks = tmp_path / "tasks.json"
    tasks.write_text('[{"name": "x", "description": "y"}]')
    if command == "benchmark":
        args += ["--tasks", str(tasks)]
    result = CliRunner().invoke(app, [*args, "--robot", "gripper"])
    assert result.exit_code == 2, result.output
    assert "ur10e" in result.output


def test_the_verifier_takes_every_robot_and_refuses_others() -> None:
    from factask.gen.verify import Verifier

    for name in ROBOT_NAMES:
        assert Verifier(episodes=1, robot=name).robot == name
    with pytest.raises(RobotError):
        Verifier(episodes=1, robot="gripper")


def test_the_robot_docs_name_every_registered_robot() -> None:
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "docs" / "robot.md").read_text()
    missing = [n for n in ROBOT_NAMES if f'`"{n}"`' not in text]
    assert not missing, f"docs/robot.md does not name {missing}"
