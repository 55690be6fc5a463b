#!/usr/bin/env python3
"""Solve an rccpack-model/1 JSON model (`rccpack synth --emit model.json`)
with OR-Tools CP-SAT.

    python3 cpsat.py MODEL.json [--time-limit SECONDS] [--workers N] [--seed S]

Prints ONE JSON line on stdout:

    {"status": "optimal"|"feasible"|"infeasible"|"unknown",
     "values": [grid value per model variable] or null,
     "objective": int or null, "time_s": float}

`objective` is the integer score numerator of `values` (constant terms
included), recomputed exactly from the literals; `time_s` is the wall time
of CP-SAT's solve. Every Boolean is an exact reification, both ways
(`OnlyEnforceIf(b)` and `OnlyEnforceIf(~b)`). Errors (an unreadable or
malformed model) go to stderr with exit code 1.
"""

import argparse
import json
import sys
import time


def fail(msg):
    print(f"cpsat.py: {msg}", file=sys.stderr)
    sys.exit(1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("model", help="rccpack-model/1 JSON file")
    ap.add_argument("--time-limit", type=float, default=None, metavar="SECONDS")
    ap.add_argument("--workers", type=int, default=1, metavar="N")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    if args.workers < 1:
        fail(f"--workers {args.workers}: expected at least 1")
    if args.time_limit is not None and not (args.time_limit >= 0):
        fail(f"--time-limit {args.time_limit}: expected a number of seconds >= 0")

    cp_model, (model, xs, soft_lits, value_of, _) = load(args.model)

    solver = cp_model.CpSolver()
    if args.time_limit is not None:
        solver.parameters.max_time_in_seconds = args.time_limit
    solver.parameters.num_workers = args.workers
    solver.parameters.random_seed = args.seed
    t0 = time.perf_counter()
    st = solver.Solve(model)
    elapsed = time.perf_counter() - t0

    if st == cp_model.MODEL_INVALID:
        fail(f"{args.model}: CP-SAT says the model is invalid: {model.Validate()}")
    status = {
        cp_model.OPTIMAL: "optimal",
        cp_model.FEASIBLE: "feasible",
        cp_model.INFEASIBLE: "infeasible",
    }.get(st, "unknown")
    values = None
    objective = None
    if status in ("optimal", "feasible"):
        values = [int(solver.Value(x)) for x in xs]
        objective = 0
        for coef, lit in soft_lits:
            if value_of(solver, lit):
                objective += coef
    print(json.dumps({"status": status, "values": values,
                      "objective": objective, "time_s": elapsed}))


def load(path):
    """CP-SAT's module and `build`'s result for the model file `path`;
    every failure ends the script with a message (`fail`)."""
    try:
        from ortools.sat.python import cp_model
    except ImportError:
        fail("the Python package `ortools` is missing; install it with `pip install ortools`")

    try:
        with open(path, encoding="utf-8") as f:
            m = json.load(f)
    except (OSError, ValueError) as e:
        fail(f"{path}: cannot read the model: {e}")
    if not isinstance(m, dict) or m.get("format") != "rccpack-model/1":
        fail(f"{path}: not an rccpack-model/1 file (format {m.get('format') if isinstance(m, dict) else None!r})")

    try:
        return cp_model, build(cp_model, m)
    except (KeyError, TypeError, ValueError, IndexError) as e:
        fail(f"{path}: malformed model: {e!r}")


def build(cp_model, m):
    model = cp_model.CpModel()
    true = model.NewBoolVar("true")
    model.Add(true == 1)

    xs = [model.NewIntVar(int(v.get("lb", 0)), int(v["ub"]), f"v{i}")
          for i, v in enumerate(m["vars"])]
    bs = [model.NewBoolVar(f"b{j}") for j in range(len(m["bools"]))]

    def lit(l):
        """A CP-SAT literal for a JSON literal."""
        if "const" in l:
            return true if l["const"] else true.Not()
        b = bs[int(l["var"])]
        return b.Not() if l["neg"] else b

    def as_int(l):
        """The 0/1 value of a JSON literal as a linear expression."""
        if "const" in l:
            return 1 if l["const"] else 0
        b = bs[int(l["var"])]
        return 1 - b if l["neg"] else b

    for j, d in enumerate(m["bools"]):
        b = bs[j]
        op = d["op"]
        if op == "ge":
            x, k = xs[int(d["var"])], int(d["k"])
            model.Add(x >= k).OnlyEnforceIf(b)
            model.Add(x <= k - 1).OnlyEnforceIf(b.Not())
        elif op == "diff_ge":
            xa, xb, k = xs[int(d["a"])], xs[int(d["b"])], int(d["k"])
            model.Add(xa - xb >= k).OnlyEnforceIf(b)
            model.Add(xa - xb <= k - 1).OnlyEnforceIf(b.Not())
        elif op == "and":
            ls = [lit(l) for l in d["lits"]]
            model.AddBoolAnd(ls).OnlyEnforceIf(b)
            model.AddBoolOr([l.Not() for l in ls]).OnlyEnforceIf(b.Not())
        elif op == "at_least":
            k = int(d["k"])
            # Repeated literals count with their multiplicity.
            s = sum(as_int(l) for l in d["lits"])
            model.Add(s >= k).OnlyEnforceIf(b)
            model.Add(s <= k - 1).OnlyEnforceIf(b.Not())
        else:
            raise ValueError(f"bools[{j}]: unknown op {op!r}")

    for c in m["clauses"]:
        # An empty clause is false (the model is infeasible).
        model.AddBoolOr([lit(l) for l in c] or [true.Not()])
    for h in m["hard"]:
        for l in h["lits"]:
            model.AddBoolOr([lit(l)])
    for s in m["symmetry"]:
        model.Add(sum(int(c) * xs[int(v)] for c, v in s["terms"]) <= int(s["rhs"]))
    for ci, cu in enumerate(m["cumulative"]):
        intervals, demands = [], []
        for ti, t in enumerate(cu["tasks"]):
            st = t["start"]
            if "const" in st:
                start = int(st["const"])
            else:
                start = int(st["scale"]) * xs[int(st["var"])] + int(st["offset"])
            dur = int(t["duration"])
            intervals.append(model.NewFixedSizeIntervalVar(start, dur, f"c{ci}t{ti}"))
            demands.append(int(t["demand"]))
        model.AddCumulative(intervals, demands, int(cu["capacity"]))

    soft_lits = [(int(s["coef"]), s["lit"]) for s in m["soft"]]
    constant = sum(c for c, l in soft_lits if l.get("const") is True)
    terms = [c * as_int(l) for c, l in soft_lits if "const" not in l]
    objective = constant + sum(terms)
    if terms:
        model.Maximize(objective)

    def value_of(solver, l):
        if "const" in l:
            return bool(l["const"])
        v = solver.BooleanValue(bs[int(l["var"])])
        return (not v) if l["neg"] else v

    return model, xs, soft_lits, value_of, objective


if __name__ == "__main__":
    main()
