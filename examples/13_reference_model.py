"""Example 13: the pipeline with a model that knows the answer, perfect and noisy.

Run: ``python examples/13_reference_model.py`` (about half a minute: no LLM, one
oracle episode per check). Writes ``out/examples/13_reference.json``.

``local/reference`` answers every generation step from a reference graph, in the
step's own form, through litellm to a loopback server on the path remote models take
(no grounding: the model writes the objects). It is what a capable model that
understood the proposal would write, so anything short of "the same task" is a place
where the pipeline loses a correct answer. ``local/noisy-reference:RATE`` first
answers a share of the steps with a typical model error (an unknown name, a missing
field, a kind not in the vocabulary, a goal on itself, a cut-off answer) and every
repair correctly: it shows which errors the checks catch and the repairs mend
(``factask benchmark --model local/noisy-reference`` measures this for a list).
"""

# %% Imports and the output folder
import json
import os
from pathlib import Path

os.environ.setdefault("LITELLM_LOCAL_MODEL_COST_MAP", "True")  # offline: bundled cost map
os.environ.setdefault("MUJOCO_GL", "egl")

from factask import get_task
from factask.gen import Generator, LLMConfig, Verifier
from factask.gen.compare import compare
from factask.gen.reference_model import repair_table
from factask.gen.session import open_client

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)
TASK = "towers-of-hanoi-seq"  # seven moves, each after the one before
reference = get_task(TASK)
proposal = f"{TASK}: {reference.description}"
rows = []

# %% The perfect reference and the noisy one (every first answer spoiled), each approach
for model in ("local/reference", "local/noisy-reference:1.0"):
    for approach in ("one-shot", "variables-first", "subtasks-first"):
        with open_client(LLMConfig(model=model), references={TASK: reference}) as client:
            result = Generator(client, Verifier(episodes=1), max_repairs=2).generate(
                proposal, approach)
        same = result.graph is not None and compare(result.graph, reference).equivalent
        record = {"task": TASK, "faithful": same,
                  "steps": [s.to_dict() for s in result.steps]}
        errors = {k: v for k, v in repair_table([record], 1.0).items() if v["made"]}
        print(f"{model:<28} {approach:<16} calls {result.usage.calls:>2}, "
              f"repairs {result.repairs}, the same task: {same}")
        if "noisy" in model:
            print("    errors made / caught / repaired: "
                  + ", ".join(f"{k} {v['made']}/{v['caught']}/{v['repaired']}"
                              for k, v in errors.items()))
        rows.append({"model": model, "approach": approach, "faithful": same,
                     "calls": result.usage.calls, "repairs": result.repairs,
                     "errors": errors})
        assert same, result.failure

(OUT / "13_reference.json").write_text(json.dumps(rows, indent=2))
print(f"wrote {OUT / '13_reference.json'}")
