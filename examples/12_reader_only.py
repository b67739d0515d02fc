"""Example 12: what the reading alone makes of a proposal (no model), judged by meaning.

Run: ``python examples/12_reader_only.py`` (about half a minute: no LLM, one oracle
episode). Writes ``out/examples/12_reader.json``.

``local/reader`` answers every generation step with the first choice its schema allows
(:mod:`factask.gen.first_choice`), through the same pipeline a model takes (litellm over
HTTP to a loopback server). What it writes is what the proposal reader decided by
itself; a real model's result is what the model adds over it. The result is then
judged against a reference graph with the words: a colour the words do not name
matches any colour (``factask benchmark --model local/reader`` does this for a list).
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

(OUT / "12_reader.json").write_text(json.dumps(
    {"proposal": PROPOSAL, "level": result.level_reached, "graph": json.loads(
        result.graph.to_json()), "meaning": meaning.to_dict()}, indent=2))
print(f"wrote {OUT / '12_reader.json'}")
