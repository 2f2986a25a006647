#!/usr/bin/python3
"""Solve a CBF conic problem with CVXOPT and print one JSON line (the report's CVXOPT peer).

Reads the CBF v3 subset that linear and second-order cone problems use: VAR cones L+, L-, F, Q;
CON cones L=, L+, L-; OBJACOORD, OBJBCOORD, ACOORD, BCOORD (CBF: A x + b in K). The problem
becomes CVXOPT's conelp form

    min c'x + c0   s.t.   G x + s = h,  s in R+^l x Q^q1 x ...,   A x = b,

with G = -I on the cone variables (a free variable is split into two nonnegative ones; an L-
variable is negated), and inequality rows (L+, L-) as extra nonnegative slack rows of G.

Why a custom KKT solver: CVXOPT's built-in KKT solvers for problems with second-order cones
('qr', 'ldl', 'chol') are dense, so a problem with 60 000 variables does not fit in memory.
The solver here uses the structure G = -I: eliminating x and z leaves the normal equations

    (A H A') dy = A (H bx - bz) - by,   H = W'W (block diagonal: d^2 on R+, a 3x3 block per cone),

factorised by CHOLMOD (cvxopt.cholmod, a fresh symbolic analysis each iteration, since the
pattern is fixed this costs little). Columns of A that are much denser than the rest (the load
multiplier of a seismic load touches every block) are kept out of A H A' and added back by the
Sherman-Morrison-Woodbury formula, as interior-point codes do; they must be nonnegative
variables (diagonal H). CVXOPT's own iteration, stopping criteria and step rules are unchanged.

Usage: /usr/bin/python3 bench/report/cvxopt_cbf.py PROBLEM.cbf [--tol T] [--maxiters N]
Prints: {"status", "primal_objective", "dual_objective", "iterations", "read_seconds",
"solve_seconds", "gap", "relative_gap", "primal_infeasibility", "dual_infeasibility", ...}.
Exit status 0 when CVXOPT returned (whatever its status), 2 on a reading or KKT failure.
"""
import argparse
import json
import sys
import time

import numpy as np
from cvxopt import cholmod, matrix, solvers, spmatrix


def read_cbf(path):
    """Parse a CBF file into plain Python/numpy structures."""
    with open(path) as fh:
        lines = [ln.strip() for ln in fh]
    lines = [ln for ln in lines if ln and not ln.startswith("#")]
    i = 0
    prob = {"sense": "MIN", "var_cones": [], "con_cones": [], "c": {}, "c0": 0.0,
            "A": ([], [], []), "b": {}}

    def nxt():
        nonlocal i
        i += 1
        return lines[i - 1]

    while i < len(lines):
        key = nxt()
        if key == "VER":
            nxt()
        elif key == "OBJSENSE":
            prob["sense"] = nxt()
        elif key in ("VAR", "CON"):
            n, k = (int(t) for t in nxt().split())
            cones = []
            for _ in range(k):
                name, size = nxt().split()
                cones.append((name, int(size)))
            prob["n" if key == "VAR" else "m"] = n
            prob["var_cones" if key == "VAR" else "con_cones"] = cones
        elif key == "OBJACOORD":
            for _ in range(int(nxt())):
                j, v = nxt().split()
                prob["c"][int(j)] = float(v)
        elif key == "OBJBCOORD":
            prob["c0"] = float(nxt())
        elif key == "ACOORD":
            rows, cols, vals = prob["A"]
            for _ in range(int(nxt())):
                r, c, v = nxt().split()
                rows.append(int(r))
                cols.append(int(c))
                vals.append(float(v))
        elif key == "BCOORD":
            for _ in range(int(nxt())):
                r, v = nxt().split()
                prob["b"][int(r)] = float(v)
        else:
            raise ValueError("unsupported CBF section %r" % key)
    prob.setdefault("m", 0)
    return prob


def to_conelp(prob):
    """CBF -> (c, G, h, dims, A, b, c0, sign), with x ordered as CVXOPT's cone blocks."""
    n, m = prob["n"], prob["m"]
    # variable map: new column index and a sign for every CBF variable (free ones get two)
    lin, socs, free = [], [], []  # CBF indices
    pos = 0
    neg_vars = set()
    for name, size in prob["var_cones"]:
        idx = list(range(pos, pos + size))
        pos += size
        if name == "L+":
            lin.extend(idx)
        elif name == "L-":
            lin.extend(idx)
            neg_vars.update(idx)
        elif name == "F":
            free.extend(idx)
        elif name == "Q":
            socs.append(idx)
        else:
            raise ValueError("unsupported variable cone %s" % name)
    if pos != n:
        raise ValueError("VAR cones cover %d of %d variables" % (pos, n))
    # columns: [lin..., free+ ..., free- ..., soc1..., soc2...]
    cols = {}  # CBF var -> list of (new column, sign)
    k = 0
    for j in lin:
        cols[j] = [(k, -1.0 if j in neg_vars else 1.0)]
        k += 1
    for j in free:
        cols[j] = [(k, 1.0)]
        k += 1
    for j in free:
        cols[j].append((k, -1.0))
        k += 1
    num_l_vars = k
    for cone in socs:
        for j in cone:
            cols[j] = [(k, 1.0)]
            k += 1
    nn = k
    c = np.zeros(nn)
    for j, v in prob["c"].items():
        for col, s in cols[j]:
            c[col] += s * v
    if prob["sense"] == "MAX":
        c = -c
    # rows: equality rows go to A; L+/L- rows become slack rows of G (in the 'l' block)
    row_kind = []
    for name, size in prob["con_cones"]:
        if name not in ("L=", "L+", "L-"):
            raise ValueError("unsupported constraint cone %s" % name)
        row_kind.extend([name] * size)
    eq_rows = [r for r in range(m) if row_kind[r] == "L="]
    ineq_rows = [r for r in range(m) if row_kind[r] != "L="]
    eq_index = {r: i for i, r in enumerate(eq_rows)}
    in_index = {r: i for i, r in enumerate(ineq_rows)}
    bvec = np.zeros(m)
    for r, v in prob["b"].items():
        bvec[r] = v
    Ar, Ac, Av = [], [], []
    Gr, Gc, Gv = [], [], []
    rows, cbf_cols, vals = prob["A"]
    for r, j, v in zip(rows, cbf_cols, vals):
        for col, s in cols[j]:
            if row_kind[r] == "L=":
                Ar.append(eq_index[r])
                Ac.append(col)
                Av.append(s * v)
            else:
                # L+: a x + b >= 0  ->  -a x <= b ; L-: a x + b <= 0  ->  a x <= -b
                sg = -1.0 if row_kind[r] == "L+" else 1.0
                Gr.append(in_index[r])
                Gc.append(col)
                Gv.append(sg * s * v)
    h_ineq = np.array([bvec[r] if row_kind[r] == "L+" else -bvec[r] for r in ineq_rows])
    b_eq = np.array([-bvec[r] for r in eq_rows])  # A x + b = 0  ->  A x = -b
    # G: the inequality rows first, then -I on the nonnegative variables, then -I on the cones
    n_in = len(ineq_rows)
    Gr += [n_in + t for t in range(nn)]
    Gc += list(range(nn))
    Gv += [-1.0] * nn
    dims = {"l": n_in + num_l_vars, "q": [len(cone) for cone in socs], "s": []}
    h = np.concatenate([h_ineq, np.zeros(nn)])
    return {"c": c, "G": (Gr, Gc, Gv, n_in + nn, nn), "h": h, "dims": dims,
            "A": (Ar, Ac, Av, len(eq_rows), nn), "b": b_eq, "c0": prob["c0"],
            "sign": -1.0 if prob["sense"] == "MAX" else 1.0, "n_ineq_rows": n_in}


class NormalEquationsKKT(object):
    """KKT solver for conelp when G = [G_in; -I] with G_in empty (see the module docstring)."""

    def __init__(self, A_coo, dims, dense_factor=10.0):
        Ar, Ac, Av, p, n = A_coo
        self.p, self.n, self.dims = p, n, dims
        Ar, Ac, Av = np.asarray(Ar), np.asarray(Ac), np.asarray(Av)
        counts = np.bincount(Ac, minlength=n)
        nz = counts[counts > 0]
        threshold = max(40.0, dense_factor * (np.median(nz) if nz.size else 1.0), 0.05 * p)
        dense = np.nonzero(counts > threshold)[0]
        if dense.size and np.any(dense >= dims["l"]):
            dense = dense[dense < dims["l"]]  # only nonnegative (diagonal-H) columns are split off
        self.dense = dense
        keep = ~np.isin(Ac, dense)
        self.A = spmatrix(Av.tolist(), Ar.tolist(), Ac.tolist(), (p, n))
        self.As = spmatrix(Av[keep].tolist(), Ar[keep].tolist(), Ac[keep].tolist(), (p, n))
        self.Ad = np.zeros((p, dense.size))
        for k, j in enumerate(dense):
            sel = Ac == j
            np.add.at(self.Ad[:, k], Ar[sel], Av[sel])
        self.l = dims["l"]
        q = dims["q"]
        self.qsize = q[0] if q else 0
        if q and any(s != self.qsize for s in q):
            raise ValueError("cones of different sizes are not supported by this KKT solver")
        self.nq = len(q)
        # pattern of the block-diagonal H: diagonal on l, full blocks on the cones
        I, J = list(range(self.l)), list(range(self.l))
        base = self.l
        s = self.qsize
        for k in range(self.nq):
            for a in range(s):
                for b in range(s):
                    I.append(base + k * s + a)
                    J.append(base + k * s + b)
        self.HI, self.HJ = I, J

    def factor(self, W):
        l, s, nq = self.l, self.qsize, self.nq
        d = np.array(W["d"]).ravel()
        vals = [d * d]
        if nq:
            beta = np.array(W["beta"])
            V = np.array([np.array(v).ravel() for v in W["v"]])  # nq x s
            J = np.ones(s)
            J[1:] = -1.0
            vJ = V * J  # rows v_i J
            # (2 v v' - J)^2 = 4 (v'v) v v' - 2 (v v'J + J v v') + I
            vv = np.einsum("ki,kj->kij", V, V)
            blk = (4.0 * np.einsum("k,kij->kij", (V * V).sum(1), vv)
                   - 2.0 * (np.einsum("ki,kj->kij", V, vJ) + np.einsum("ki,kj->kij", vJ, V))
                   + np.eye(s)[None, :, :])
            blk *= (beta * beta)[:, None, None]
            vals.append(blk.reshape(-1))
        Hv = np.concatenate(vals)
        H = spmatrix(Hv.tolist(), self.HI, self.HJ, (self.n, self.n))
        M = self.As * H * self.As.T
        F = cholmod.symbolic(M)
        try:
            cholmod.numeric(M, F)
        except ArithmeticError:
            # not positive definite in floating point: a relative diagonal shift per row,
            # which CVXOPT's iterative refinement then corrects for
            D = np.array([M[i, i] for i in range(self.p)])
            M = M + spmatrix((1e-12 * np.maximum(np.abs(D), 1e-300)).tolist(),
                             range(self.p), range(self.p))
            cholmod.numeric(M, F)
        # dense columns: M_full = M + Ad diag(h) Ad'
        if self.dense.size:
            h = (d * d)[self.dense]
            Z = matrix(self.Ad.copy())
            cholmod.solve(F, Z)
            Z = np.array(Z)
            small = np.diag(1.0 / h) + self.Ad.T @ Z
        else:
            Z, small = None, None

        def solve_M(r):
            x = matrix(r)
            cholmod.solve(F, x)
            x = np.array(x).ravel()
            if Z is not None:
                x = x - Z @ np.linalg.solve(small, self.Ad.T @ x)
            return x

        Hfull = spmatrix(Hv.tolist(), self.HI, self.HJ, (self.n, self.n))

        def apply_W(u):
            out = np.empty_like(u)
            out[:l] = d * u[:l]
            if nq:
                U = u[l:].reshape(nq, s)
                Ju = U.copy()
                Ju[:, 1:] *= -1.0
                vu = (V * U).sum(1)
                out[l:] = (beta[:, None] * (2.0 * V * vu[:, None] - Ju)).reshape(-1)
            return out

        def solve(x, y, z):
            bx = np.array(x).ravel()
            by = np.array(y).ravel()
            bz = np.array(z).ravel()
            Hbx = np.array(Hfull * matrix(bx)).ravel()
            rhs = np.array(self.A * matrix(Hbx - bz)).ravel() - by
            uy = solve_M(rhs)
            uz = np.array(self.A.T * matrix(uy)).ravel() - bx
            ux = -bz - np.array(Hfull * matrix(uz)).ravel()
            x[:] = matrix(ux)
            y[:] = matrix(uy)
            z[:] = matrix(apply_W(uz))

        return solve


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("cbf")
    ap.add_argument("--tol", type=float, default=1e-7,
                    help="abstol, reltol and feastol of CVXOPT (its defaults: 1e-7, 1e-6, 1e-7)")
    ap.add_argument("--maxiters", type=int, default=100, help="CVXOPT's maxiters (its default 100)")
    ap.add_argument("--refinement", type=int, default=None,
                    help="CVXOPT's iterative refinement steps (its default: 0 for LPs, 1 with cones)")
    ap.add_argument("--verbose", action="store_true")
    args = ap.parse_args()
    t0 = time.perf_counter()
    try:
        prob = read_cbf(args.cbf)
        P = to_conelp(prob)
    except (ValueError, KeyError, IndexError) as e:
        print(json.dumps({"status": "read_error", "message": str(e)}))
        return 2
    if P["n_ineq_rows"]:
        print(json.dumps({"status": "unsupported", "message": "inequality rows (L+/L-) in CON"}))
        return 2
    Gr, Gc, Gv, gm, gn = P["G"]
    G = spmatrix(Gv, Gr, Gc, (gm, gn))
    Ar, Ac, Av, am, an = P["A"]
    A = spmatrix(Av, Ar, Ac, (am, an))
    kkt = NormalEquationsKKT(P["A"], P["dims"])
    t1 = time.perf_counter()
    solvers.options.clear()
    solvers.options.update({"show_progress": args.verbose, "abstol": args.tol, "reltol": args.tol,
                            "feastol": args.tol, "maxiters": args.maxiters})
    if args.refinement is not None:
        solvers.options["refinement"] = args.refinement
    out = {"tol": args.tol, "num_variables": gn, "num_equality_rows": am,
           "num_cones": len(P["dims"]["q"]), "num_dense_columns": int(kkt.dense.size),
           "kkt": "normal equations, CHOLMOD (cvxopt.cholmod), dense columns by Sherman-Morrison"}
    try:
        sol = solvers.conelp(matrix(P["c"]), G, matrix(P["h"]), P["dims"], A=A, b=matrix(P["b"]),
                             kktsolver=kkt.factor)
    except (ArithmeticError, ValueError) as e:
        t2 = time.perf_counter()
        out.update({"status": "error", "message": str(e), "read_seconds": t1 - t0,
                    "solve_seconds": t2 - t1})
        print(json.dumps(out))
        return 0
    t2 = time.perf_counter()
    sign, c0 = P["sign"], P["c0"]

    def obj(v):
        return None if v is None else sign * (v + c0)

    out.update({"status": sol["status"], "primal_objective": obj(sol["primal objective"]),
                "dual_objective": obj(sol["dual objective"]), "iterations": sol["iterations"],
                "gap": sol["gap"], "relative_gap": sol["relative gap"],
                "primal_infeasibility": sol["primal infeasibility"],
                "dual_infeasibility": sol["dual infeasibility"],
                "read_seconds": t1 - t0, "solve_seconds": t2 - t1})
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
