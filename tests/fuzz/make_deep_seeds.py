#!/usr/bin/env python3
"""Writes the seed inputs of the two deep harnesses (docs/fuzzing.md):

  make_deep_seeds.py RBLA ANALYSIS_DIR CONIC_DIR [MODEL_DIR ...]

ANALYSIS_DIR gets the small models (at most 64 blocks, at most 64 kB, as fuzz_analysis
accepts them) among the samples, the schema examples, the model-stage seeds of make_seeds.py and
the JSON files of every MODEL_DIR (e.g. the stiff cases written by
`rbla_stiff_bench --fast --dump DIR`), minified. CONIC_DIR gets the conic problem of each of
them that `RBLA solve --dump-problem` writes (CBF, at most 64 kB), plus small hand-written
problems: feasible, infeasible and unbounded LPs and SOCPs, with and without free rows.
Standard library only, besides the rbla binary."""
import json
import pathlib
import subprocess
import sys
import tempfile

MAX_BYTES = 65536
MAX_BLOCKS = 64

root = pathlib.Path(__file__).resolve().parents[2]
rbla, analysis_dir, conic_dir = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
extra = [pathlib.Path(d) for d in sys.argv[4:]]
analysis_dir.mkdir(parents=True, exist_ok=True)
conic_dir.mkdir(parents=True, exist_ok=True)

candidates = sorted((root / "samples").glob("*.json")) + sorted((root / "schema" / "examples").glob("*.json"))
with tempfile.TemporaryDirectory() as tmp:
    subprocess.run([sys.executable, str(root / "tests" / "fuzz" / "make_seeds.py"), tmp], check=True,
                   stdout=subprocess.DEVNULL)
    seeds = sorted(pathlib.Path(tmp).glob("var_*.json"))
    texts = {p.stem: p.read_text() for p in candidates + seeds}
for d in extra:
    texts.update({p.stem: p.read_text() for p in sorted(d.glob("*.json"))})

kept = 0
problems = 0
with tempfile.TemporaryDirectory() as tmp:
    for name, text in sorted(texts.items()):
        try:
            doc = json.loads(text)
        except ValueError:
            continue
        if not isinstance(doc, dict) or len(doc.get("blocks", [])) > MAX_BLOCKS:
            continue
        small = json.dumps(doc, separators=(",", ":"))
        if len(small) > MAX_BYTES:
            continue
        (analysis_dir / (name + ".json")).write_text(small)
        kept += 1
        model = pathlib.Path(tmp) / "model.json"
        cbf = pathlib.Path(tmp) / "problem.cbf"
        model.write_text(small)
        cbf.unlink(missing_ok=True)
        subprocess.run([rbla, "solve", "-q", str(model), "--dump-problem", str(cbf)],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=120)
        if cbf.exists() and cbf.stat().st_size <= MAX_BYTES:
            (conic_dir / (name + ".cbf")).write_bytes(cbf.read_bytes())
            problems += 1


def cbf(name, n, cones, rows, c, a, b, sense="MIN"):
    """cones: [("L+", k) | ("Q", k)], a: [(row, col, value)], b: the CBF constant (A x + b = 0)."""
    lines = ["VER", "3", "", "OBJSENSE", sense, "", "VAR", f"{n} {len(cones)}"]
    lines += [f"{kind} {size}" for kind, size in cones]
    if rows:
        lines += ["", "CON", f"{rows} 1", f"L= {rows}"]
    lines += ["", "OBJACOORD", str(len(c))] + [f"{j} {v}" for j, v in c]
    lines += ["", "ACOORD", str(len(a))] + [f"{i} {j} {v}" for i, j, v in a]
    if b:
        lines += ["", "BCOORD", str(len(b))] + [f"{i} {v}" for i, v in b]
    (conic_dir / (name + ".cbf")).write_text("\n".join(lines) + "\n")


# min x0 + x1, x0 + x1 = 1, x >= 0 (optimum 1, a whole face of solutions).
cbf("hand_lp_face", 2, [("L+", 2)], 1, [(0, 1), (1, 1)], [(0, 0, 1), (0, 1, 1)], [(0, -1)])
# x0 + x1 = -1, x >= 0: infeasible.
cbf("hand_lp_infeasible", 2, [("L+", 2)], 1, [(0, 1)], [(0, 0, 1), (0, 1, 1)], [(0, 1)])
# min -x0, x0 - x1 = 0: unbounded.
cbf("hand_lp_unbounded", 2, [("L+", 2)], 1, [(0, -1)], [(0, 0, 1), (0, 1, -1)], [])
# min t, (t, u1, u2) in Q3, u1 = 3, u2 = 4: optimum 5.
cbf("hand_socp", 3, [("Q", 3)], 2, [(0, 1)], [(0, 1, 1), (1, 2, 1)], [(0, -3), (1, -4)])
# max alpha with one nonnegative variable and a cone, the shape of rbla's problems.
cbf("hand_max_mixed", 4, [("L+", 1), ("Q", 3)], 2, [(0, 1)], [(0, 0, 1), (0, 1, -1), (1, 2, 1), (1, 3, 1)],
    [(0, 0), (1, -0.5)], sense="MAX")
# (t, u) in Q2 with t = -1: infeasible cone constraint.
cbf("hand_socp_infeasible", 2, [("Q", 2)], 1, [(1, 1)], [(0, 0, 1)], [(0, 1)])
print(f"{kept} models in {analysis_dir}, {problems + 6} problems in {conic_dir}")
