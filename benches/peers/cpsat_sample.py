#!/usr/bin/env python3
"""The baseline of `rccpack-bench sample`: layouts of an rccpack-model/1
JSON model drawn by OR-Tools CP-SAT with randomised search, one solve per
seed, under "objective >= K" instead of the objective.

    python3 cpsat_sample.py MODEL.json --min-objective K --n N [--seed S]
                            [--time-limit SECONDS]

Solve i (0 <= i < N) runs with `random_seed = S + i`,
`randomize_search = true`, one worker, and stops at the first layout.
Prints ONE JSON line on stdout:

    {"layouts": [[grid value per model variable], ...], "time_s": float}

(`time_s`: the summed wall time of the N solves, model building excluded;
solves that find nothing within the limit add no layout.) Nothing excludes
earlier layouts, so layouts may repeat: that is the baseline.
"""

import argparse
import json
import os
import sys
import time

# Import cpsat.py from this folder without leaving a __pycache__ behind.
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cpsat import load  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("model")
    ap.add_argument("--min-objective", type=int, required=True)
    ap.add_argument("--n", type=int, required=True)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--time-limit", type=float, default=10.0, metavar="SECONDS")
    args = ap.parse_args()
    cp_model, (model, xs, _, _, objective) = load(args.model)
    model.ClearObjective()
    model.Add(objective >= args.min_objective)
    layouts = []
    total = 0.0
    for i in range(args.n):
        solver = cp_model.CpSolver()
        solver.parameters.num_workers = 1
        solver.parameters.random_seed = args.seed + i
        solver.parameters.randomize_search = True
        solver.parameters.max_time_in_seconds = args.time_limit
        t0 = time.perf_counter()
        st = solver.Solve(model)
        total += time.perf_counter() - t0
        if st in (cp_model.OPTIMAL, cp_model.FEASIBLE):
            layouts.append([int(solver.Value(x)) for x in xs])
    print(json.dumps({"layouts": layouts, "time_s": total}))


if __name__ == "__main__":
    main()
