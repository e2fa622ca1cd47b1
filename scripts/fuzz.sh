#!/usr/bin/env bash
# The firmware's hostile-input checks, built with clang's AddressSanitizer and UndefinedBehavior-
# Sanitizer in build/sanitize (firmware/CMakeLists.txt, UV_SANITIZE):
#   scripts/fuzz.sh --tests            every host test suite under the sanitizers (ctest)
#   scripts/fuzz.sh [SECONDS] [NAME…]  each libFuzzer harness in firmware/fuzz/ for SECONDS (20)
#                                      on its seeds and grown corpus; a broken invariant or a
#                                      sanitizer report fails
#   scripts/fuzz.sh --merge SECONDS    a longer run, then its finds are folded (libFuzzer -merge)
#                                      into the grown corpus and the seeds are picked anew from it
# npm test runs the first two; run the third by hand (e.g. 600 s each) and commit firmware/fuzz/seeds/.
#
# Two corpora a harness: its seeds, about 20 inputs committed in firmware/fuzz/seeds/NAME (picked by
# scripts/fuzz-seeds.py, a greedy cover of the grown corpus's features), and the grown corpus in
# $UV_FUZZ_CORPUS/NAME (build/fuzz-corpus by default), which keeps every run's finds on this machine
# and which the public CI keeps as a cache (.github/workflows/firmware.yml). A fresh clone starts
# from the seeds alone.
set -euo pipefail
cd "$(dirname "$0")/.."

build=build/sanitize
configure() {
  CC=clang CXX=clang++ cmake -S firmware -B "$build" -DUV_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
}
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

if [[ ${1:-} == --tests ]]; then
  configure
  suites=(protocol_tests nano_tests planner_tests mega_tests esp_tests)
  cmake --build "$build" -j"$(nproc)" --target "${suites[@]}" >/dev/null
  (cd "$build" && ctest --output-on-failure -R "^($(IFS='|'; echo "${suites[*]}"))\$")
  exit
fi

merge=0
if [[ ${1:-} == --merge ]]; then
  merge=1
  shift
fi
seconds=${1:-20}
shift || true
configure
cmake --build "$build" -j"$(nproc)" --target fuzzers >/dev/null
names=("$@")
if ((${#names[@]} == 0)); then
  for f in firmware/fuzz/*_fuzz.cpp; do names+=("$(basename "$f" _fuzz.cpp)"); done
fi

failed=0
for name in "${names[@]}"; do
  seeds=firmware/fuzz/seeds/$name  # only read
  grown=${UV_FUZZ_CORPUS:-build/fuzz-corpus}/$name
  work=$build/corpus/$name  # what this run finds
  rm -rf "$work"
  mkdir -p "$seeds" "$grown" "$work"
  log=$build/fuzz-$name.log
  if ! "$build/fuzz/${name}_fuzz" -max_total_time="$seconds" -print_final_stats=1 -timeout=10 -rss_limit_mb=2048 \
      -artifact_prefix="$build/crash-$name-" "$work" "$grown" "$seeds" >"$log" 2>&1; then
    echo "[fuzz] $name: FAILED; reproduce with $build/fuzz/${name}_fuzz $(ls -t "$build"/crash-"$name"-* 2>/dev/null | head -1)"
    grep -a -E 'invariant broken|runtime error|ERROR: (AddressSanitizer|libFuzzer)|SUMMARY' "$log" | head -5
    failed=1
    continue
  fi
  runs=$(awk '/stat::number_of_executed_units:/ {print $2}' "$log")
  rate=$(awk '/stat::average_exec_per_sec:/ {print $2}' "$log")
  last=$(grep -a -E '^#[0-9]+' "$log" | tail -1)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")
  corp=$(sed -n 's/.* corp: \([0-9]*\).*/\1/p' <<<"$last")
  echo "[fuzz] $name: $runs runs in $seconds s ($rate/s), coverage $cov edges, $ft features, corpus $corp"
  # What this run found joins the grown corpus (libFuzzer's merge keeps only inputs with new features).
  "$build/fuzz/${name}_fuzz" -merge=1 "$grown" "$work" >/dev/null 2>&1
  if ((merge)); then
    echo "[fuzz] $name: grown corpus now $(ls "$grown" | wc -l) files"
    python3 scripts/fuzz-seeds.py "$build/fuzz/${name}_fuzz" "$seeds" 20 "$grown" "$seeds"
  fi
done
exit $failed
