# %% [markdown]
# # Generating a task with each strategy, offline
#
# A scripted OpenAI-compatible server on 127.0.0.1 stands in for the LLM; the
# rest is the real pipeline: litellm sends the prompts, the answers are read as
# JSON data, validated, compiled into MuJoCo and checked by the oracle, and every
# failure goes back to the "model" as feedback. The script's first answer of one
# step per strategy is wrong on purpose, so each strategy shows a repair.
#
# Run with `python examples/06_generate_with_loopback.py`. For a real model, drop the
# server and pass e.g. `LLMConfig(model="openai/gpt-4o")` (see docs/generation.md).

# %%
import json
import os
from pathlib import Path

os.environ.setdefault("LITELLM_LOCAL_MODEL_COST_MAP", "True")  # offline: bundled cost map
os.environ.setdefault("MUJOCO_GL", "egl")

from factask.gen import APPROACHES, Generator, LLMClient, LLMConfig, LoopbackServer, Verifier
from factask.gen.demo import DEMO_PROPOSAL, demo_responder
from factask.gen.reading.bases import base_order
from factask.gen.reading.cover import colour_pins
from factask.gen.reading.grounded import movable
from factask.gen.reading.mentions import mentions

# %% [markdown]
# ## The scripted server

# %%
server = LoopbackServer(demo_responder(broken=True)).start()
print("loopback API base:", server.url)
client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url))


# %% [markdown]
# ## One generation per strategy, printing each step as it happens


# %%
def show(rec):
    status = "ok" if rec.ok else "FAILED"
    print(f"  {rec.step:<34} attempt {rec.attempt}  {status:<6} level={rec.level}")
    if rec.feedback:
        print("      feedback:", rec.feedback.splitlines()[0][:110])
        for line in rec.feedback.splitlines()[1:3]:
            print("               ", line[:110])


results = {}
for approach in APPROACHES:
    print(f"\n== {approach}: {DEMO_PROPOSAL}")
    gen = Generator(client, Verifier(episodes=2), max_repairs=3, on_step=show)
    result = gen.generate(DEMO_PROPOSAL, approach)
    results[approach] = result
    print(f"-> level reached: {result.level_reached}; repairs: {result.repairs}; "
          f"calls: {result.usage.calls}, tokens: {result.usage.total_tokens}")

# %% [markdown]
# ## The generated graph (subtasks-first)

# %%
graph = results["subtasks-first"].graph
print(graph.to_json())
print("order:", " -> ".join(graph.factor_order()))

# %% [markdown]
# ## Saved for later: the graph, and every generation's record (steps, feedback, usage)

# %%
out = Path("out/examples")
out.mkdir(parents=True, exist_ok=True)
(out / "06_generated.json").write_text(graph.to_json())
(out / "06_results.json").write_text(
    json.dumps([r.to_dict() for r in results.values()], indent=2))
print("wrote", out / "06_generated.json")

# %% [markdown]
# ## What a proposal's words fix before the model writes a token
#
# For the packaged local model the steps are grounded in the objects the proposal
# names (`factask.gen.reading.mentions`): a matching-colour phrase gives one object per
# colour, a moving verb before a bowl makes it carried, and the one-shot grammar
# pins each fixed object to the movable one of its colour (docs/generation.md,
# "Grounded answers for the local model"); "horizontally" lays a cylinder down (a
# log), and the words' bases come first in the order goals may build on one another
# (`factask.gen.reading.bases`: no answer can put two objects on each other).

# %%
for proposal in ("sort the red and blue blocks into the bowls of the same colour",
                 "drop the pink ball into the yellow bowl, then put the bowl in the green zone",
                 "balance a green cylinder horizontally on top of the two red blocks"):
    found = mentions(proposal)
    print(proposal)
    for m in found:
        print("   ", m.describe())
    movers = [m.name for m in movable(found)]
    fixed = [m.name for m in found if m.name not in movers]
    print("    pinned:", colour_pins(movers, fixed, {m.name: m.color for m in found}))
    print("    bases first:", base_order(found, proposal))

# %%
server.stop()
