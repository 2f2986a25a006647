#!/usr/bin/env bash
# Builds the test suite with AddressSanitizer + UndefinedBehaviorSanitizer (GCC, RBLA_SANITIZE)
# into build-asan-ci/ and runs it. Any sanitizer report fails its test: UB does not recover
# (-fno-sanitize-recover) and ASan stops at the first error. Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
# -O1 without -g: builds in about half the time of -O2 -g (docs/benchmark/measurements.md) and
# the tests run no slower; reports then name functions but not lines: rebuild with -g for those.
# -Wno-maybe-uninitialized: with -fsanitize=address GCC 12 warns inside libstdc++'s <regex>
# (std::function moved in _NFA::_M_insert_*; valijson's pattern checks); a false positive that
# the normal build does not show, and this build must stay warning-free too.
cmake -S . -B build-asan-ci -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRBLA_SANITIZE=ON \
      "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -DNDEBUG" -DCMAKE_CXX_FLAGS=-Wno-maybe-uninitialized >/dev/null
cmake --build build-asan-ci -j"$(nproc)"
# detect_stack_use_after_return stays off (ASan's default): it nearly doubles the CPU time of the
# stiff cases.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Excluded: web. It installs npm packages and drives headless Chromium for minutes to test the
# JavaScript viewer and .3dm exchange; the only C++ it reaches is `rbla solve` on the samples,
# which the regression and CLI tests already run here under the sanitizers.
# The stiff cases run as one process, not one per case as ctest does: under ASan each of those
# processes costs over a second of start-up, which for the ~130 stiff cases would be most of the
# stage's time.
ctest --test-dir build-asan-ci --output-on-failure -j"$(nproc)" -LE "web|stiff" "$@"
if [ $# -eq 0 ] && [ -x build-asan-ci/tests/rbla_stiff_tests ]; then
  build-asan-ci/tests/rbla_stiff_tests --gtest_brief=1
fi
