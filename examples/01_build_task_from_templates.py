"""Example 01: build a task from library templates and your own variables.

Run: ``python examples/01_build_task_from_templates.py`` (a few seconds).
Writes ``out/examples/01_task.json`` and ``out/examples/01_task_graph.png``.

A task is a bipartite graph of *state variables* (the things in the scene) and
*subtask factors* (one goal each). Library templates are factors over slots;
``instantiate`` binds the slots to variables and returns a fragment, ``compose``
joins fragments into one task graph, ``validate`` checks it as a whole.
"""

# %% Imports and the output folder
from pathlib import Path

import factask as ft
from factask.library import TEMPLATES, template_names
from factask.viz import draw_graph

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)

# %% The library's templates: each has slots and factors whose goals name slots
print("library templates:", ", ".join(template_names()))
stack_tpl = TEMPLATES["stack_on_base"]
zone_tpl = TEMPLATES["place_in_zone"]
for tpl in (stack_tpl, zone_tpl):
    slots = ", ".join(f"{s.name}{'[many]' if s.many else ''}: {s.kinds}" for s in tpl.slots)
    print(f"  {tpl.name}: {tpl.description}\n    slots: {slots}")

# %% Our own variables: sizes are full extents (x, y, z) in metres
red = ft.StateVariable(name="red_block", kind="block", color="red")
blue = ft.StateVariable(name="blue_block", kind="block", color="blue")
pallet = ft.StateVariable(name="pallet", kind="pallet", color="brown",
                          description="the pallet the column stands on")
cylinders = ft.StateVariable(name="cylinders", kind="cylinder", color="yellow", count=2,
                             size=(0.04, 0.04, 0.06), description="two yellow cylinders")
zone = ft.StateVariable(name="green_zone", kind="zone", color="green", size=(0.15, 0.15, 0.001))
print("instances of a count-2 variable:", cylinders.instances)

# %% Instantiate: bind slots to variables (a `many` slot takes an ordered list)
column = stack_tpl.instantiate(layers=[red, blue], base=pallet)
park = zone_tpl.instantiate(objects=cylinders, zone=zone)
for frag in (column, park):
    for f in frag.factors:
        print(f"fragment {frag.name}: factor {f.name!r} ({f.goal.type}) - {f.description}")

# %% Compose the fragments into one task and validate the whole graph
task = ft.compose(column, park, name="stack-and-park",
                  description="Stack the red then the blue block on the pallet and put both "
                              "yellow cylinders in the green zone.").ensure_valid()
print("variables:", task.variable_names())
print("factor order:", task.factor_order())
print("weights:", {f.name: round(f.weight, 3) for f in task.factors})

# %% A cylinder lying on its side is a `log`, size (length, diameter, diameter): the
# bridge template lays one across two blocks it first stands in a row
pillars = ft.StateVariable(name="pillars", kind="block", color="red", count=2)
log = ft.StateVariable(name="green_log", kind="log", color="green", size=(0.14, 0.04, 0.04))
bridge = ft.compose(TEMPLATES["bridge"].instantiate(pillars=pillars, deck=log),
                    name="log-bridge", description="Balance the green log across two red "
                                                   "blocks.").ensure_valid()
print("log bridge:", [(f.name, f.goal.type) for f in bridge.factors])

# %% A `holed_box` has a square hole in its +x side; `aligned` mode "hole" lays a log in
# front of it, axis through the hole (the layout keeps that spot clear at reset). Any
# other mode on a holed box is refused, naming the one to use.
holed = ft.StateVariable(name="red_box", kind="holed_box", color="red", size=(0.08, 0.08, 0.05))
line_up = ft.SubtaskFactor(name="line_up", description="line the log up with the red box's hole",
                           goal=ft.Aligned(objects=["green_log"], reference="red_box",
                                           mode="hole"))
hole_task = ft.TaskGraph(name="log-to-hole", variables=[log, holed],
                         factors=[line_up]).ensure_valid()
print("log to hole:", [(f.name, f.goal.type, f.goal.mode) for f in hole_task.factors])
centred = line_up.model_copy(update={"goal": line_up.goal.model_copy(update={"mode": "center"})})
try:
    hole_task.model_copy(update={"factors": [centred]}).ensure_valid()
except ft.GraphValidationError as exc:
    print(exc)

# %% Validation reports every problem at once, each with a fix
extra = ft.SubtaskFactor(name="also_zone", description="put the red block in a purple zone",
                         goal=ft.InZone(objects=["red_block"], zone="purple_zone"), weight=0.2)
broken = task.model_copy(update={"factors": [
    task.factors[0].model_copy(update={"weight": 0.9}), task.factors[1], extra]})
try:
    broken.ensure_valid()
except ft.GraphValidationError as exc:
    print(exc)

# %% JSON round trip: what `factask validate FILE.json` accepts
text = task.to_json()
(OUT / "01_task.json").write_text(text)
assert ft.parse_graph(text) == task
print(text[:600], "...")

# %% Draw the bipartite graph (variables left, factors right, in order)
png = draw_graph(task, OUT / "01_task_graph.png")
print("wrote", OUT / "01_task.json", "and", png)
