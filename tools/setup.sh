#!/usr/bin/env bash
# First of README's two commands: install dependencies, build, and run the main job on a bundled
# sample (prints the verdict, writes the result JSON to out/).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install_deps.sh
tools/build.sh
mkdir -p out
./build/solver/rbla solve samples/wall_opening.json -o out/wall_opening.result.json --svg out/wall_opening
echo "setup: wrote out/wall_opening.result.json and the pictures in out/wall_opening/"
