"""The docs run (issue 20): every Python block of README.md and docs/ runs, every
``factask ...`` line parses, every link and every named repository file exists.

A Python block can be marked as not runnable by a line
``<!-- not runnable: <reason> -->`` right before it.
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import click
import pytest
import typer

from factask.cli import app

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
FENCE = re.compile(r"(<!-- not runnable: [^>]+-->\n)?```(\w*)\n(.*?)```", re.S)
#: Folders of the repository whose files the docs may name.
NAMED = re.compile(r"`((?:src|tests|examples|benchmarks|scripts|docs|mjcf_assets)/[\w./-]+)`")
LINK = re.compile(r"\]\(([^)#\s]+)(?:#[^)]*)?\)")


def _blocks(language: str) -> list[tuple[str, str]]:
    out = []
    for page in PAGES:
        for k, m in enumerate(FENCE.finditer(page.read_text(encoding="utf-8"))):
            if m.group(2) == language and not m.group(1):
                out.append((f"{page.relative_to(ROOT)}#{k}", m.group(3)))
    return out


@pytest.mark.parametrize(("where", "code"), _blocks("python"),
                         ids=[w for w, _ in _blocks("python")])
def test_every_python_block_runs(where: str, code: str) -> None:
    env = {**os.environ, "MPLBACKEND": "Agg", "MUJOCO_GL": os.environ.get("MUJOCO_GL", "egl")}
    proc = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=300, check=False)
    assert proc.returncode == 0, f"{where}:\n{proc.stderr[-3000:]}"


def _factask_lines() -> list[tuple[str, str]]:
    lines = []
    for where, code in _blocks("bash"):
        for line in code.replace("\\\n", " ").splitlines():
            line = line.split(" # ")[0].split("  #")[0].strip()
            if line.startswith("factask "):
                lines.append((where, line))
    return lines


@pytest.mark.parametrize(("where", "line"), _factask_lines(),
                         ids=[f"{w}:{line[:40]}" for w, line in _factask_lines()])
def test_every_factask_line_parses(where: str, line: str) -> None:
    group = typer.main.get_command(app)
    words = shlex.split(line)
    for k, word in enumerate(words):  # the shell's part of the line is not factask's
        if word in (">", ">>", "|", "&&", ";", "2>&1"):
            words = words[:k]
            break
    name, *rest = words[1:]
    ctx = click.Context(group, info_name="factask")
    command = group.get_command(ctx, name)
    assert command is not None, f"{where}: unknown command in {line!r}"
    try:
        command.make_context(name, rest, parent=ctx)
    except click.UsageError as exc:
        pytest.fail(f"{where}: {line!r} does not parse: {exc}")


def test_every_link_and_named_file_exists() -> None:
    missing = []
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        for target in LINK.findall(text):
            if "://" in target or target.startswith("mailto:"):
                continue
            if not (page.parent / target).exists():
                missing.append(f"{page.relative_to(ROOT)}: link {target}")
        for named in NAMED.findall(text):
            if not (ROOT / named.rstrip("/.")).exists():
                missing.append(f"{page.relative_to(ROOT)}: names {named}")
    assert not missing, missing
