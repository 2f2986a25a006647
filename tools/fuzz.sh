#!/usr/bin/env bash
# Fuzzes the model stage (JSON -> schema -> typed model -> geometry -> interface detection) with
# libFuzzer under ASan+UBSan: clang build in build-fuzz/, harness tests/fuzz/fuzz_model.cpp.
#   tools/fuzz.sh --smoke        about 60 s, for CI: stops at the first finding
#   tools/fuzz.sh --seconds N    a long run: one forked worker that carries on past findings
# Exits non-zero when anything was found. New inputs go to build-fuzz/corpus (the committed
# tests/fuzz/corpus is only read); findings go to build-fuzz/artifacts/. See docs/fuzzing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=()
case "${1:-}" in
  --smoke) seconds=60 ;;
  --seconds) seconds="${2:?--seconds needs a number}"
             # -fork=1: one worker process, restarted after a crash, timeout or OOM, so an hour's
             # run collects every finding instead of stopping at the first.
             mode=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1) ;;
  *) echo "usage: tools/fuzz.sh --smoke | --seconds N" >&2; exit 2 ;;
esac
# RelWithDebInfo: optimised enough to fuzz fast, with line numbers in sanitizer reports.
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DRBLA_FUZZ=ON >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz_model
mkdir -p build-fuzz/corpus build-fuzz/artifacts
# Findings are crash-, timeout-, oom- and leak- files; slow-unit- files are only a note.
findings() { find build-fuzz/artifacts -type f \( -name 'crash-*' -o -name 'timeout-*' -o -name 'oom-*' -o -name 'leak-*' \) | wc -l; }
before=$(findings)
# -max_len: the bundled samples are 1-45 kB; 64 kB leaves room to grow them without spending
#   most of the time on huge inputs. -timeout: the 34 kB wall samples load in 0.6 s under ASan;
#   30 s, not less, because the limit is wall-clock and a niced run on a busy machine (as the
#   long runs are) gets little CPU. -rss_limit_mb: a 64 kB input has no business with more than
#   1 GB (and the machine is shared).
status=0
build-fuzz/tests/fuzz/fuzz_model build-fuzz/corpus tests/fuzz/corpus tests/fuzz/regressions \
  -dict=tests/fuzz/model.dict -max_len=65536 -timeout=30 -rss_limit_mb=1024 \
  -max_total_time="$seconds" -artifact_prefix=build-fuzz/artifacts/ -print_final_stats=1 \
  "${mode[@]}" || status=$?
# libFuzzer's exit status misses what fork mode was told to ignore: count the files too.
after=$(findings)
if [ "$status" -ne 0 ] || [ "$after" -gt "$before" ]; then
  echo "fuzz: FINDINGS (exit $status, $((after - before)) new files in build-fuzz/artifacts/)" >&2
  exit 1
fi
echo "fuzz: no findings in ${seconds} s"
