#!/bin/bash
# The scale table of docs/benchmark/scale.md: generated façade (running bond), church (openings)
# and town house (English bond, windows with flat lintels; the scene not tuned on), 3-D cones
# forced, one whole run of rbla solve per case with /usr/bin/time. Minutes (30k blocks: about
# 100 s per run). SPECS="townhouse 5 3|townhouse 10 6" runs a subset. Writes one line per case to $OUT/table.txt: scene load blocks iterations
# seconds peak_MiB status value.
cd "$(dirname "$0")/../.."
mkdir -p "${OUT:-/tmp/scale}"
R=build/solver/rbla
out=${OUT:-/tmp/scale}/table.txt
: > $out
gen() { python3 samples/generate_samples.py "$@" 2>/dev/null >/dev/null; }
SPECS=${SPECS:-"facade 50 38|facade 100 76|facade 200 152|church 2000|church 8000|church 30000|townhouse 5 3|townhouse 10 6|townhouse 20 11"}
IFS='|' read -ra SPEC_LIST <<< "$SPECS"
for spec in "${SPEC_LIST[@]}"; do
  set -- $spec
  for load in seismic settlement; do
    f=${OUT:-/tmp/scale}/m.json
    if [ $1 = facade ]; then
      if [ $load = seismic ]; then gen facade --nx $2 --ny $3 --seismic x -o $f; else gen facade --nx $2 --ny $3 --settling-fraction 0.5 -o $f; fi
    elif [ $1 = townhouse ]; then
      if [ $load = seismic ]; then gen townhouse --bays $2 --storeys $3 --load seismic-x -o $f; else gen townhouse --bays $2 --storeys $3 --load settlement -o $f; fi
    else
      if [ $load = seismic ]; then gen church --blocks $2 --load seismic-x -o $f; else gen church --blocks $2 --load settlement -o $f; fi
    fi
    python3 - <<PY
import json; m=json.load(open('$f')); m['analysis']['formulation']='3d'; json.dump(m,open('$f','w'))
PY
    /usr/bin/time -f "%e %M" -o ${OUT:-/tmp/scale}/time.txt $R solve $f -q -o ${OUT:-/tmp/scale}/r.json
    python3 - <<PY >> $out
import json
r=json.load(open('${OUT:-/tmp/scale}/r.json')); t=open('${OUT:-/tmp/scale}/time.txt').read().split()
it=r.get('solver',{}).get('iterations')
print('$1', '$load', r['model_summary']['num_blocks'], it, t[0], int(t[1])//1024, r['status'], r.get('load_multiplier') or r.get('base_reaction',{}).get('at_collapse'))
PY
    tail -1 $out
  done
done
echo done >> $out
