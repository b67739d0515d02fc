"""scripts/reading_faithful.py: the reading's one-shot faithful rate, no model, no physics."""

from __future__ import annotations

import json
from pathlib import Path

from scripts.reading_faithful import main

SET = Path(__file__).parent / "data" / "proposals.json"


def test_it_judges_each_proposal_against_its_reference(tmp_path, capsys) -> None:
    out = tmp_path / "reading.json"
    assert main(["--tasks", str(SET), "--limit", "3", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "proposals.json: faithful" in printed and "/ 3 (" in printed
    rows = json.loads(out.read_text())[str(SET)]
    assert len(rows) == 3
    for row in rows:
        assert isinstance(row["faithful"], bool) and isinstance(row["stated"], bool)
        assert row["faithful"] or row.get("differences") or row.get("why")


def test_a_list_that_cannot_be_read_is_exit_2(tmp_path, capsys) -> None:
    assert main(["--tasks", str(tmp_path / "none.json")]) == 2
    assert "cannot read task list" in capsys.readouterr().err
