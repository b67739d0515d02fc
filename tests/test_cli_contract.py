"""The command line's contract (issue 20): version, exit codes, any graph shown."""

from __future__ import annotations

from typer.testing import CliRunner

from factask.cli import app


def _cli(*args: str):
    return CliRunner().invoke(app, list(args))


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
