#!/usr/bin/env python3
"""Solve a MiniZinc model written by `rccpack synth --emit model.mzn` with
MiniZinc and Gecode.

    python3 minizinc.py MODEL.mzn [--time-limit SECONDS] [--workers N] [--solver gecode]

Runs `minizinc --solver gecode --time-limit MS MODEL.mzn` and prints ONE
JSON line on stdout:

    {"status": "optimal"|"feasible"|"infeasible"|"unknown",
     "values": [grid value per model variable] or null,
     "objective": int or null, "time_s": float}

`==========` after the last solution means proven optimal,
`=====UNSATISFIABLE=====` infeasible, a solution without the marker
feasible (the time limit struck), no solution unknown. `time_s` is the wall
time of the whole `minizinc` run (flattening included). Errors (minizinc
missing, `=====ERROR=====`, output it cannot read) go to stderr with exit
code 1.
"""

import argparse
import json
import re
import subprocess
import sys
import time

VALUES = re.compile(r"^values = (\[.*\])\s*$")
OBJECTIVE = re.compile(r"^objective = (-?\d+)\s*$")


def fail(msg):
    print(f"minizinc.py: {msg}", file=sys.stderr)
    sys.exit(1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("model", help="MiniZinc model (.mzn) written by rccpack")
    ap.add_argument("--time-limit", type=float, default=None, metavar="SECONDS")
    ap.add_argument("--workers", type=int, default=1, metavar="N")
    ap.add_argument("--solver", default="gecode")
    args = ap.parse_args()
    if args.workers < 1:
        fail(f"--workers {args.workers}: expected at least 1")
    if args.time_limit is not None and not (args.time_limit >= 0):
        fail(f"--time-limit {args.time_limit}: expected a number of seconds >= 0")

    cmd = ["minizinc", "--solver", args.solver]
    if args.time_limit is not None:
        # minizinc wants whole milliseconds, at least 1.
        cmd += ["--time-limit", str(max(1, int(round(args.time_limit * 1000))))]
    if args.workers > 1:
        cmd += ["-p", str(args.workers)]
    cmd.append(args.model)
    # A safety net beyond minizinc's own limit.
    timeout = None if args.time_limit is None else args.time_limit + 60
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except FileNotFoundError:
        fail("`minizinc` is not on PATH; install it (Debian: `apt-get install minizinc`)")
    except subprocess.TimeoutExpired:
        fail(f"minizinc still running {timeout} s after the start, killed")
    elapsed = time.perf_counter() - t0

    out = p.stdout.splitlines()
    if any(l.strip() == "=====ERROR=====" for l in out) or p.returncode != 0:
        tail = "\n".join((p.stderr or p.stdout).splitlines()[-15:])
        fail(f"minizinc failed (exit {p.returncode}):\n{tail}")

    values = None
    objective = None
    pending_values = None
    pending_objective = None
    optimal = False
    infeasible = False
    for line in out:
        s = line.strip()
        mv = VALUES.match(s)
        mo = OBJECTIVE.match(s)
        if mv:
            pending_values = json.loads(mv.group(1))
        elif mo:
            pending_objective = int(mo.group(1))
        elif s == "----------":
            # A complete solution.
            if pending_values is None or pending_objective is None:
                fail("a solution without `values = ` and `objective = ` lines")
            values, objective = pending_values, pending_objective
            pending_values = pending_objective = None
        elif s == "==========":
            optimal = True
        elif s == "=====UNSATISFIABLE=====":
            infeasible = True
    if infeasible:
        status, values, objective = "infeasible", None, None
    elif values is not None:
        status = "optimal" if optimal else "feasible"
    else:
        status = "unknown"
    if values is not None and not all(isinstance(v, int) for v in values):
        fail(f"values that are not integers: {values!r}")
    print(json.dumps({"status": status, "values": values,
                      "objective": objective, "time_s": elapsed}))


if __name__ == "__main__":
    main()
