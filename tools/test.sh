#!/usr/bin/env bash
# Second of README's two commands: install what is missing, build, run the whole test suite.
# Extra arguments select tests of the main run (ctest -L unit, -R name, ...) and then skip the
# two whole-suite stages that follow it.
set -euo pipefail
cd "$(dirname "$0")/.."
# Each stage's start time goes to the log, so that CI runs show where their time went.
stage() { echo "test.sh: $1 at $(date -u +%T)"; }
stage "dependencies and build"
tools/install_deps.sh
tools/build.sh
stage "tests"
ctest --test-dir build --output-on-failure -j"$(nproc)" "$@"
[ $# -eq 0 ] || exit 0
# Memory errors and undefined behaviour the Release run cannot see: the suite under ASan+UBSan.
stage "sanitizer build and tests"
tools/sanitize.sh
# 35 s each of coverage-guided fuzzing of the model stage, the whole analysis and the conic
# solver, starting from the committed corpora (tests/fuzz/corpus*), with the harnesses that
# tools/sanitize.sh built.
stage "fuzz smoke run"
tools/fuzz.sh --smoke --tree build-asan-ci
stage "end"
