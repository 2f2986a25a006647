#!/usr/bin/env bash
# First of README's two commands: install dependencies, build, and run the main job on a bundled
# sample (prints the verdict, writes the result JSON to out/).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install_deps.sh
tools/build.sh
mkdir -p out
./build/solver/rbla info samples/wall_opening.json -o out/wall_opening.info.json
echo "setup: wrote out/wall_opening.info.json"
