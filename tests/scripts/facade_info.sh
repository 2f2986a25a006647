#!/usr/bin/env bash
# Issue 2's acceptance scene: a generated running-bond façade of about 1900 blocks loads through
# the whole model stage and detection finds over 20000 contact points. (Time is reported by
# bench/, never asserted here: the machines are shared.)
set -euo pipefail
python=${1:?python interpreter}; source_dir=${2:?source dir}; rbla=${3:?rbla binary}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$python" "$source_dir/samples/generate_samples.py" facade -o "$tmp/facade.json" 2>/dev/null
"$rbla" info -q "$tmp/facade.json" | tee "$tmp/info.txt"
points=$(awk '/^contact points:/ {print $3}' "$tmp/info.txt")
blocks=$(awk '/^blocks:/ {print $2}' "$tmp/info.txt")
[ "$blocks" -ge 1800 ] || { echo "expected about 1900 blocks, got $blocks"; exit 1; }
[ "$points" -gt 20000 ] || { echo "expected over 20000 contact points, got $points"; exit 1; }
echo "ok: $blocks blocks, $points contact points"
