#!/usr/bin/python3
"""Cross-check rbla's conic solver against CVXOPT on random LPs and SOCPs.

Each problem is generated in primal standard form  min c'x  s.t.  A x = b,  x in K
(K = R_+^l x Q^q1 x ... ) from a chosen primal-dual pair (x0, y0, z0):
  b = A x0,  c = A'y0 + z0.
"strict" problems take x0, z0 in the interior of K (unique bounded optimum, value found by the
solvers); "complementary" problems take x0, z0 on the boundary with x0'z0 = 0, so x0 is optimal
and the optimum c'x0 is known exactly (many cones at the apex, as in limit analysis).
The problem is written as CBF (by this script, independently of rbla's writer), solved by
`rbla_conic_cbf_solve`, and by cvxopt.solvers.conelp with G = -I, h = 0.

Usage (Debian python with python3-cvxopt and python3-numpy):
  /usr/bin/python3 tests/crosscheck/crosscheck_cvxopt.py --solver build-conic-bench/rbla_conic_cbf_solve
Exit status 0 when every objective agrees to --rtol (default 1e-6) relative; rbla must report
"solved" or "solved (reduced accuracy)" (the count of the latter is printed). Problems where
CVXOPT itself fails and no exact optimum is known are skipped and counted.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import cvxopt
from cvxopt import solvers, spmatrix, matrix


def random_cone_point(rng, l, socs, mode):
    """A point of K; mode 'interior', or a list of per-component roles for complementarity."""
    x = np.zeros(l + sum(socs))
    x[:l] = rng.uniform(0.5, 2.0, l)
    k = l
    for q in socs:
        u = rng.normal(size=q - 1)
        x[k] = np.linalg.norm(u) + rng.uniform(0.5, 2.0)
        x[k + 1:k + q] = u
        k += q
    return x


def complementary_pair(rng, l, socs):
    """x0, z0 in K with x0'z0 = 0 and strict complementarity."""
    n = l + sum(socs)
    x = np.zeros(n)
    z = np.zeros(n)
    for i in range(l):
        if rng.uniform() < 0.6:
            z[i] = rng.uniform(0.5, 2.0)  # x at zero
        else:
            x[i] = rng.uniform(0.5, 2.0)
    k = l
    for q in socs:
        role = rng.uniform()
        u = rng.normal(size=q - 1)
        u /= np.linalg.norm(u)
        if role < 0.5:  # x at the apex, z interior
            v = rng.normal(size=q - 1)
            z[k] = np.linalg.norm(v) + rng.uniform(0.5, 2.0)
            z[k + 1:k + q] = v
        elif role < 0.8:  # both on the boundary, opposite rays
            a, s = rng.uniform(0.5, 2.0, 2)
            x[k] = a
            x[k + 1:k + q] = a * u
            z[k] = s
            z[k + 1:k + q] = -s * u
        else:  # x interior, z at the apex
            v = rng.normal(size=q - 1)
            x[k] = np.linalg.norm(v) + rng.uniform(0.5, 2.0)
            x[k + 1:k + q] = v
        k += q
    return x, z


def generate(rng, kind):
    l = int(rng.integers(0, 30))
    socs = [int(rng.integers(2, 6)) for _ in range(int(rng.integers(0, 15)))]
    if l + len(socs) == 0:
        l = 5
    n = l + sum(socs)
    m = max(1, int(rng.integers(n // 4 + 1, max(n // 2, n // 4 + 1) + 2)))
    m = min(m, n - 1) if n > 1 else 1
    density = min(1.0, 4.0 / max(m, 1) + 0.05)
    A = np.where(rng.uniform(size=(m, n)) < density, rng.normal(size=(m, n)), 0.0)
    for i in range(m):  # no empty rows
        if not A[i].any():
            A[i, rng.integers(0, n)] = 1.0
    y0 = rng.normal(size=m)
    if kind == "strict":
        x0 = random_cone_point(rng, l, socs, "interior")
        z0 = random_cone_point(rng, l, socs, "interior")
        known = None
    else:
        x0, z0 = complementary_pair(rng, l, socs)
        known = None
    b = A @ x0
    c = A.T @ y0 + z0
    if kind != "strict":
        known = float(c @ x0)
    return A, b, c, l, socs, known


def write_cbf(path, A, b, c, l, socs):
    m, n = A.shape
    with open(path, "w") as f:
        f.write("VER\n3\n\nOBJSENSE\nMIN\n\n")
        cones = ([("L+", l)] if l > 0 else []) + [("Q", q) for q in socs]
        f.write("VAR\n%d %d\n" % (n, len(cones)))
        for name, size in cones:
            f.write("%s %d\n" % (name, size))
        f.write("\nCON\n%d 1\nL= %d\n\n" % (m, m))
        nz = [(j, c[j]) for j in range(n) if c[j] != 0]
        f.write("OBJACOORD\n%d\n" % len(nz))
        for j, v in nz:
            f.write("%d %.17g\n" % (j, v))
        rows, cols = np.nonzero(A)
        f.write("\nACOORD\n%d\n" % len(rows))
        for i, j in zip(rows, cols):
            f.write("%d %d %.17g\n" % (i, j, A[i, j]))
        nz = [(i, b[i]) for i in range(m) if b[i] != 0]
        f.write("\nBCOORD\n%d\n" % len(nz))
        for i, v in nz:
            f.write("%d %.17g\n" % (i, -v))


def solve_cvxopt(A, b, c, l, socs):
    m, n = A.shape
    G = spmatrix(-1.0, range(n), range(n))
    h = matrix(0.0, (n, 1))
    # Tight tolerances first; CVXOPT can raise near the end at 1e-10 (math domain error in its
    # scaling update), then it is rerun at its defaults (1e-7 absolute).
    for tol in (1e-10, 1e-7):
        solvers.options.update({"show_progress": False, "abstol": tol, "reltol": tol, "feastol": tol,
                                "maxiters": 200})
        try:
            res = solvers.conelp(matrix(c), G, h, {"l": l, "q": socs, "s": []}, A=matrix(A), b=matrix(b))
            return res["status"], res["primal objective"]
        except (ValueError, ArithmeticError):
            continue
    return "error", float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--solver", required=True, help="path to rbla_conic_cbf_solve")
    parser.add_argument("--count", type=int, default=40)
    parser.add_argument("--seed", type=int, default=20261121)
    parser.add_argument("--rtol", type=float, default=1e-6)
    parser.add_argument("--keep", help="directory to keep the CBF files in")
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    workdir = args.keep or tempfile.mkdtemp(prefix="rbla_crosscheck_")
    os.makedirs(workdir, exist_ok=True)
    failures = 0
    skipped = 0
    reduced = 0
    for k in range(args.count):
        kind = "strict" if k % 2 == 0 else "complementary"
        A, b, c, l, socs, known = generate(rng, kind)
        path = os.path.join(workdir, "problem_%03d.cbf" % k)
        write_cbf(path, A, b, c, l, socs)
        out = subprocess.run([args.solver, path], capture_output=True, text=True)
        if out.returncode != 0:
            print("problem %d: solver failed: %s" % (k, out.stderr.strip()))
            failures += 1
            continue
        ours = json.loads(out.stdout)
        cvx_status, cvx_obj = solve_cvxopt(A, b, c, l, socs)
        reference = known if known is not None else cvx_obj
        scale = max(1.0, abs(reference))
        # "solved (reduced accuracy)" counts if the objective still agrees; it is reported below.
        ok = ours["status"].startswith("solved") and abs(ours["primal_objective"] - reference) <= args.rtol * scale
        reduced += ours["status"] != "solved"
        if known is None and cvx_status != "optimal":
            print("problem %3d skipped: cvxopt status %s gives no reference" % (k, cvx_status))
            skipped += 1
            continue
        if known is not None and cvx_status == "optimal":
            ok = ok and abs(cvx_obj - known) <= 1e-5 * scale  # sanity of the reference itself
        print("problem %3d %-13s m=%3d n=%3d l=%2d socs=%2d  rbla %-8s %+.10e (%2d it)  cvxopt %-8s %+.10e%s  %s"
              % (k, kind, A.shape[0], A.shape[1], l, len(socs), ours["status"], ours["primal_objective"],
                 ours["iterations"], cvx_status, cvx_obj,
                 "" if known is None else "  exact %+.10e" % known, "ok" if ok else "MISMATCH"))
        failures += not ok
    print("%d of %d problems agree (%d of them at reduced accuracy), %d skipped (no CVXOPT reference)"
          % (args.count - failures - skipped, args.count - skipped, reduced, skipped))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
