"""Example 02: compose two tasks - shared and separate variables, weights, order.

Run: ``python examples/02_compose_tasks.py`` (about ten seconds: it ends with one
oracle episode of the composed task). Writes ``out/examples/02_composed.json``
and ``out/examples/02_composed_graph.png``.

``compose(a, b, ..., renames=[...], shares=[...])``: variables with the same name
are the same variable (and must be defined identically); ``renames`` keeps
variables apart or identifies them; each input keeps its share of the reward
(by default proportional to its number of factors) and its factors' weights are
rescaled to it; factors keep their input order, and the task's order is the
explicit ``after`` lists plus the order implied by anchoring.
"""

# %% Imports and the output folder
from pathlib import Path

import factask as ft
from factask.library import TEMPLATES, get_task
from factask.sim.episode import run_episode
from factask.viz import draw_graph

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)


def weights(graph: ft.TaskGraph) -> dict[str, float]:
    """Factor name -> weight, rounded for printing."""
    return {f.name: round(f.weight, 3) for f in graph.factors}


# %% Two library tasks and their weights
bowl_task = get_task("put-block-in-bowl")
bridge_task = get_task("build-bridge")
for g in (bowl_task, bridge_task):
    print(f"{g.name}: variables {g.variable_names()}\n  weights {weights(g)}")

# %% Same name, different definition: a CompositionError names the fields
# Both tasks have a `blue_block`, described differently: they cannot be one object.
try:
    ft.compose(bowl_task, bridge_task)
except ft.CompositionError as exc:
    print("conflict:", exc)

# %% renames keep them apart: the bridge's block becomes `top_block`
keep_apart = [None, {"blue_block": "top_block"}]
both = ft.compose(bowl_task, bridge_task, name="bowl-and-bridge", renames=keep_apart).ensure_valid()
print("kept apart:", both.variable_names())
# Default shares are proportional to the number of factors: 1/4 for the bowl task,
# 3/4 for the bridge, so the bridge's weights go from 1/3 to 1/4 each.
print("default shares:", weights(both), "sum", round(sum(f.weight for f in both.factors), 6))

# %% Explicit shares: the bowl is worth as much as the whole bridge
weighted = ft.compose(bowl_task, bridge_task, name="bowl-and-bridge", renames=keep_apart,
                      shares=[0.5, 0.5]).ensure_valid()
print("shares 0.5 / 0.5:", weights(weighted))
print("factor order:", weighted.factor_order())

# %% Sharing: fragments naming the same (identical) variable use one object
bowl = ft.StateVariable(name="bowl", kind="bowl", color="white")
red = ft.StateVariable(name="red", kind="block", color="red")
blue = ft.StateVariable(name="blue", kind="block", color="blue")
zone = ft.StateVariable(name="red_zone", kind="zone", color="red", size=(0.12, 0.12, 0.001))
put = TEMPLATES["put_in_container"]
shared = ft.compose(put.instantiate(objects=red, container=bowl),
                    put.instantiate(objects=blue, container=bowl), name="two-into-one-bowl")
print("shared bowl:", shared.variable_names(), weights(shared))
# ... and a rename can identify differently named variables (defined identically).
other_bowl = bowl.model_copy(update={"name": "other_bowl"})
identified = ft.compose(put.instantiate(objects=red, container=bowl),
                        put.instantiate(objects=blue, container=other_bowl),
                        renames=[None, {"other_bowl": "bowl"}], name="identified")
print("identified by rename:", identified.variable_names())

# %% Order: explicit `after` plus the order implied by anchoring
# The blue block goes on top of the red block: anchoring alone puts it after the
# factor that moves the red block, even though it is declared first.
on_top = TEMPLATES["place_on_top"].instantiate(objects=blue, support=red)
red_in_zone = TEMPLATES["place_in_zone"].instantiate(objects=red, zone=zone)
ordered = ft.compose(on_top, red_in_zone, name="red-in-zone-blue-on-top").ensure_valid()
print("declared:", ordered.factor_names(), "-> order:", ordered.factor_order())

# %% The composed library tasks compile and the oracle solves them
(OUT / "02_composed.json").write_text(weighted.to_json())
draw_graph(weighted, OUT / "02_composed_graph.png")
result = run_episode(weighted, seed=0, robot="floating")
print(f"oracle on {weighted.name}: success={result.success} reward={result.reward:.2f} "
      f"actions={result.steps} factors={ {k: round(v, 2) for k, v in result.factors.items()} }")
print("wrote", OUT / "02_composed.json", "and", OUT / "02_composed_graph.png")
