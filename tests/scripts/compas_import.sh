#!/usr/bin/env bash
# Real, imperfect CAD geometry from other tools (../shared/data/compas, COMPAS projects, MIT):
# every assembly converts to a valid model, loads through the whole model stage, and where
# COMPAS stored its own interfaces our detection finds the same number.
set -euo pipefail
python=${1:?python}; source_dir=${2:?source dir}; rbla=${3:?rbla binary}
data="$source_dir/../shared/data/compas"
[ -d "$data" ] || { echo "no $data: skipped"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
declare -A compas_count
failures=0; converted=0
for f in "$data"/*/*.json; do
  name=$(basename "$(dirname "$f")")__$(basename "$f")
  if ! (cd "$source_dir/plugin" && "$python" -m rbla_cad.compas_import "$f" -o "$tmp/$name") 2>"$tmp/err"; then
    # wall.json is the example's input data (a curve and loose boxes), not an assembly.
    if [ "$(basename "$f")" = "wall.json" ]; then continue; fi
    echo "FAIL convert $name: $(cat "$tmp/err")"; failures=$((failures + 1)); continue
  fi
  converted=$((converted + 1))
  if ! "$rbla" info -q "$tmp/$name" >"$tmp/info" 2>&1; then
    echo "FAIL load $name:"; cat "$tmp/info"; failures=$((failures + 1)); continue
  fi
  detected=$(awk '/^interfaces:/ {print $2}' "$tmp/info")
  if (cd "$source_dir/plugin" && "$python" -m rbla_cad.compas_import "$f" --interfaces -o "$tmp/with_$name") 2>/dev/null; then
    stored=$("$python" -c "import json,sys; print(len(json.load(open(sys.argv[1])).get('interfaces', [])))" "$tmp/with_$name")
    case "$name" in
      # COMPAS merges the faceted contacts of these curved interlocking pieces differently.
      compas_cra__concave-*) ;;
      *) if [ "$stored" -gt 0 ] && [ "$stored" != "$detected" ]; then
           echo "FAIL $name: COMPAS stored $stored interfaces, rbla detected $detected"; failures=$((failures + 1))
         fi ;;
    esac
  fi
  echo "ok $name: $detected interfaces"
done
echo "$converted converted, $failures failures"
[ "$converted" -ge 19 ] && [ "$failures" -eq 0 ]
