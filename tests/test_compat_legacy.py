"""GenSim-era NumPy / ``random`` names are lent while a task file runs, and only then."""

from __future__ import annotations

import random
from pathlib import Path

import numpy as np
import pytest

from factask.compat.cliport import import_cliport
from factask.compat.cliport.legacy import NUMPY_NAMES, legacy_names

TASKS = Path(__file__).parent / "cliport_tasks"


def test_the_removed_numpy_names_mean_what_they_meant() -> None:
    with legacy_names():
        assert np.float(1) == 1.0 and np.int(2.7) == 2
        assert np.product([2, 3]) == 6 and np.alltrue([1, 1]) and not np.sometrue([0])
        assert np.isnan(np.NaN) and np.Inf == np.inf and np.isneginf(np.NINF)
        assert np.asscalar(np.array([4])) == 4 and np.asfarray([1]).dtype == np.float64
        assert np.array([1, 2], dtype=np.float).dtype == np.float64


def test_nothing_leaks_out_of_the_block() -> None:
    before = {name for name in NUMPY_NAMES if name in vars(np)}
    sample, shuffle = random.sample, random.shuffle
    with legacy_names():
        pass
    assert {name for name in NUMPY_NAMES if name in vars(np)} == before
    assert random.sample is sample and random.shuffle is shuffle
    with pytest.raises(AttributeError):
        np.product  # noqa: B018 (NumPy 2 has no product; the block lent it)


def test_sample_of_a_set_or_view_draws_as_python_3_8_did() -> None:
    colors = {"red": 1, "green": 2, "blue": 3, "yellow": 4}
    random.seed(3)
    expected = random.sample(tuple(colors), 2)  # Python 3.8: tuple(population)
    with legacy_names():
        random.seed(3)
        assert random.sample(colors.keys(), 2) == expected


def test_shuffle_with_a_generator_argument_is_python_3_8s() -> None:
    draws = iter([0.9, 0.1, 0.5])
    x = [1, 2, 3, 4]
    with legacy_names():
        random.shuffle(x, lambda: next(draws))
    # i=3: j=floor(0.9*4)=3; i=2: j=floor(0.1*3)=0; i=1: j=floor(0.5*2)=1
    assert x == [3, 2, 1, 4]


def test_a_task_written_for_gensims_stack_imports() -> None:
    result = import_cliport(TASKS / "gensim_era_numpy_names.py", seed=0)
    assert 2 <= sum(v.kind == "block" for v in result.graph.variables) <= 3
    assert "product" not in vars(np)  # lent during the import only


def test_debugging_imports_and_calls_do_nothing_and_are_reported(tmp_path: Path) -> None:
    """``import IPython`` / ``ipdb`` at the top of a task file, ``embed()``,
    ``set_trace()`` and ``breakpoint()`` in its reset: the import goes on (never waits
    for a console), each call is a warning, and nothing is left in ``sys.modules``."""
    import sys

    source = (TASKS / "place_red_in_green.py").read_text()
    source = ("import IPython\nimport ipdb\nfrom IPython import embed\n"
              "from IPython.core.debugger import set_trace\n" + source)
    source = source.replace("    def reset(self, env):\n",
                            "    def reset(self, env):\n        embed()\n        ipdb.set_trace()\n"
                            "        set_trace()\n        breakpoint()\n", 1)
    path = tmp_path / "debugging.py"
    path.write_text(source)
    before = {name: sys.modules.get(name) for name in ("IPython", "ipdb")}
    hook = sys.breakpointhook
    result = import_cliport(path)
    assert result.graph.factors
    said = " ".join(result.warnings)
    for call in ("IPython.embed()", "ipdb.set_trace()", "IPython.core.debugger.set_trace()",
                 "breakpoint()"):
        assert f"{call} ignored" in said, said
    assert {name: sys.modules.get(name) for name in ("IPython", "ipdb")} == before
    assert sys.breakpointhook is hook
