"""scripts/reference_repairs.py: a noisy-reference run's errors, made / caught / repaired."""

from __future__ import annotations

import json

from factask.gen.reference_model import planned_error
from scripts.reference_repairs import main


def test_it_counts_each_kind_of_error_per_approach(tmp_path, capsys) -> None:
    # every first answer spoiled (rate 1): the goal step's error is caught and repaired,
    # the variables step's is caught and never mended
    steps = [{"step": "variables", "attempt": 0, "ok": False},
             {"step": "variables", "attempt": 1, "ok": False},
             {"step": "subtask_goal:a", "attempt": 0, "ok": False},
             {"step": "subtask_goal:a", "attempt": 1, "ok": True},
             {"step": "assembly", "attempt": 0, "ok": True}]  # no answer: not counted
    records = [{"approach": "variables-first", "task": "t", "faithful": False,
                "steps": steps},
               {"approach": "one-shot", "task": "u", "faithful": None, "steps": steps}]
    (tmp_path / "results.jsonl").write_text("".join(json.dumps(r) + "\n" for r in records))
    assert main([str(tmp_path), "--rate", "1"]) == 0
    rows = [line.split(" | ") for line in capsys.readouterr().out.splitlines()[2:]]
    kinds = {planned_error("t", "variables", 1.0): (1, 1, 0),
             planned_error("t", "subtask_goal:a", 1.0): (1, 1, 1)}
    got = {r[1]: tuple(int(x) for x in r[2:5]) for r in rows}
    assert {r[0] for r in rows} == {"| variables-first"}  # no reference: not judged
    if len(kinds) == 2:
        assert got == kinds
    else:  # the same kind twice
        assert list(got.values()) == [(2, 2, 1)]


def test_a_run_without_results_is_exit_2(tmp_path, capsys) -> None:
    assert main([str(tmp_path)]) == 2
    assert "no results.jsonl" in capsys.readouterr().err
