"""How a noisy-reference benchmark's errors fared: made, caught, repaired, per kind.

``factask benchmark --model local/noisy-reference[:RATE]`` spoils a share of first
answers with typical model errors (:mod:`factask.gen.reference_model`) and answers
every repair correctly. This reads a run's ``results.jsonl`` back into a table, per
approach and kind of error: how many were made, how many the checks caught (the
spoiled answer was refused), how many the repair mended (a later attempt of that
step passed), and how many generations with such an error still ended faithful.

    python scripts/reference_repairs.py runs/noisy-set            # rate 0.3
    python scripts/reference_repairs.py runs/noisy --rate 0.5 --seed 0

Exit status: 0 (the table is printed), 2 a run that cannot be read.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from factask.evaluation.benchmark import RESULTS_FILE, read_results
from factask.gen.reference_model import DEFAULT_NOISE, ERROR_KINDS, repair_table


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", type=Path, help="the benchmark's run directory")
    parser.add_argument("--rate", type=float, default=DEFAULT_NOISE,
                        help="the noise rate of the run (the model name's :RATE)")
    parser.add_argument("--seed", type=int, default=0, help="the run's --seed")
    args = parser.parse_args(argv)
    path = args.run / RESULTS_FILE
    if not path.is_file():
        print(f"no {RESULTS_FILE} in {args.run}", file=sys.stderr)
        return 2
    records = [r for r in read_results(path) if r.get("faithful") is not None]
    print("| approach | error | made | caught | repaired | generation faithful |")
    print("|---|---|---|---|---|---|")
    for approach in dict.fromkeys(r["approach"] for r in records):
        table = repair_table([r for r in records if r["approach"] == approach],
                             args.rate, args.seed)
        for kind in ERROR_KINDS:
            row = table[kind]
            if row["made"]:
                print(f"| {approach} | {kind} | {row['made']} | {row['caught']} | "
                      f"{row['repaired']} | {row['faithful']} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
