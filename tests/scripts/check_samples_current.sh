#!/usr/bin/env bash
# The bundled samples are exactly what the generator writes today (so samples stay current with
# the code), and the generator's own geometric self-check passes.
set -euo pipefail
python=${1:?python interpreter}; source_dir=${2:?source dir}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$python" "$source_dir/samples/generate_samples.py" all --dir "$tmp" --self-check >/dev/null
status=0
for f in "$tmp"/*.json; do
  name=$(basename "$f")
  if ! cmp -s "$f" "$source_dir/samples/$name"; then
    echo "samples/$name differs from what generate_samples.py writes; regenerate with:"
    echo "  python3 samples/generate_samples.py all --dir samples/ --self-check"
    status=1
  fi
done
exit $status
