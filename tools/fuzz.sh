#!/usr/bin/env bash
# Fuzzes rbla with libFuzzer under ASan+UBSan (clang build in build-fuzz/). Three harnesses:
#   model     tests/fuzz/fuzz_model.cpp: JSON -> schema -> typed model -> geometry -> detection
#   analysis  tests/fuzz/fuzz_analysis.cpp: a model through the whole analysis, result, pictures
#   conic     tests/fuzz/fuzz_conic.cpp: CBF problems read and solved by the conic solver
#
#   tools/fuzz.sh --smoke [HARNESS...]          CI: 35 s per harness, stops at the first finding
#   tools/fuzz.sh --seconds N [HARNESS...]      a long run of N s per harness: one forked worker
#                                               that carries on past findings
#   --tree DIR (after the mode): fuzz with the harnesses already built in DIR instead of
#   building build-fuzz/; tools/sanitize.sh builds them in build-asan-ci/ with edge counters
#   only, which is what the CI smoke run uses.
# Without HARNESS, all three, one after the other. Exits non-zero when anything was found. New
# inputs go to TREE/corpus-HARNESS (the committed tests/fuzz/corpus* are only read); findings go
# to TREE/artifacts/HARNESS-*, TREE being build-fuzz unless --tree says otherwise. See
# docs/fuzzing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=()
case "${1:-}" in
  --smoke) seconds=35; shift ;;
  --seconds) seconds="${2:?--seconds needs a number}"; shift 2
             # -fork=1: one worker process, restarted after a crash, timeout or OOM, so an hour's
             # run collects every finding instead of stopping at the first.
             mode=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1) ;;
  *) echo "usage: tools/fuzz.sh --smoke | --seconds N  [--tree DIR] [model] [analysis] [conic]" >&2; exit 2 ;;
esac
tree=build-fuzz
prebuilt=0
if [ "${1:-}" = "--tree" ]; then
  tree="${2:?--tree needs a build folder}"; prebuilt=1; shift 2
fi
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(model analysis conic)
for h in "${harnesses[@]}"; do
  case "$h" in model|analysis|conic) ;; *) echo "fuzz: unknown harness '$h'" >&2; exit 2 ;; esac
done
# -O2 to fuzz fast; line tables only (not full -g): line numbers in sanitizer reports without
# the build cost of full debug information.
if [ "$prebuilt" -eq 0 ]; then
  cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DRBLA_FUZZ=ON "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG" >/dev/null
  cmake --build build-fuzz -j"$(nproc)" --target "${harnesses[@]/#/fuzz_}"
fi
for h in "${harnesses[@]}"; do
  [ -x "$tree/tests/fuzz/fuzz_$h" ] || { echo "fuzz: no harness $tree/tests/fuzz/fuzz_$h (configure with -DRBLA_FUZZ=ON)" >&2; exit 2; }
done
mkdir -p "$tree/artifacts"
# Findings are crash-, timeout-, oom- and leak- files; slow-unit- files are only a note.
findings() { find "$tree/artifacts" -type f \( -name '*crash-*' -o -name '*timeout-*' -o -name '*oom-*' -o -name '*leak-*' \) | wc -l; }
before=$(findings)
# -max_len: the bundled samples are 1-45 kB; 64 kB leaves room to grow them without spending
#   most of the time on huge inputs. -timeout: the 34 kB wall samples load in 0.6 s under ASan
#   and the analysis harness stops itself after 2 s of solving; 30 s, not less, because the
#   limit is wall-clock and a niced run on a busy machine (as the long runs are) gets little CPU.
#   -rss_limit_mb: a 64 kB input has no business with more than 1 GB (and the machine is shared).
status=0
for h in "${harnesses[@]}"; do
  case "$h" in
    model) inputs=(tests/fuzz/corpus tests/fuzz/regressions); dict=tests/fuzz/model.dict ;;
    analysis) inputs=(tests/fuzz/corpus_analysis tests/fuzz/regressions_analysis); dict=tests/fuzz/model.dict ;;
    conic) inputs=(tests/fuzz/corpus_conic tests/fuzz/regressions_conic); dict=tests/fuzz/cbf.dict ;;
  esac
  mkdir -p "$tree/corpus-$h"
  echo "fuzz: $h for $seconds s" >&2
  "$tree/tests/fuzz/fuzz_$h" "$tree/corpus-$h" "${inputs[@]}" \
    -dict="$dict" -max_len=65536 -timeout=30 -rss_limit_mb=1024 \
    -max_total_time="$seconds" -artifact_prefix="$tree/artifacts/$h-" -print_final_stats=1 \
    "${mode[@]}" || status=$?
  # Stop at the first harness with a finding in a smoke run; a long run carries on.
  if [ ${#mode[@]} -eq 0 ] && [ "$status" -ne 0 ]; then break; fi
done
# libFuzzer's exit status misses what fork mode was told to ignore: count the files too.
after=$(findings)
if [ "$status" -ne 0 ] || [ "$after" -gt "$before" ]; then
  echo "fuzz: FINDINGS (exit $status, $((after - before)) new files in $tree/artifacts/)" >&2
  exit 1
fi
echo "fuzz: no findings in ${seconds} s per harness (${harnesses[*]})"
