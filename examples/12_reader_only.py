"""Example 12: what the reading alone makes of a proposal (no model), judged by meaning.

Run: ``python examples/12_reader_only.py`` (about a minute: no LLM, one oracle
episode per check). Writes ``out/examples/12_reader.json``.

``local/reader`` answers every generation step with the first choice its schema allows
(:mod:`factask.gen.first_choice`), through the same pipeline a model takes (litellm over
HTTP to a loopback server). What it writes is what the proposal reader decided by
itself; a real model's result is what the model adds over it. The result is then
judged against a reference graph with the words: a colour the words do not name
matches any colour (``factask benchmark --model local/reader`` does this for a list).
Last, a two-step proposal through all three approaches: where the words state every
goal, variables-first and subtasks-first ask the one-shot grammar's decisions piece
by piece (:mod:`factask.gen.grounded_steps`) and write the same task.
"""

# %% Imports and the output folder
import json
import os
from pathlib import Path

os.environ.setdefault("LITELLM_LOCAL_MODEL_COST_MAP", "True")  # offline: bundled cost map
os.environ.setdefault("MUJOCO_GL", "egl")

from factask.gen import Generator, LLMConfig, Verifier
from factask.gen.compare import compare
from factask.gen.session import open_client
from factask.graph import parse_graph

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)
PROPOSAL = "put a block in the green bowl"

# %% The reader-only generation: no model, the schema's first choices
with open_client(LLMConfig(model="local/reader")) as client:
    result = Generator(client, Verifier(episodes=1), max_repairs=1).generate(
        PROPOSAL, "one-shot")
print(f"{PROPOSAL!r}: level {result.level_reached}, unread {result.unread}")
assert result.graph is not None

# %% Judged against a reference: the block's colour is not in the words
reference = parse_graph({
    "name": "reference", "variables": [
        {"name": "block", "kind": "block", "color": "blue"},
        {"name": "bowl", "kind": "bowl", "color": "green"}],
    "factors": [{"name": "in_bowl", "goal": {"type": "inside", "objects": ["block"],
                                             "container": "bowl"}}]})
meaning = compare(result.graph, reference, PROPOSAL)
print(f"means the proposal: {meaning.equivalent}; differences: {meaning.differences}")
assert meaning.equivalent

# %% Every approach, one two-step proposal: the same task, piece by piece or at once
STEPS = "put the red block in the green bowl, then put the blue block on the red block"
two_step = parse_graph({
    "name": "reference", "variables": [
        {"name": "red_block", "kind": "block", "color": "red"},
        {"name": "blue_block", "kind": "block", "color": "blue"},
        {"name": "green_bowl", "kind": "bowl", "color": "green"}],
    "factors": [
        {"name": "in_bowl", "weight": 0.5, "goal": {"type": "inside", "objects": ["red_block"],
                                     "container": "green_bowl"}},
        {"name": "on_red", "weight": 0.5, "after": ["in_bowl"],
         "goal": {"type": "on", "objects": ["blue_block"], "support": "red_block"}}]})
approaches = {}
with open_client(LLMConfig(model="local/reader")) as client:
    for approach in ("one-shot", "variables-first", "subtasks-first"):
        out = Generator(client, Verifier(episodes=1), max_repairs=1).generate(STEPS, approach)
        same = out.graph is not None and compare(out.graph, two_step, STEPS).equivalent
        approaches[approach] = {"level": out.level_reached, "steps": len(out.steps),
                                "faithful": same}
        print(f"{approach:16s} level {out.level_reached:10s} {len(out.steps)} step(s), "
              f"faithful {same}")
assert all(a["faithful"] for a in approaches.values())

(OUT / "12_reader.json").write_text(json.dumps(
    {"proposal": PROPOSAL, "level": result.level_reached, "graph": json.loads(
        result.graph.to_json()), "meaning": meaning.to_dict(),
     "approaches": {"proposal": STEPS, **approaches}}, indent=2))
print(f"wrote {OUT / '12_reader.json'}")
