#!/usr/bin/python3
"""Solve a linear program written by `rbla solve --dump-problem` with HiGHS's interior point.

An outside reference for rbla's iteration counts: HiGHS's IPX (an interior-point method with
basis-preconditioned conjugate gradients, then crossover), reached through SciPy's `linprog`.
Only the LP subset of the CBF files rbla writes is read (planar formulations: `L+` variables,
`L=` rows): min c'x  s.t.  A x + b = 0 (CBF's sign),  x >= 0.

    /usr/bin/python3 bench/conic/highs_lp.py problem.cbf [--method highs-ipm|highs-ds]
    /usr/bin/python3 bench/conic/highs_lp.py problem.cbf --check solution.txt

Prints HiGHS's log and then one JSON line: status, objective, IPM iterations, seconds. With
--check it solves nothing and measures a solution written by `rbla_conic_cbf_solve
--write-solution` on the data of the file: the primal residual ||A x + b||_inf, min x and c'x;
the dual slack c - A'y (its most negative entry) and the dual objective -b'y.
Needs Debian's python3-scipy (1.10 ships HiGHS); not a test, not run by CI.
"""
import argparse
import json
import sys
import time

import numpy as np
from scipy.optimize import linprog
from scipy.sparse import csc_matrix


def read_cbf_lp(path):
    """(c, A as (rows, cols, values), b, n, m) of an LP-only CBF file; exits on other cones."""
    with open(path) as f:
        lines = [line.strip() for line in f if not line.startswith("#")]
    n = m = 0
    c, rows, cols, vals, b = {}, [], [], [], {}
    i = 0
    while i < len(lines):
        key = lines[i]
        if key in ("VAR", "CON"):
            size, parts = lines[i + 1].split()
            cone = lines[i + 2].split()[0]
            if int(parts) != 1 or cone != ("L+" if key == "VAR" else "L="):
                sys.exit(f"{path}: only one L+ variable block and one L= row block are read (an LP)")
            if key == "VAR":
                n = int(size)
            else:
                m = int(size)
            i += 3
        elif key in ("OBJACOORD", "ACOORD", "BCOORD"):
            count = int(lines[i + 1])
            for entry in lines[i + 2:i + 2 + count]:
                fields = entry.split()
                if key == "OBJACOORD":
                    c[int(fields[0])] = float(fields[1])
                elif key == "ACOORD":
                    rows.append(int(fields[0]))
                    cols.append(int(fields[1]))
                    vals.append(float(fields[2]))
                else:
                    b[int(fields[0])] = float(fields[1])
            i += 2 + count
        else:
            i += 1
    return c, (rows, cols, vals), b, n, m


def read_solution(path):
    """{'x': array, 'y': array, 'z': array} of rbla_conic_cbf_solve --write-solution."""
    vectors, name, values = {}, None, []
    with open(path) as f:
        for line in f:
            fields = line.split()
            if fields[0] in ("x", "y", "z"):
                if name:
                    vectors[name] = np.array(values)
                name, values = fields[0], []
            else:
                values.append(float(fields[0]))
    vectors[name] = np.array(values)
    return vectors


def check(A, cost, rhs, solution):
    """Feasibility and objectives of rbla's x and y for min c'x, A x = rhs, x >= 0."""
    x, y = solution["x"], solution["y"]
    slack = cost - A.T @ y
    return {"primal_objective": float(cost @ x), "primal_residual": float(np.abs(A @ x - rhs).max()),
            "min_x": float(x.min()), "dual_objective": float(rhs @ y), "min_dual_slack": float(slack.min())}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cbf")
    parser.add_argument("--method", default="highs-ipm")
    parser.add_argument("--check", help="a solution of rbla_conic_cbf_solve --write-solution to measure")
    args = parser.parse_args()
    c, (rows, cols, vals), b, n, m = read_cbf_lp(args.cbf)
    cost = np.zeros(n)
    for j, v in c.items():
        cost[j] = v
    rhs = np.zeros(m)
    for r, v in b.items():
        rhs[r] = -v  # CBF: A x + b = 0
    A = csc_matrix((vals, (rows, cols)), shape=(m, n))
    if args.check:
        print(json.dumps(check(A, cost, rhs, read_solution(args.check))))
        return
    start = time.time()
    result = linprog(cost, A_eq=A, b_eq=rhs, bounds=(0, None), method=args.method,
                     options={"disp": True, "presolve": True})
    seconds = time.time() - start
    print(json.dumps({"status": result.status, "message": result.message, "objective": result.fun,
                      "ipm_iterations": getattr(result, "nit", None), "seconds": round(seconds, 2)}))


if __name__ == "__main__":
    main()
