#!/usr/bin/env bash
# Runs every libFuzzer harness (fuzz/) for a while and prints, per harness,
# the executions, libFuzzer's coverage figures (cov: edges reached in the
# instrumented parser code, ft: features) and the corpus size. $JOBS
# harnesses (default 2) run at once.
#
#   scripts/fuzz.sh [--seconds S | --minutes M] [HARNESS...]
#
# Default: 10 minutes each, every harness (names as in fuzz/: imu_csv, tum,
# config_estimator, ...). The harnesses are built in the sanitizer folder
# (scripts/sanitize.sh --configure makes it when missing). New inputs go to
# build-asan/fuzz-work/<harness>/ (the committed seeds in fuzz/corpus/ are
# only read); a finding stops its harness, is saved to
# build-asan/fuzz-findings/<harness>/ and makes the script exit with 1.
set -euo pipefail
cd "$(dirname "$0")/.."

build=${VIO_SANITIZE_BUILD:-build-asan}
jobs=${JOBS:-2}
seconds=600
harnesses=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --minutes) seconds=$(( $2 * 60 )); shift 2 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 1 ;;
    *) harnesses+=("$1"); shift ;;
  esac
done
if [ ${#harnesses[@]} -eq 0 ]; then
  for dir in fuzz/corpus/*/; do harnesses+=("$(basename "$dir")"); done
fi

if [ -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" > /dev/null  # picks up harnesses added since
else
  bash scripts/sanitize.sh --configure
fi
targets=()
for h in "${harnesses[@]}"; do targets+=("${h}_fuzzer"); done
cmake --build "$build" -j"$jobs" --target "${targets[@]}"

symbolizer=$(command -v llvm-symbolizer-14 || command -v llvm-symbolizer || true)
export ASAN_SYMBOLIZER_PATH=$symbolizer
export ASAN_OPTIONS=detect_leaks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

# One harness, in the background: its log and exit status go to files, so
# $jobs harnesses run at once (each is single-threaded) and the table below
# still lists them in order.
run_harness() {
  local h=$1 dict=() status=0
  local work="$build/fuzz-work/$h" findings="$build/fuzz-findings/$h"
  mkdir -p "$work" "$findings"
  case "$h" in config_*|sensor_yaml) dict=(-dict=fuzz/dict/yaml.dict) ;; esac
  "$build/fuzz/${h}_fuzzer" "$work" "fuzz/corpus/$h" "${dict[@]}" \
    -max_total_time="$seconds" -max_len=16384 -timeout=20 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$findings/" \
    > "$build/fuzz-work/$h.log" 2>&1 || status=$?
  echo "$status" > "$build/fuzz-work/$h.status"
}

mkdir -p "$build/fuzz-work"
running=0
for h in "${harnesses[@]}"; do
  rm -f "$build/fuzz-work/$h.status"
  run_harness "$h" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n
    running=$((running - 1))
  fi
done
wait

passed=0
failed=0
printf '%-18s %10s %8s %8s %7s %s\n' harness runs cov ft corpus result
for h in "${harnesses[@]}"; do
  findings="$build/fuzz-findings/$h"
  log="$build/fuzz-work/$h.log"
  status=$(cat "$build/fuzz-work/$h.status" 2>/dev/null || echo missing)
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<< "$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<< "$last")
  corpus=$(sed -n 's/.* corp: \([0-9]*\).*/\1/p' <<< "$last")
  if [ "$status" = 0 ]; then
    result=ok
    passed=$((passed + 1))
  else
    result="FINDING (see $log and $findings/)"
    failed=$((failed + 1))
    grep -E 'ERROR|fuzz finding|runtime error|Test unit written' "$log" | head -5 >&2 || true
  fi
  printf '%-18s %10s %8s %8s %7s %s\n' "$h" "${runs:--}" "${cov:--}" \
    "${ft:--}" "${corpus:--}" "$result"
done
echo "fuzz: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
