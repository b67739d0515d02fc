"""The grounded reading of a proposal is one answer: the same first choice of the
one-shot grammar whatever the hash seed (set order) and however much time the layout
checks get (:mod:`factask.gen.reading.capacity`: a search that runs out of time counts
as fitting).

"put the red block into the brown container, then put the blue block ..., then ..."
once read as five goals or as one goal over all five blocks, as the joint layout check
of the five goals ran out of CPU time or not; the stated goals' anchor is now grown
until those goals fit one after the other (:func:`factask.gen.reading.stated_goals.fit_sizes`),
and the grammar's check finds that answer again.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

from factask.gen.reading import capacity

#: Library tasks whose descriptions are read (the first one was the flaky one).
TASKS = ("color-sequenced-block-in-container", "ball-on-box-on-container",
         "stack-block-pyramid", "place-red-in-green")

_SCRIPT = """
import json, sys
from factask.gen.first_choice import first_choice
from factask.gen.reading import capacity, grounded
from factask.gen.reading.describe import describe
from factask.gen.reading.mentions import mentions
from factask.library.tasks import get_task

capacity.BUDGET_S = float(sys.argv[1])
out = {}
for name in sys.argv[2:]:
    words = describe(get_task(name))
    found = mentions(words)
    out[name] = first_choice(grounded.compact_graph_schema(found, words))
print(json.dumps(out, sort_keys=True))
"""

#: (hash seed, layout budget in CPU seconds): the default budget, one that never runs
#: out, and one that always does.
RUNS = (("0", None), ("1", 5.0), ("2", 1e-6))


def test_the_first_choice_does_not_hang_on_the_hash_seed_or_the_layout_budget() -> None:
    procs = []
    for seed, budget in RUNS:
        env = {**os.environ, "PYTHONHASHSEED": seed}
        procs.append(subprocess.Popen(
            [sys.executable, "-c", _SCRIPT, str(budget or capacity.BUDGET_S), *TASKS],
            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True))
    answers = []
    for proc in procs:
        out, err = proc.communicate(timeout=120)
        assert proc.returncode == 0, err[-2000:]
        answers.append(json.loads(out.strip().splitlines()[-1]))
    assert set(answers[0]) == set(TASKS)
    for (seed, budget), answer in zip(RUNS[1:], answers[1:], strict=True):
        for name in TASKS:
            assert answer[name] == answers[0][name], (name, seed, budget)
    factors = answers[0]["color-sequenced-block-in-container"]["factors"]
    assert len(factors) == 5, factors  # a goal per "then ..." clause
