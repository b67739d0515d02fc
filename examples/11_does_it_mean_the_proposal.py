"""Example 11: does a graph mean its proposal? The meaning metric and the word check.

Run: ``python examples/11_does_it_mean_the_proposal.py`` (a few seconds, no LLM, no
simulation). Writes ``out/examples/11_meaning.json``.

Completion says the oracle could solve *a* task. Two checks say whether it is the task
asked for:

* ``compare(generated, reference)`` (``factask compare A B``): the same objects, goals,
  roles and orders, up to names, wording, weights, tolerances and numbers;
* ``account(proposal, graph)``: every colour, number, order, side, quantifier, shape,
  relation and kind word of the proposal is used by the graph, or listed as unread (a
  generation with unread words ends at level ``partial``).
"""

# %% Imports and the output folder
import json
from pathlib import Path

import factask as ft
from factask.gen.compare import compare
from factask.gen.reading.accounting import account
from factask.gen.reading.describe import describe
from factask.library import get_task

OUT = Path("out/examples")
OUT.mkdir(parents=True, exist_ok=True)

# %% A reference task, and the same task written another way
reference = get_task("build-house")
data = json.loads(reference.to_json())
for k, factor in enumerate(data["factors"]):  # other names and words: the same task
    factor["description"] = f"step {k}"
renamed = ft.rename(ft.parse_graph(data), {f["name"]: f"goal_{k}"
                                          for k, f in enumerate(data["factors"])})
same = compare(renamed, reference)
print(f"renamed: equivalent={same.equivalent}, relation F1 {same.relation_f1:.2f}")
assert same.equivalent

# %% Another task is told apart, with what differs
other = compare(get_task("stack-block-pyramid"), reference)
print(f"stack-block-pyramid vs build-house: equivalent={other.equivalent}, "
      f"object F1 {other.object_f1:.2f}")
for line in other.differences[:4]:
    print("  ", line)
assert not other.equivalent

# %% Words: the graph told in words reads back in full; extra words are unread
words = describe(reference)
print(f"described: {words}")
assert account(words, reference).complete
asked = words + ", on the left side of the table"
check = account(asked, reference)
print("unread:", ", ".join(str(w) for w in check.unread))
assert check.unread_words() == ["left", "side"]

(OUT / "11_meaning.json").write_text(json.dumps(
    {"same": same.to_dict(), "other": other.to_dict(), "unread": check.to_dict()["unread"]},
    indent=2))
print(f"wrote {OUT / '11_meaning.json'}")
