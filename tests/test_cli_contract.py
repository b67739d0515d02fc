"""The command line's contract (issue 20, docs/cli.md): every command of the
application has a case here, task inputs in three forms, ``--json``, exit codes,
piped output, escaped text, pictures and video a user can choose."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

from factask.cli import app
from factask.library import get_task

ROOT = Path(__file__).resolve().parents[1]
TASK_FILE = ROOT / "tests" / "cliport_tasks" / "place_red_in_green.py"
ORIGINAL = ROOT / "src" / "factask" / "data" / "cliport_tasks" / "towers_of_hanoi.py"


def _cli(*args: str):
    return CliRunner().invoke(app, [str(a) for a in args])


def _commands() -> list[str]:
    """The commands the application registers (what ``factask --help`` lists)."""
    return sorted(typer.main.get_command(app).commands)  # type: ignore[attr-defined]


def _json(result) -> object:
    """The one JSON value a --json command printed on stdout."""
    assert result.exit_code in (0, 1), result.output
    return json.loads(result.stdout)


#: One fast case per command: arguments (``{tmp}`` is a scratch folder), the exit
#: code, and whether stdout must be one JSON value. A command added to the
#: application without a case here fails test_every_command_has_a_contract_case.
CASES: dict[str, tuple[list[str], int, bool]] = {
    "list": (["list", "--json"], 0, True),
    "show": (["show", "towers-of-hanoi", "--json"], 0, True),
    "validate": (["validate", "{tmp}/hanoi.json", "--json"], 0, True),
    "schema": (["schema"], 0, True),
    "run": (["run", "put-block-in-bowl", "--json"], 0, True),
    "render": (["render", "put-block-in-bowl", "-o", "{tmp}/s.png", "--size", "64x48",
                "--json"], 0, True),
    "demo": (["demo", "--task", "put-block-in-bowl", "--out", "{tmp}/demo", "--json"], 0,
             True),
    "eval-library": (["eval-library", "-n", "1", "-t", "put-block-in-bowl", "--json"], 0,
                     True),
    "import-cliport": (["import-cliport", str(TASK_FILE), "-o", "{tmp}/t.json", "--json"], 0,
                       True),
    "import-cliport-batch": (["import-cliport-batch", "{tmp}/tasks", "-o", "{tmp}/r.jsonl",
                              "--json"], 0, True),
    "import-libero": (["import-libero", str(ROOT / "src" / "factask" / "data" / "libero"
                                            / "libero_goal" / "put_the_bowl_on_the_plate.bddl"),
                       "-o", "{tmp}/l.json"], 0, False),
    # No LLM is called: a bad approach is refused first (bad usage, exit 2).
    "generate": (["generate", "x: y", "-a", "no-such-approach"], 2, False),
    "benchmark": (["benchmark", "-a", "no-such-approach", "-o", "{tmp}/b"], 2, False),
    # The meaning metric: a graph file against a library name, the same task.
    "compare": (["compare", "{tmp}/hanoi.json", "towers-of-hanoi", "--json"], 0, True),
    # The dataset commands (cli/data_cmds.py): bad input, refused before any work.
    "collect": (["collect", "-o", "{tmp}/ds"], 2, False),
    "replay": (["replay", "{tmp}/no-dataset", "--json"], 2, False),
    # Policy evaluation (cli/policy_cmds.py): bad input, refused before any work.
    "eval-policy": (["eval-policy", "oracle", "--split", "nowhere"], 2, False),
}


def test_every_command_has_a_contract_case_and_a_row_in_the_docs() -> None:
    missing = sorted(set(_commands()) - set(CASES))
    assert not missing, f"commands without a contract case here (add one to CASES): {missing}"
    doc = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")
    rows = set(re.findall(r"^\| `([\w-]+)` \|", doc, flags=re.MULTILINE))
    assert set(_commands()) <= rows, (
        f"docs/cli.md has no row for {sorted(set(_commands()) - rows)}")


@pytest.mark.parametrize("name", sorted(CASES))
def test_each_command_keeps_the_contract(name: str, tmp_path: Path) -> None:
    if name not in _commands():  # a case written ahead of its command (work in progress)
        pytest.skip(f"{name} is not a command of this tree")
    args, code, is_json = CASES[name]
    (tmp_path / "hanoi.json").write_text(get_task("towers-of-hanoi").to_json())
    (tmp_path / "tasks").mkdir()
    (tmp_path / "tasks" / TASK_FILE.name).write_text(TASK_FILE.read_text())
    result = _cli(*(a.replace("{tmp}", str(tmp_path)) for a in args))
    assert result.exit_code == code, result.output
    assert "Traceback" not in result.output
    if is_json:
        json.loads(result.stdout)  # one JSON value, nothing else on stdout
    assert name in _cli(name, "--help").output


@pytest.mark.parametrize("command", ["show", "run", "render", "demo"])
def test_task_commands_take_a_name_a_graph_file_and_a_task_file(command: str,
                                                                 tmp_path: Path) -> None:
    graph = tmp_path / "g.json"
    graph.write_text(get_task("place-red-in-green").to_json())
    for k, task in enumerate(["place-red-in-green", graph, TASK_FILE]):
        args = {"show": ["show", task, "--json"],
                "run": ["run", task, "--json"],
                "render": ["render", task, "-o", tmp_path / f"{k}.png", "--size", "48x32",
                           "--json"],
                "demo": ["demo", "--task", task, "--out", tmp_path / f"d{k}", "--json"]}
        data = _json(_cli(*args[command]))
        assert (data.get("name") or data.get("task")) == "place-red-in-green", (command, task)
    unknown = _cli(*(["demo", "--task"] if command == "demo" else [command]), "no-such-task",
                   *(["-o", tmp_path / "x.png"] if command == "render" else []))
    assert unknown.exit_code == 2 and "Traceback" not in unknown.output


def test_the_shipped_cliport_originals_are_task_inputs(tmp_path: Path) -> None:
    data = _json(_cli("show", ORIGINAL, "--json"))
    assert data["name"] == "towers-of-hanoi" and len(data["factors"]) >= 3


def test_list_options_take_commas_and_repeats_alike() -> None:
    both = [_json(_cli("eval-library", "-n", "1", *t, "--json"))
            for t in (["-t", "put-block-in-bowl,align-box-corner"],
                      ["-t", "put-block-in-bowl", "-t", "align-box-corner"])]
    assert [t["task"] for t in both[0]["tasks"]] == [t["task"] for t in both[1]["tasks"]] == [
        "put-block-in-bowl", "align-box-corner"]


def test_user_text_in_square_brackets_is_printed_as_text(tmp_path: Path) -> None:
    data = json.loads(get_task("put-block-in-bowl").to_json())
    data["description"] = "a [red]bracketed[/red] description"
    data["factors"][0]["description"] = "put it [b]in[/b] the bowl"
    path = tmp_path / "[x]task.json"
    path.write_text(json.dumps(data))
    shown = _cli("show", path)
    assert shown.exit_code == 0, shown.output
    text = " ".join(shown.output.split())
    assert "a [red]bracketed[/red] description" in text and "[b]in[/b]" in text
    missing = _cli("run", tmp_path / "[y]missing.json")
    assert missing.exit_code == 2 and "[y]missing.json" in missing.output


def test_version_and_exit_codes_are_in_the_help() -> None:
    from importlib.metadata import version

    assert _cli("--version").output.strip() == f"factask {version('factask')}"
    assert "Exit codes: 0 success; 1" in " ".join(_cli("--help").output.split())


def test_show_draws_a_graph_file_and_a_task_file(tmp_path) -> None:
    from pathlib import Path

    from factask.library import get_task

    graph_file = tmp_path / "g.json"
    graph_file.write_text(get_task("towers-of-hanoi").to_json())
    shown = _cli("show", str(graph_file), "--png", str(tmp_path / "g.png"))
    assert shown.exit_code == 0, shown.output
    assert "milestones count once reached" in shown.output
    assert (tmp_path / "g.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    task_file = Path(__file__).parent / "cliport_tasks" / "place_red_in_green.py"
    shown = _cli("show", str(task_file), "--json")
    assert shown.exit_code == 0 and '"name"' in shown.output


def test_piped_output_is_plain_lines_nothing_cut() -> None:
    from factask.library import task_names

    listed = _cli("list")
    assert listed.exit_code == 0
    rows = [line.split("\t") for line in listed.stdout.splitlines()]
    assert rows[0][0] == "task" and [r[0] for r in rows[1:]] == task_names()
    evaluated = _cli("eval-library", "--limit", "2", "-n", "1", "-t",
                     "put-block-in-bowl,align-box-corner")
    assert evaluated.exit_code == 0, evaluated.output
    assert "[1/2] put-block-in-bowl: 1/1 episodes succeeded" in evaluated.output
    lines = evaluated.stdout.splitlines()
    assert lines[0].startswith("task\tsuccess") and lines[1].startswith("put-block-in-bowl\t")
    ran = _cli("run", "put-block-in-bowl", "-n", "2", "--seed", "5")
    assert ran.exit_code == 0, ran.output
    rows = [line.split("\t") for line in ran.stdout.splitlines()]
    assert rows[0][:4] == ["seed", "reward", "success", "actions"]
    assert [r[0] for r in rows[1:3]] == ["5", "6"] and rows[1][2] == "yes"
    assert rows[3] == ["put-block-in-bowl: success 100% (completed)"]


def test_run_writes_an_mp4_when_asked_for_one(tmp_path) -> None:
    import av

    video = tmp_path / "episode.mp4"
    result = _cli("run", "place-red-in-green", "--video", str(video))
    assert result.exit_code == 0, result.output
    assert f"video: {video}" in " ".join(result.output.split())
    with av.open(str(video)) as container:
        assert container.streams.video[0].codec_context.name == "h264"
        assert sum(1 for _ in container.decode(video=0)) > 3


def test_render_writes_a_png_of_the_asked_size_reset_or_solved(tmp_path) -> None:
    import imageio.v3 as iio

    for extra in ([], ["--solved", "--camera", "top"]):
        out = tmp_path / f"scene{len(extra)}.png"
        result = _cli("render", "put-block-in-bowl", "-o", str(out), "--size", "320x240",
                      *extra)
        assert result.exit_code == 0, result.output
        image = iio.imread(out)
        assert image.shape == (240, 320, 3) and image.std() > 1.0
    for bad in (["--size", "big"], ["--camera", "side"], ["-o", str(tmp_path / "x.jpg")]):
        args = ["render", "put-block-in-bowl", "-o", str(tmp_path / "y.png"), *bad]
        result = _cli(*args)
        assert result.exit_code == 2 and "Traceback" not in result.output


def test_validate_json_and_paths_that_look_like_markup(tmp_path) -> None:
    import json

    bad = tmp_path / "[red]bad.json"
    bad.write_text('{"name": "t", "variables": [{"name": "B", "kind": "x"}]}')
    text = _cli("validate", str(bad))
    assert text.exit_code == 1 and "[red]bad.json: invalid (2 problem(s))" in text.output
    data = json.loads(_cli("validate", str(bad), "--json").stdout)
    assert data["valid"] is False and {p["node"] for p in data["problems"]} == {"B"}
    assert {p["field"] for p in data["problems"]} == {"name", "kind"}
    good = tmp_path / "good.json"
    from factask.library import get_task

    good.write_text(get_task("towers-of-hanoi").to_json())
    data = json.loads(_cli("validate", str(good), "--json").stdout)
    assert data["valid"] and len(data["order"]) == 7


def test_import_cliport_json_reports_milestones_and_failures(tmp_path) -> None:
    import json
    from pathlib import Path

    tasks = Path(__file__).parent / "cliport_tasks"
    ok = _cli("import-cliport", str(tasks / "towers_of_hanoi_seq.py"), "-o",
              str(tmp_path / "h.json"), "--json")
    assert ok.exit_code == 0, ok.output
    data = json.loads(ok.stdout.strip().splitlines()[-1])
    assert data["ok"] and data["factors"] == 7 and len(data["milestones"]) == 4
    bad = tmp_path / "exits.py"
    bad.write_text("import sys\nsys.exit(0)\n")
    failed = _cli("import-cliport", str(bad), "-o", str(tmp_path / "x.json"), "--json")
    assert failed.exit_code == 1
    data = json.loads(failed.stdout.strip().splitlines()[-1])
    assert not data["ok"] and "sys.exit(0)" in data["error"]


def _frames(path: Path) -> list:
    import av

    with av.open(str(path)) as container:
        assert container.streams.video[0].codec_context.name == "h264"
        return [f.to_ndarray(format="rgb24") for f in container.decode(video=0)]


def test_video_size_fps_and_camera_are_the_users(tmp_path: Path) -> None:
    counts = {}
    for fps in (5, 10):
        video = tmp_path / f"v{fps}.mp4"
        data = _json(_cli("run", "put-block-in-bowl", "--json", "--video", video, "--fps", fps,
                          "--size", "96x64", "--camera", "left"))
        frames = _frames(video)
        assert len(frames) == data["video"]["frames"] and frames[0].shape == (64, 96, 3)
        assert data["video"] | {"path": None} == {"path": None, "frames": len(frames),
                                                   "fps": fps, "size": [96, 64],
                                                   "camera": "left", "caption": False}
        counts[fps] = len(frames)
    # The same simulated time, twice the frames (give or take the first and last).
    assert abs(counts[10] - 2 * counts[5]) <= 2 and counts[5] >= 3


def test_a_bad_video_option_stops_before_the_episode(tmp_path: Path) -> None:
    for bad, says in ((["--video", tmp_path / "v.avi"], ".gif or .mp4"),
                      (["--video", tmp_path / "v.mp4", "--size", "96"], "WIDTHxHEIGHT"),
                      (["--video", tmp_path / "v.mp4", "--camera", "nowhere"], "nowhere"),
                      (["--video", tmp_path / "v.mp4", "--fps", "0"], "--fps")):
        result = _cli("run", "put-block-in-bowl", *bad)
        assert result.exit_code == 2 and says in result.output, result.output
        assert "Traceback" not in result.output and "action 1" not in result.output
    assert not list(tmp_path.iterdir())


def test_the_caption_draws_the_subtask_into_the_frames(tmp_path: Path) -> None:
    import imageio.v3 as iio
    import numpy as np

    from factask.viz import caption_height

    plain, captioned = tmp_path / "plain.gif", tmp_path / "captioned.gif"
    for path, extra in ((plain, []), (captioned, ["--caption"])):
        result = _cli("run", "put-block-in-bowl", "--video", path, "--size", "160x120", *extra)
        assert result.exit_code == 0, result.output
    a, b = iio.imread(plain, index=0), iio.imread(captioned, index=0)
    assert a.shape == b.shape == (120, 160, 3)
    band = b[-caption_height(160):].astype(int)
    assert np.abs(band - a[-caption_height(160):].astype(int)).mean() > 10
    dark, bright = (band.max(axis=2) < 60).mean(), (band.min(axis=2) > 180).mean()
    assert dark > 0.5 and bright > 0.01  # white text on a dark band


@pytest.mark.parametrize("camera", ["front", "top", "left", "right", "back"])
def test_render_writes_the_asked_size_from_every_view(camera: str, tmp_path: Path) -> None:
    import imageio.v3 as iio

    out = tmp_path / "view.png"
    result = _cli("render", "put-block-in-bowl", "-o", out, "--size", "72x40", "--camera",
                  camera, "--robot", "ur10e")
    assert result.exit_code == 0, result.output
    image = iio.imread(out)
    assert image.shape == (40, 72, 3) and image.std() > 1.0


@pytest.mark.parametrize("command", ["eval-policy", "collect"])
def test_help_keeps_square_brackets(command: str) -> None:
    """Help is plain text: an extra's name in brackets is not read as a style tag."""
    assert "pip install 'factask[ray]'" in " ".join(_cli(command, "--help").output.split())


def test_piped_output_is_never_wrapped_or_cut(tmp_path: Path) -> None:
    """Piped (CliRunner is no terminal), a long line stays one line and a table cell is
    never cut at rich's 80 columns (issue 37, item 11)."""
    graph = get_task("towers-of-hanoi")
    path = tmp_path / "hanoi.json"
    path.write_text(graph.to_json())
    order = " -> ".join(graph.factor_order())
    validated = _cli("validate", path)
    assert validated.exit_code == 0 and order in validated.output  # one line, not split
    data = json.loads(graph.to_json())
    data["factors"][0]["description"] = "a language goal long enough to pass 80 columns " * 3
    path.write_text(json.dumps(data))
    shown = _cli("show", path)
    assert shown.exit_code == 0 and data["factors"][0]["description"].strip() in shown.output
