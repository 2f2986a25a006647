#!/usr/bin/env bash
# Builds the test suite with AddressSanitizer + UndefinedBehaviorSanitizer (clang, RBLA_SANITIZE)
# into build-asan-ci/ and runs it. Any sanitizer report fails its test: UB does not recover
# (-fno-sanitize-recover) and ASan stops at the first error. Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
# clang, not GCC: its ASan+UBSan build of this code takes two thirds of the time of GCC's at the
# same -O1 and the tests a fifth longer, a net saving of about a fifth of the stage
# (docs/benchmark/measurements.md); and a second compiler catches what the first lets through
# (the order in which function arguments are evaluated differs, for one).
# -O1 with line tables only: reports name files and lines, at little build cost over no -g.
# The fuzz harnesses come with it, the libraries instrumented with edge counters only: the CI's
# fuzz smoke run uses them (tools/fuzz.sh --smoke --tree build-asan-ci) instead of building a
# tree of its own, and the counters did not slow the tests measurably (docs/fuzzing.md).
cmake -S . -B build-asan-ci -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DRBLA_SANITIZE=ON -DRBLA_FUZZ=ON -DRBLA_FUZZ_COVERAGE=edges \
      "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only -DNDEBUG" >/dev/null
cmake --build build-asan-ci -j"$(nproc)"
# detect_stack_use_after_return stays off (ASan's default): it nearly doubles the CPU time of the
# stiff cases.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Excluded: web. It installs npm packages and drives headless Chromium for minutes to test the
# JavaScript viewer and .3dm exchange; the only C++ it reaches is `rbla solve` on the samples,
# which the regression and CLI tests already run here under the sanitizers.
# Also excluded: the label heavy, two whole-scene script tests (the non-associative scheme on real
# scenes, imperfect CAD scenes) that took 146 s and 62 s here, a third of the stage's test time,
# while the unit, validation and regression tests reach the same code on smaller models.
# The stiff cases run as one process, not one per case as ctest does: under ASan each of those
# processes costs over a second of start-up, which for the ~130 stiff cases would be most of the
# stage's time.
ctest --test-dir build-asan-ci --output-on-failure -j"$(nproc)" -LE "web|stiff|heavy" "$@"
if [ $# -eq 0 ] && [ -x build-asan-ci/tests/rbla_stiff_tests ]; then
  build-asan-ci/tests/rbla_stiff_tests --gtest_brief=1
fi
